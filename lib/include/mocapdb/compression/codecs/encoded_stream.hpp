#pragma once
// The byte streams the codec module produces, and how their size is accounted.
//
// Every encoder returns a self-describing stream: a small container header (a 4-byte magic naming the
// codec, a format version, the tensor's dimensions and codec parameters that are metadata of the set,
// and a CRC-32 of the payload) followed by the payload: everything that must be stored to reconstruct
// the values once the dimensions are known. Honest byte accounting counts payload_bytes(); the header
// is container overhead, reported separately (header_bytes), like the HDF5 overhead.
//
// Decoders refuse a stream that is truncated, has a wrong magic or version, a checksum mismatch, or
// sizes that do not add up, with a ParseError whose file() is "<name> stream" (e.g. "zfp stream")
// and whose message names the byte offset and what was expected; they never read outside the
// given buffer and never return non-finite values.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace mocapdb::compression::codecs {

using Bytes = std::vector<std::uint8_t>;

/// A finished stream: bytes = header (header_bytes) then payload.
struct EncodedStream {
    Bytes bytes;                   ///< the whole stream, as it would be written to a file
    std::size_t header_bytes = 0;  ///< container overhead: magic, version, dims, parameters, CRC-32

    /// Bytes that must be stored to reconstruct (the figure compression ratios use).
    std::size_t payload_bytes() const { return bytes.size() - header_bytes; }
    std::size_t total_bytes() const { return bytes.size(); }
};

}  // namespace mocapdb::compression::codecs
