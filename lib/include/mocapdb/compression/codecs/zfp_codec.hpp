#pragma once
// The zfp baseline: zfp's fixed-accuracy mode (Lindstrom 2014, Debian libzfp-dev 1.0) on the
// D by T by N tensor as a 3-D array of doubles (x = dof, fastest; y = time; z = sample), in 4x4x4
// blocks. Doubles, not floats: the tensor is double, and converting to float32 would add up to
// 2^-24 relative error on top of zfp's own, breaking the bound for small tolerances; the compressed
// size in fixed-accuracy mode depends on the tolerance, not on the input type.
//
// Details: docs/headers/compression.md (mocapdb/compression/codecs/zfp_codec.hpp).
#include <cstdint>

#include "mocapdb/compression/codecs/encoded_stream.hpp"
#include "mocapdb/core/types.hpp"
#include "mocapdb/core/tensor3.hpp"

namespace mocapdb::compression::codecs {

/// Fixed-accuracy zfp stream of a ("zfp stream", magic "MCZF"). a: D by T by N, non-empty, finite.
/// tolerance: finite, > 0. Payload: the zfp bit stream (the tolerance, as a double, is in the header;
/// the decoder needs only zfp's minimum exponent from it). Throws InvalidArgument on bad arguments.
EncodedStream zfp_encode(const Tensor3& a, double tolerance);

/// Per-dof tolerances: eps has D entries, each finite and >= 1e-30; stored as float32 rounded down.
/// Payload: 4 D bytes of tolerances, then the zfp stream. Throws InvalidArgument on bad arguments.
EncodedStream zfp_encode(const Tensor3& a, const Eigen::Ref<const VecX>& eps);

/// Decodes either form: D by T by N, all finite. Throws ParseError ("zfp stream") on a bad stream.
/// A corrupt or truncated zfp payload is decoded from a zero-padded copy (zfp has no checks of its
/// own), so it never reads outside the buffer; the CRC-32 in the header catches it first.
Tensor3 zfp_decode(const std::uint8_t* data, std::size_t size);
Tensor3 zfp_decode(const Bytes& stream);

}  // namespace mocapdb::compression::codecs
