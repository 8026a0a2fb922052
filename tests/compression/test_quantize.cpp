#include <catch2/catch.hpp>

#include "codec_fixtures.hpp"
#include "mocapdb/compression/codecs/quantize.hpp"
#include "mocapdb/tensor/hosvd.hpp"

using namespace mocapdb;
using namespace mocapdb::compression::codecs;

namespace {
MatX random_matrix(Eigen::Index r, Eigen::Index c, unsigned seed, double scale) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> nd(0.0, scale);
    MatX m(r, c);
    for (Eigen::Index i = 0; i < m.size(); ++i) m.data()[i] = nd(rng) + (i % 3 == 0 ? 5.0 * scale : 0.0);
    return m;
}
}  // namespace

TEST_CASE("column quantization meets its error bound at every bit count", "[codec][quantize]") {
    const MatX m = random_matrix(57, 6, 1, 3.0);
    for (int bits = 1; bits <= 16; ++bits) {
        const QuantizedColumns q = quantize_columns(m, bits);
        const MatX back = dequantize(q);
        for (Eigen::Index c = 0; c < m.cols(); ++c) {
            const double lo = m.col(c).minCoeff(), hi = m.col(c).maxCoeff();
            const double err = (back.col(c) - m.col(c)).cwiseAbs().maxCoeff();
            INFO("bits " << bits << " column " << c << " error " << err << " step " << q.step[c]);
            CHECK(err <= q.error_bound(c) * (1 + 1e-12));
            // The brief's bound range / 2^b, up to the float32 rounding of the offset and step.
            CHECK(q.error_bound(c) <= (hi - lo) / std::ldexp(1.0, bits) * (1 + 1e-6) + std::ldexp(std::abs(lo), -23));
        }
        for (std::uint16_t code : q.codes) REQUIRE(code < (1u << bits));
    }
    // More bits, smaller error.
    CHECK(quantize_columns(m, 12).max_error_bound() < quantize_columns(m, 8).max_error_bound() / 15);
}

TEST_CASE("column quantization edge cases and bad arguments", "[codec][quantize]") {
    MatX m(4, 2);
    m << 1.1, 0, 1.1, -1e-30, 1.1, 2, 1.1, 3;  // column 0 constant
    const QuantizedColumns q = quantize_columns(m, 8);
    CHECK(q.step[0] < 1e-8f);  // the float32 rounding of 1.1, spread over the codes
    CHECK((dequantize(q).col(0).array() - 1.1).abs().maxCoeff() <= q.error_bound(0));
    CHECK(dequantize(quantize_columns(MatX(0, 3), 8)).size() == 0);
    const QuantizedColumns exact = quantize_columns(MatX::Constant(3, 1, 0.5), 8);  // float32-exact constant
    CHECK(exact.step[0] == 0.0f);
    CHECK(dequantize(exact)(2, 0) == 0.5);
    CHECK_THROWS_AS(quantize_columns(m, 0), InvalidArgument);
    CHECK_THROWS_AS(quantize_columns(m, 17), InvalidArgument);
    m(2, 1) = std::numeric_limits<double>::infinity();
    CHECK_THROWS_AS(quantize_columns(m, 8), InvalidArgument);
    QuantizedColumns broken = q;
    broken.codes.pop_back();
    CHECK_THROWS_AS(dequantize(broken), InvalidArgument);
    CHECK_THROWS_AS(encode_quantized(broken, Packing::BitPacked), InvalidArgument);
}

TEST_CASE("quantized matrix streams round-trip with exact byte counts", "[codec][quantize]") {
    const MatX m = random_matrix(90, 7, 2, 0.1);
    for (int bits : {3, 8, 11, 16}) {
        const QuantizedColumns q = quantize_columns(m, bits);
        for (Packing packing : {Packing::BitPacked, Packing::Deflated}) {
            const EncodedStream s = encode_quantized(q, packing);
            const QuantizedColumns back = decode_quantized(s.bytes.data(), s.bytes.size());
            CHECK(back.bits == bits);
            CHECK(back.codes == q.codes);
            CHECK(back.offset == q.offset);
            CHECK(back.step == q.step);
            if (packing == Packing::BitPacked)
                CHECK(s.payload_bytes() == 8 * 7 + (90 * 7 * static_cast<std::size_t>(bits) + 7) / 8);
        }
    }
    const EncodedStream good = encode_quantized(quantize_columns(m, 11), Packing::BitPacked);
    CHECK(test::mutate_and_decode(good, [](const Bytes& s) { dequantize(decode_quantized(s.data(), s.size())); }, 3) > 0);
    const EncodedStream good_z = encode_quantized(quantize_columns(m, 11), Packing::Deflated);
    CHECK(test::mutate_and_decode(good_z, [](const Bytes& s) { dequantize(decode_quantized(s.data(), s.size())); }, 4) > 0);
}

