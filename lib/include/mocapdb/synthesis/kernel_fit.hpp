#pragma once
// The coefficient kernel's variogram of a compressed synthesis model, fitted once and stored.
//
// Thread safety: plain data and pure functions.
//
// Details: docs/headers/synthesis.md (mocapdb/synthesis/kernel_fit.hpp).
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>

#include "mocapdb/core/types.hpp"
#include "mocapdb/kriging/kriging.hpp"
#include "mocapdb/kriging/variogram_fit.hpp"
#include "mocapdb/kriging/variogram_model.hpp"
#include "mocapdb/synthesis/edge_warning.hpp"
#include "mocapdb/synthesis/predictor_choice.hpp"

namespace mocapdb {
struct AlignedSet;
struct MotionSet;
namespace compression {
struct SetModel;
}
}  // namespace mocapdb

namespace mocapdb::synthesis {

struct SynthesisOptions;

/// The chosen variogram of a coefficient kernel, with the key of the inputs it was chosen for.
struct KernelFit {
    std::uint64_t key = 0;              ///< kernel_key of the inputs (0: none)
    kriging::VariogramModel variogram;  ///< the model Kriging::build is given (valid, total sill > 0)
    /// LOO MSE per grid exponent: the smallest over the candidate shapes tried with that exponent
    /// (fit_coefficient_kernel); empty when p was given, and in a fit read from a database (not stored).
    Eigen::VectorXd exponent_loo_mse;
    /// Status of the variogram fit (not stored: Ok when read, see assessed_status; `compress` reports it).
    kriging::FitStatus status = kriging::FitStatus::Ok;
    /// The status a model built from this fit reports (assess_coefficient_kernel of the variogram on the
    /// fit's inputs; it can differ from `status` at the bounds' tolerances): set by fit_kernel and stored
    /// with the kernel (attribute fit_status), so that a model built from a stored kernel of the same key
    /// need not recompute it (the 645 x R1 R2 core slices and their trend residuals). Empty in a fit read
    /// from a kernel stored without it (written before): the model then recomputes it.
    std::optional<kriging::FitStatus> assessed_status;
    /// Variance of the linear-trend residuals the variogram was fitted to (what assess_coefficient_kernel
    /// bounds the sill with); stored with assessed_status, 0 when read from a kernel stored without it.
    double residual_variance = 0.0;
    /// Leave-one-out check of the prediction variance (not stored; none when read or degenerate): the mean
    /// over samples of z_i^2 = |s_i - s_-i|^2 / V_i (the squared residual summed over the values, since the
    /// sill is the sum of their variances). Near 1 when the variance is calibrated.
    std::optional<double> loo_mean_z2;
    /// Samples the variogram was chosen on (not stored; 0 when read): N, or max_fit_samples of them.
    std::size_t fit_samples = 0;
    /// The coefficient kernel's kriging system factorized (kriging::Kriging::covariance_inverse of the
    /// model's normalized parameters, this variogram and options.kriging): set by fit_kernel for sets of
    /// up to options.max_stored_system_samples samples and stored with the kernel, so that a model of the
    /// same key builds its kriging in O(N^2) instead of O(N^3) (3 000 samples load in
    /// seconds). Null otherwise, and when read from a kernel stored without it.
    std::shared_ptr<const kriging::CovarianceInverse> system;
    /// The predictor cross-validation chose for these inputs (predictor_choice.hpp): set by fit_kernel,
    /// stored with the kernel; empty when read from a kernel stored without it (kriging is then used).
    std::optional<PredictorChoice> predictor;
    /// The rho below which a synthesis is flagged, calibrated on the set (edge_warning.hpp;
    /// workflow/edge_calibration.hpp): set by `compress` after the fit, stored with the kernel; empty for
    /// sets whose parameters are not measured back and in kernels stored without it (the fixed threshold
    /// workflow::kLowReliability then applies).
    std::optional<EdgeWarning> edge_warning;
};

/// Message for a fit status that is not Ok (what the CLI prints as a warning), "" for Ok.
std::string fit_status_warning(const KernelFit& fit);

/// The digest of a compressed model's kernel inputs (see the header comment), never 0. Let
/// mix(h, x) = ((h XOR x) * 0x100000001b3 mod 2^64) XOR (that >> 29) over 64-bit words x; starting
/// from h = 0xcbf29ce484222325, fold: the bytes of kernel_options_text(options) (one word per byte),
/// N, P, R1, R2, R3, then the IEEE-754 bit patterns of set.parameters (row after row, the file's
/// (N, P) C order), of model.tucker.U[2] (row after row, the file's (N, R3) sample_basis) and of the
/// core (the library's column-major order, the file's (R3, R2, R1) core), then, for a set with periodic
/// parameters, the bit patterns of set.parameter_periods, then, for N > options.max_fit_samples (a subset
/// fit), that number. Cost: one pass over the core.
std::uint64_t kernel_key(const compression::SetModel& model, const MotionSet& set, const SynthesisOptions& options);

/// The options that shape the coefficient kernel as text (exponent, scaling, variogram, fit and
/// kriging options; %.17g for numbers); part of the key.
std::string kernel_options_text(const SynthesisOptions& options);

/// Rows G x_3 u_i of the model (flattened core slices, N by R1 R2): their Euclidean distances are the
/// core-slice distances ||G x_3 (u_i - u_j)||_F the coefficient kernel's variogram is estimated on.
/// The model must pass compression::check.
MatX core_slice_values(const compression::SetModel& model);

/// The coefficient kernel's variogram from the normalized control parameters xc (N by P) and the
/// samples' values (N by S, finite), fitted as gstat's variogram(z ~ x + y): the
/// experimental variogram of the residuals of the linear trend (OLS; the raw values with
/// TrendKind::None), range <= options.max_range_factor * the largest lag, nugget + sill <=
/// options.max_sill_factor * the residual variance, a nugget >= options.gaussian_nugget_fraction * that
/// variance for p = 2; p = options.exponent or the leave-one-out choice over options.exponent_grid; a
/// placeholder model (status Degenerate) for samples without variation. Key left 0.
/// Shape (options.shape_selection = LeaveOneOut, the default): the candidates are the least-squares fit
/// of every exponent, then at the best exponent the grid options.range_fractions x options.nugget_shares
/// (range = fraction * the range bound, nugget = share * (nugget + sill)), then, if a grid shape won, that
/// shape at the other exponents; the one with the smallest closed-form leave-one-out MSE of the values
/// wins, so a pure-nugget fit (the trend alone) stays only when
/// no correlated shape predicts the left-out samples better. A grid shape's nugget and sill are then
/// scaled so that the leave-one-out mean z^2 is 1 (within the sill bound); the weights and rho do not
/// depend on that scale. At most 2 |exponent_grid| + |range_fractions| |nugget_shares| kriging systems,
/// O(N^3) each.
/// N > options.max_fit_samples: all of the above on options.max_fit_samples rows evenly spread over
/// the N (rows round(i (N - 1) / (m - 1))), so the cost stays bounded; KernelFit::fit_samples says so.
/// options.fit_progress is told of every candidate scored.
/// InvalidArgument (prefixed with `where`) for an exponent outside [0, 2], an empty grid, a range fraction
/// outside (0, 1], a nugget share outside [0, 1) or max_fit_samples < 2.
KernelFit fit_coefficient_kernel(const Eigen::Ref<const MatX>& xc, const Eigen::Ref<const MatX>& sample_values,
                                 const SynthesisOptions& options, const char* where);

/// The status fit_coefficient_kernel would report for `variogram` on these inputs, recomputed from the
/// bounds (largest lag, residual variance) without refitting: a stored kernel's assessed_status (fit_kernel),
/// or at load for one stored without it. Cost: the trend residuals and the control-space distances.
kriging::FitStatus assess_coefficient_kernel(const Eigen::Ref<const MatX>& xc,
                                             const Eigen::Ref<const MatX>& sample_values,
                                             const kriging::VariogramModel& variogram, const SynthesisOptions& options);

/// What `compress` stores: the fit MotionModel(model, aligned, set, ..., options) would make, with its
/// key and assessed_status (what that model reports) and, up to options.max_stored_system_samples
/// samples, its factorized system, without building the rest of the model. InvalidArgument when the model does not describe
/// `aligned` or the set has fewer than 2 samples.
KernelFit fit_kernel(const compression::SetModel& model, const AlignedSet& aligned, const MotionSet& set,
                     const SynthesisOptions& options);

}  // namespace mocapdb::synthesis
