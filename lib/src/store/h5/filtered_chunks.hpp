#pragma once
// Internal to the store's HDF5 layer: a chunk's bytes as HDF5's filter pipeline (shuffle, deflate,
// fletcher32) stores them, computed outside the library so that several chunks are compressed at once.
// HDF5 runs its filters on the calling thread, one chunk at a time (#16: 9-11 s to store the 383 MB
// model of 11 070 windows, most of it deflate). What this produces is what H5Dwrite stores for the
// same chunk (tests/store compare the raw chunks), so h5py and every HDF5 reader read it through the
// standard filters.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace mocapdb::store::h5 {

/// Fletcher-32 as HDF5's fletcher32 filter computes it: sums of 16-bit words taken most significant
/// byte first (a last odd byte is the high byte of a word), folded to 16 bits every 360 words.
std::uint32_t fletcher32(const std::uint8_t* data, std::size_t bytes);

/// The stored form of one chunk (`bytes` bytes, a whole number of `element_size`-byte elements):
/// byte-shuffled when `shuffle` (byte k of every element together, as H5Pset_shuffle), deflated at
/// `level` in zlib format (as H5Pset_deflate), then the fletcher32 of the result appended in
/// little-endian order (as H5Pset_fletcher32). Empty when zlib fails (the caller reports it).
/// Thread-safe.
std::vector<std::uint8_t> encode_filtered_chunk(const std::uint8_t* data, std::size_t bytes, std::size_t element_size,
                                                bool shuffle, int level);

}  // namespace mocapdb::store::h5
