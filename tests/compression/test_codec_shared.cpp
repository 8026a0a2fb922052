// The codecs on real motion: subject 16's walks (shared CMU clips) aligned by DTW, 90 x 100 x N.
#include <catch2/catch.hpp>

#include "codec_fixtures.hpp"
#include "mocapdb/compression/codecs/deflate.hpp"
#include "mocapdb/compression/codecs/pca_baseline.hpp"
#include "mocapdb/compression/codecs/quantize.hpp"
#include "mocapdb/compression/codecs/residual_layer.hpp"
#include "mocapdb/compression/codecs/zfp_codec.hpp"
#include "mocapdb/tensor/hosvd.hpp"

using namespace mocapdb;
using namespace mocapdb::compression::codecs;

namespace {
Tensor3 plus(const Tensor3& a, const Tensor3& b) {
    Tensor3 c = a;
    for (Eigen::Index i = 0; i < c.size(); ++i) c.data()[i] += b.data()[i];
    return c;
}
Tensor3 minus(const Tensor3& a, const Tensor3& b) {
    Tensor3 c = a;
    for (Eigen::Index i = 0; i < c.size(); ++i) c.data()[i] -= b.data()[i];
    return c;
}
}  // namespace

TEST_CASE("codec baselines on subject 16's walks", "[codec][shared]") {
    MOCAPDB_REQUIRE_SHARED(test::datasets_dir() / "cmu-asfamc");
    const Tensor3& a = test::subject16_walks_aligned().tensor;
    const Eigen::Index D = a.dimension(0), T = a.dimension(1), N = a.dimension(2);
    REQUIRE(D == 90);
    REQUIRE(T == 100);
    const std::size_t raw = static_cast<std::size_t>(4 * a.size());

    // Lossless float32.
    const EncodedStream lossless = encode_float32_deflate(a);
    CHECK(test::max_abs_diff(decode_float32_deflate(lossless.bytes), round_to_float32(a)) == 0.0);
    CHECK(lossless.payload_bytes() < raw);
    WARN("subject 16 walks " << D << "x" << T << "x" << N << ": raw float32 " << raw << " B, lossless float32 deflate "
                             << lossless.payload_bytes() << " B (ratio " << double(raw) / double(lossless.payload_bytes()) << ")");

    // zfp at tolerances in the tensor's units (cm for the root position, radians elsewhere).
    std::size_t previous = raw;
    for (double tol : {1e-3, 1e-2, 1e-1}) {
        const EncodedStream z = zfp_encode(a, tol);
        const double err = test::max_abs_diff(a, zfp_decode(z.bytes));
        WARN("zfp tolerance " << tol << ": " << z.payload_bytes() << " B (ratio " << double(raw) / double(z.payload_bytes())
                              << "), max error " << err);
        CHECK(err <= tol);
        CHECK(z.payload_bytes() < previous);
        previous = z.payload_bytes();
    }
    CHECK(zfp_encode(a, 1e-3).payload_bytes() < lossless.payload_bytes());

    // Per-sample PCA, then the residual layer on top of it: every element within eps.
    const SamplePca pca(a);
    CHECK(test::max_abs_diff(a, pca.reconstruct(N - 1, false)) < 1e-9);
    for (Eigen::Index k : {Eigen::Index{2}, Eigen::Index{5}, Eigen::Index{10}}) {
        if (k > pca.max_components()) continue;  // fewer clips under sanitizers
        const Tensor3 lossy = pca.reconstruct(k);
        for (double eps : {1e-2, 1e-1}) {
            const ResidualEncoding res = encode_residual(minus(a, lossy), eps);
            const Tensor3 final_values = plus(lossy, decode_residual(res.stream.bytes));
            CHECK(test::max_abs_diff(a, final_values) <= eps * (1 + 1e-9));
            WARN("PCA k=" << k << " (" << pca.stored_bytes(k) << " B, max error " << test::max_abs_diff(a, lossy)
                          << ") + residual eps " << eps << ": " << res.stream.payload_bytes() << " B, "
                          << res.nonzero << " nonzero codes; total " << pca.stored_bytes(k) + res.stream.payload_bytes() << " B");
        }
    }

    // Quantized Tucker + residual: the guarantee holds whatever the lossy stage.
    const tensor::TuckerModel model = tensor::hosvd(a, {40, 20, std::min<Eigen::Index>(N, 15)});
    QuantizeTuckerOptions q;
    q.core_bits = q.basis_bits = 10;
    const QuantizedTucker qt = quantize_tucker(model, q);
    const Tensor3 lossy = qt.model.reconstruct();
    const ResidualEncoding res = encode_residual(minus(a, lossy), 1e-2);
    CHECK(test::max_abs_diff(a, plus(lossy, res.decoded)) <= 1e-2 * (1 + 1e-9));
    WARN("HOSVD (40,20,15) 10-bit: packed " << qt.packed_bytes() << " B, deflated " << qt.deflated_bytes()
                                           << " B (float32 " << 4 * model.parameter_count() << " B), max error "
                                           << test::max_abs_diff(a, lossy) << "; + residual eps 0.01: "
                                           << res.stream.payload_bytes() << " B");
}
