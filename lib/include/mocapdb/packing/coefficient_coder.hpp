#pragma once
// Entropy coding of one window's quantized core coefficients with a context model.
//
// Details: docs/headers/packing.md (mocapdb/packing/coefficient_coder.hpp).
#include <array>
#include <cstdint>
#include <vector>

#include "mocapdb/packing/range_coder.hpp"

namespace mocapdb::packing {

constexpr int kClasses = 28;
constexpr int kClassBias = 10;
constexpr int kGammaBits = 31;  ///< longest Elias-gamma prefix (magnitudes below 2^31)

/// Every adaptive context of the model, in one flat array (serialized as such).
struct ContextSet {
    static constexpr int kLengthContexts = 2 * kGammaBits;
    static constexpr int kNeighbourhoods = 5;
    // nonzero x (previous nonzero, neighbourhood), greater-than-one x neighbourhood, gamma prefix
    static constexpr int kPerClass = 2 * kNeighbourhoods + kNeighbourhoods + 2 * kGammaBits;
    static constexpr int kCount = kLengthContexts + kClasses * kPerClass;
    std::array<BitContext, kCount> p;

    ContextSet() { p.fill(kProbabilityHalf); }
    BitContext* length() { return p.data(); }
    BitContext* nonzero(int cls, int previous_nonzero, int n) {
        return &p[kLengthContexts + cls * kPerClass + previous_nonzero * kNeighbourhoods + n];
    }
    BitContext* greater_one(int cls, int n) { return &p[kLengthContexts + cls * kPerClass + 2 * kNeighbourhoods + n]; }
    BitContext* gamma(int cls) { return &p[kLengthContexts + cls * kPerClass + 3 * kNeighbourhoods]; }
    BitContext* gamma_msb(int cls) { return &p[kLengthContexts + cls * kPerClass + 3 * kNeighbourhoods + kGammaBits]; }
};

/// Counts of 0s and 1s seen by each context; turned into initial probabilities for a group.
struct ContextCounts {
    std::array<std::array<std::uint64_t, 2>, ContextSet::kCount> n{};
    /// Probabilities (of a 0) estimated from the counts, with 8 bits of precision (multiples of
    /// 1/256 in 1/256 ... 255/256, never 1/2); contexts never used stay at exactly 1/2.
    ContextSet to_contexts() const;
};

/// 2·log2(sigma) of every scan position (−1e30 where sigma is 0): what position_classes needs.
std::vector<double> class_levels(const std::vector<float>& sigma);
/// Class of every scan position for a window quantized with `step` (`levels` from class_levels).
void position_classes(const std::vector<double>& levels, double step, std::vector<std::uint8_t>& out_classes);

/// Where each scan position sits in the coefficient grid (rows by columns, column-major index), for
/// the neighbourhood contexts. Every position's upper and left neighbours must come earlier in scan.
struct ScanGrid {
    const std::vector<std::uint32_t>* scan = nullptr;  ///< scan position -> grid index
    int rows = 1;
};

/// A scan in grid order (identity) of a rows-by-columns grid (the caller keeps the vector alive).
std::vector<std::uint32_t> identity_scan(std::size_t size);

/// The coded coefficients `q` (scan order; may end early, missing entries are 0) of one window.
/// `contexts` is copied: each window starts from the same initial probabilities.
std::vector<std::uint8_t> encode_coefficients(const std::vector<std::int32_t>& q,
                                              const std::vector<std::uint8_t>& classes, const ScanGrid& grid,
                                              ContextSet contexts);

/// Adds the binary decisions that coding `q` would make, per context (static statistics).
void count_coefficients(const std::vector<std::int32_t>& q, const std::vector<std::uint8_t>& classes,
                        const ScanGrid& grid, ContextCounts& counts);

/// Decodes one window's coefficients (scan order) into out_q (resized to classes.size()).
void decode_coefficients(const std::uint8_t* data, std::size_t size, const std::vector<std::uint8_t>& classes,
                         const ScanGrid& grid, ContextSet contexts, std::vector<std::int32_t>& out_q);
/// The same without allocating: `count` classes and out_q entries; `contexts` is the caller's copy
/// of the initial probabilities and is adapted in place (spent afterwards); `level` is scratch of
/// `count` bytes. Returns the coded length L (<= count): out_q is zero from L on, so a caller may
/// read only its first L entries. With `nonzero` (room for `count` entries) and `nonzero_count`:
/// the scan positions of the nonzero coefficients, ascending, and their number.
std::size_t decode_coefficients(const std::uint8_t* data, std::size_t size, const std::uint8_t* classes,
                                std::size_t count, const ScanGrid& grid, ContextSet& contexts, std::int32_t* out_q,
                                std::uint8_t* level, std::uint32_t* nonzero = nullptr,
                                std::size_t* nonzero_count = nullptr);

}  // namespace mocapdb::packing
