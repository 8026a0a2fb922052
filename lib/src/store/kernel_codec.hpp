#pragma once
// A model's precomputed coefficient kernel as the group /sets/{set}/model/kernel (schemas/format-v3.md
// §8.1; synthesis/kernel_fit.hpp says what it is and when it is used).
#include <string>

#include "h5/file.hpp"
#include "mocapdb/synthesis/kernel_fit.hpp"

namespace mocapdb::store {

/// Writes /sets/{set}/model/kernel (which must not exist), with fit_status and residual_variance when
/// the fit has an assessed_status. The caller has checked that the model
/// exists and that the fit is valid (check_kernel_fit).
void write_kernel_fit(h5::File& file, const std::string& set, const synthesis::KernelFit& fit);

/// Reads /sets/{set}/model/kernel (which must exist). StoreError naming the offending object for a
/// malformed key, an unknown family, an invalid variogram (non-finite, negative, range <= 0, exponent
/// outside (0, 2], nugget + sill = 0), and for the optional fit_status / residual_variance pair: one
/// without the other, an unknown status, a negative or non-finite variance. Without them the result's
/// assessed_status is empty (a kernel written before they were stored). The LOO MSE per exponent is not
/// stored (the result's is empty).
synthesis::KernelFit read_kernel_fit(const h5::File& file, const std::string& set);

/// InvalidArgument (prefixed with `who`) unless the fit could be stored: key != 0, a valid variogram
/// with nugget + sill > 0, and with an assessed_status a finite residual variance >= 0.
void check_kernel_fit(const synthesis::KernelFit& fit, const std::string& who);

}  // namespace mocapdb::store
