#pragma once
// The error-bounded residual layer: after a lossy stage (Tucker, quantized Tucker, PCA, ...) has
// reconstructed A_lossy, the residual R = A - A_lossy is stored quantized so that the final
// reconstruction A_lossy + R_hat is within a per-dof tolerance of A everywhere:
//     q(d, t, n) = round(R(d, t, n) / s_d),   R_hat = q s_d,   |R - R_hat| <= eps_d,
// with s_d = 2 eps_d (1 - 2^-20) (a hair under 2 eps_d, so the bound survives double rounding) and
// eps_d the requested tolerance rounded down to float32 (stored). When the lossy part is good most q
// are 0: the codes are zigzag-mapped, written as LEB128 varints (one byte for |q| <= 63) and deflated.
// A residual whose codes are all 0 stores no payload at all (0 bytes; the header says so).
//
// Usage: R must be computed against what the decoder of the lossy part really reconstructs (e.g.
// after float32 rounding or quantization of its parameters), and the final values are
// A_lossy + R_hat; the addition itself adds only double rounding (~1e-16 |A|).
#include <cstdint>

#include "mocapdb/compression/codecs/encoded_stream.hpp"
#include "mocapdb/core/types.hpp"
#include "mocapdb/core/tensor3.hpp"

namespace mocapdb::compression::codecs {

/// Order in which the D T N codes are written before deflating.
enum class ResidualOrder : std::uint8_t {
    DofMajor = 0,  ///< for each dof, for each sample, every frame (long zero runs per dof)
    Storage = 1    ///< the tensor's column-major storage order (dof fastest)
};

struct ResidualOptions {
    ResidualOrder order = ResidualOrder::DofMajor;
    int deflate_level = 9;  ///< 0..9 or -1
};

/// An encoded residual and what the decoder will reconstruct from it.
struct ResidualEncoding {
    EncodedStream stream;      ///< "residual stream", magic "MCRL"
    Tensor3 decoded;           ///< R_hat, D by T by N (equal to decode_residual(stream))
    VecX tolerance;            ///< the stored eps_d (float32 values, <= the requested ones), D entries
    Eigen::Index nonzero = 0;  ///< codes that are not 0
    std::int64_t max_abs_code = 0;
    double max_abs_error = 0;  ///< measured max |R - R_hat| (<= max tolerance)
};

/// Encodes r (D by T by N, non-empty, finite) with per-dof tolerances eps: D entries, or 1 entry
/// used for every dof; each finite and >= 1.2e-38 (the smallest normal float32). Payload: the stored
/// tolerances as float32 (4 bytes, or 4 D when they differ), a varint with the length of the varint
/// code stream, and that stream deflated; nothing when every code is 0.
/// Throws InvalidArgument on bad shapes or values, or when some |R / (2 eps_d)| exceeds 2^31.
ResidualEncoding encode_residual(const Tensor3& r, const Eigen::Ref<const VecX>& eps,
                                 const ResidualOptions& options = {});
/// Same with one tolerance for every dof.
ResidualEncoding encode_residual(const Tensor3& r, double eps, const ResidualOptions& options = {});

/// R_hat (D by T by N) from a residual stream. Throws ParseError ("residual stream") on a bad stream.
Tensor3 decode_residual(const std::uint8_t* data, std::size_t size);
Tensor3 decode_residual(const Bytes& stream);

}  // namespace mocapdb::compression::codecs
