#pragma once
// Lossless deflate (zlib) of byte buffers, and the "lossless float32" baseline: a D by T by N tensor
// rounded to float32 and deflated (optionally after a byte shuffle, as HDF5's shuffle filter does).
#include <cstddef>
#include <cstdint>
#include <string>

#include "mocapdb/compression/codecs/encoded_stream.hpp"
#include "mocapdb/core/tensor3.hpp"

namespace mocapdb::compression::codecs {

/// zlib stream (RFC 1950: deflate with a 2-byte header and an Adler-32 trailer) of size bytes at
/// data (data may be null when size is 0). level: 0 (store) to 9 (best), or -1 for zlib's default.
/// Throws InvalidArgument on a bad level or a buffer larger than zlib can take in one call (4 GiB).
Bytes deflate_bytes(const std::uint8_t* data, std::size_t size, int level = 9);
Bytes deflate_bytes(const Bytes& data, int level = 9);

/// Inflates a zlib stream that must decode to exactly expected_size bytes. source names the stream
/// in errors. Throws ParseError (file() == source) when the stream is corrupt, truncated, decodes to
/// a different size, or has bytes after its end.
Bytes inflate_bytes(const std::uint8_t* data, std::size_t size, std::size_t expected_size,
                    const std::string& source = "zlib stream");

struct Float32DeflateOptions {
    /// Byte shuffle before deflating: the N float32 values are written as four planes (all first
    /// bytes, then all second bytes, ...), which lets deflate find the repeated sign/exponent bytes.
    bool shuffle = true;
    int level = 9;  ///< zlib level, 0..9 or -1
};

/// The lossless float32 baseline. a: D by T by N, non-empty, every element finite and within float
/// range. The payload is the zlib stream of the float32 image (column-major, little-endian); the
/// header holds the magic "MCDF", version, shuffle flag, dims and CRC-32 (container overhead).
/// Throws InvalidArgument on an empty tensor or a value that is not finite in float32.
EncodedStream encode_float32_deflate(const Tensor3& a, const Float32DeflateOptions& options = {});

/// Decodes encode_float32_deflate: D by T by N, every element exactly the float32 value that was
/// encoded (widened to double). Throws ParseError ("float32-deflate stream") on a bad stream.
Tensor3 decode_float32_deflate(const std::uint8_t* data, std::size_t size);
Tensor3 decode_float32_deflate(const Bytes& stream);

/// The float32 image of a: every element rounded to float32 and widened back (what the lossless
/// float32 baseline reconstructs). Same shape as a.
Tensor3 round_to_float32(const Tensor3& a);

}  // namespace mocapdb::compression::codecs