TEST_CASE("quantized Tucker model: both serializations decode to the same model within the bounds", "[codec][quantize]") {
    // A smooth tensor and its truncated HOSVD.
    const Tensor3 a = test::smooth_tensor3(40, 60, 15, 5);
    const tensor::TuckerModel model = tensor::hosvd(a, {12, 8, 6});
    const double truncation = tensor::absolute_error(a, model);
    double previous_error = 1e300;
    for (int bits : {6, 8, 10, 12, 16}) {
        for (CoreGrouping grouping : {CoreGrouping::FrontalSlice, CoreGrouping::Mode0Fibre, CoreGrouping::Whole}) {
            QuantizeTuckerOptions options;
            options.core_bits = bits;
            options.basis_bits = bits;
            options.core_grouping = grouping;
            const QuantizedTucker qt = quantize_tucker(model, options);
            for (int part = 0; part < 4; ++part) CHECK(qt.max_abs_error[part] <= qt.error_bound[part] * (1 + 1e-12));
            CHECK(qt.packed_bytes() == packed_tucker_bytes(model.dims(), model.ranks, options));
            for (const EncodedStream* s : {&qt.packed, &qt.deflated}) {
                const tensor::TuckerModel back = decode_quantized_tucker(s->bytes);
                CHECK(back.ranks == model.ranks);
                CHECK(back.method == model.method);
                CHECK(test::max_abs_diff(back.core, qt.model.core) == 0.0);
                for (int k = 0; k < 3; ++k) CHECK((back.U[k] - qt.model.U[k]).cwiseAbs().maxCoeff() == 0.0);
            }
            CHECK(quantize_tucker(model, options).deflated.bytes == qt.deflated.bytes);  // deterministic
            if (grouping == CoreGrouping::FrontalSlice) {
                const double err = tensor::absolute_error(a, qt.model);
                INFO("bits " << bits << ": |A - A_q| = " << err << " (truncation alone " << truncation << "), packed "
                             << qt.packed_bytes() << " B, deflated " << qt.deflated_bytes() << " B");
                CHECK(err < previous_error);
                previous_error = err;
                if (bits == 16) CHECK(err < truncation * 1.001 + 1e-9);
            }
        }
    }
    // Raw float32 storage of the same model, for scale: 4 (12*8*6 + 40*12 + 60*8 + 15*6) bytes.
    QuantizeTuckerOptions eight;
    eight.core_bits = eight.basis_bits = 8;
    CHECK(quantize_tucker(model, eight).packed_bytes() < static_cast<std::size_t>(model.parameter_count()) * 4 / 3);

    CHECK(test::mutate_and_decode(quantize_tucker(model, eight).packed,
                                  [](const Bytes& s) { decode_quantized_tucker(s); }, 5, 100) > 0);
    CHECK(test::mutate_and_decode(quantize_tucker(model, eight).deflated,
                                  [](const Bytes& s) { decode_quantized_tucker(s); }, 6, 100) > 0);
}

TEST_CASE("quantize_tucker refuses inconsistent models and options", "[codec][quantize]") {
    const tensor::TuckerModel model = tensor::hosvd(test::random_tensor3(6, 5, 4, 1), {2, 2, 2});
    QuantizeTuckerOptions bad;
    bad.core_bits = 0;
    CHECK_THROWS_AS(quantize_tucker(model, bad), InvalidArgument);
    bad = {};
    bad.deflate_level = 12;
    CHECK_THROWS_AS(quantize_tucker(model, bad), InvalidArgument);
    tensor::TuckerModel broken = model;
    broken.U[1] = MatX::Zero(5, 3);
    CHECK_THROWS_AS(quantize_tucker(broken), InvalidArgument);
    broken = model;
    broken.core = Tensor3(2, 2, 3);
    CHECK_THROWS_AS(quantize_tucker(broken), InvalidArgument);
}
