#pragma once
// Uniform scalar quantization of matrices and of Tucker models (core + three bases) to b bits with
// one offset and one step per column, and its compact serialization.
//
// Details: docs/headers/compression.md (mocapdb/compression/codecs/quantize.hpp).
#include <array>
#include <cstdint>
#include <vector>

#include "mocapdb/compression/codecs/encoded_stream.hpp"
#include "mocapdb/core/types.hpp"
#include "mocapdb/tensor/tucker.hpp"

namespace mocapdb::compression::codecs {

/// A matrix quantized per column. Plain data; build it with quantize_columns().
struct QuantizedColumns {
    int bits = 0;  ///< 1..16
    Eigen::Index rows = 0;
    Eigen::Index cols = 0;
    std::vector<float> offset;         ///< cols entries
    std::vector<float> step;           ///< cols entries, >= 0
    std::vector<std::uint16_t> codes;  ///< rows * cols, column-major, each < 2^bits

    /// Upper bound on |x - x_hat| over column c: step/2, or 2^-24 |offset| for a constant column
    /// (step 0). 0 <= c < cols.
    double error_bound(Eigen::Index c) const;
    /// max over the columns of error_bound(c) (0 for an empty matrix).
    double max_error_bound() const;
};

/// Quantizes m (rows by cols, every element finite) per column to bits (1..16) bits.
/// Throws InvalidArgument on a bad bit count or a non-finite element.
QuantizedColumns quantize_columns(const Eigen::Ref<const MatX>& m, int bits);

/// x_hat: rows by cols. Throws InvalidArgument when q's sizes are inconsistent.
MatX dequantize(const QuantizedColumns& q);

enum class Packing : std::uint8_t {
    BitPacked = 0,  ///< b-bit codes packed back to back
    Deflated = 1    ///< byte-plane codes and parameters in one zlib stream
};

/// One quantized matrix as a stream ("quantized-matrix stream", magic "MCQM"). Payload: 8 bytes per
/// column (offset, step) plus the codes; the header holds bits, rows, cols and packing.
/// deflate_level: 0..9 or -1 (used by Deflated only). Throws InvalidArgument when q is inconsistent.
EncodedStream encode_quantized(const QuantizedColumns& q, Packing packing, int deflate_level = 9);

/// Decodes encode_quantized. Throws ParseError ("quantized-matrix stream") on a bad stream.
QuantizedColumns decode_quantized(const std::uint8_t* data, std::size_t size);

/// Grouping of the core's values that share one offset and step (see the file comment).
enum class CoreGrouping : std::uint8_t {
    FrontalSlice = 0,  ///< R3 groups G(:, :, k)
    Mode0Fibre = 1,    ///< R2 R3 groups G(:, j, k)
    Whole = 2          ///< one group
};

struct QuantizeTuckerOptions {
    int core_bits = 12;   ///< 1..16
    int basis_bits = 12;  ///< 1..16, for all three bases
    CoreGrouping core_grouping = CoreGrouping::FrontalSlice;
    int deflate_level = 9;  ///< 0..9 or -1
};

/// A Tucker model after quantization, with both serializations.
struct QuantizedTucker {
    /// What a decoder reconstructs: dequantized core and bases, the original ranks and method. Its
    /// fit, data_norm, error_bound, iterations and fit_history are left at their defaults (they need
    /// the data): measure the error of model.reconstruct() against the tensor.
    tensor::TuckerModel model;
    EncodedStream packed;    ///< Packing::BitPacked ("quantized-Tucker stream", magic "MCQT")
    EncodedStream deflated;  ///< Packing::Deflated
    /// Bound on |x - x_hat| per part: core, U[0], U[1], U[2] (max over their groups).
    std::array<double, 4> error_bound{0, 0, 0, 0};
    /// Measured max |x - x_hat| per part (same order).
    std::array<double, 4> max_abs_error{0, 0, 0, 0};

    std::size_t packed_bytes() const { return packed.payload_bytes(); }
    std::size_t deflated_bytes() const { return deflated.payload_bytes(); }
    /// min(packed_bytes, deflated_bytes): what storing the better of the two costs.
    std::size_t best_bytes() const;
};

/// Quantizes a model's core and bases. model: core R1 by R2 by R3 and bases U[n] (I_n by R_n) that
/// agree with model.ranks, every value finite. Throws InvalidArgument otherwise or on bad options.
QuantizedTucker quantize_tucker(const tensor::TuckerModel& model, const QuantizeTuckerOptions& options = {});

/// Decodes either serialization of quantize_tucker to the same model as QuantizedTucker::model.
/// Throws ParseError ("quantized-Tucker stream") on a bad stream.
tensor::TuckerModel decode_quantized_tucker(const std::uint8_t* data, std::size_t size);
tensor::TuckerModel decode_quantized_tucker(const Bytes& stream);

/// Size in bytes of the payload quantize_tucker(...).packed would have, without encoding:
/// 8 (groups of the core + R1 + R2 + R3) + the packed codes of each part, rounded up to bytes.
std::size_t packed_tucker_bytes(const tensor::Dims3& dims, const tensor::Ranks& ranks,
                                const QuantizeTuckerOptions& options = {});

}  // namespace mocapdb::compression::codecs
