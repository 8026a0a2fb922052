#include <catch2/catch.hpp>

#include "codec_fixtures.hpp"
#include "mocapdb/compression/codecs/deflate.hpp"
#include "mocapdb/compression/codecs/zfp_codec.hpp"

using namespace mocapdb;
using namespace mocapdb::compression::codecs;

TEST_CASE("zfp fixed accuracy keeps every error within the tolerance", "[codec][zfp]") {
    const Tensor3 smooth = test::smooth_tensor3(30, 100, 12, 31);
    const Tensor3 noisy = test::random_tensor3(13, 21, 6, 32, 2.0);  // sizes not multiples of 4
    for (const Tensor3* a : {&smooth, &noisy}) {
        std::size_t previous = std::numeric_limits<std::size_t>::max();
        for (double tol : {1e-6, 1e-4, 1e-3, 1e-2, 0.1, 1.0}) {
            const EncodedStream s = zfp_encode(*a, tol);
            const Tensor3 back = zfp_decode(s.bytes);
            const double err = test::max_abs_diff(*a, back);
            INFO("tolerance " << tol << ": max error " << err << ", " << s.payload_bytes() << " B of "
                              << 8 * a->size() << " raw double");
            CHECK(err <= tol);
            CHECK(s.payload_bytes() <= previous);
            previous = s.payload_bytes();
            CHECK(s.header_bytes + s.payload_bytes() == s.bytes.size());
            CHECK(zfp_encode(*a, tol).bytes == s.bytes);  // deterministic
        }
    }
    // Smooth data compresses far better than noise at the same tolerance and size.
    const auto smooth_bytes = static_cast<double>(zfp_encode(smooth, 1e-3).payload_bytes()) / static_cast<double>(smooth.size());
    const auto noisy_bytes = static_cast<double>(zfp_encode(noisy, 1e-3).payload_bytes()) / static_cast<double>(noisy.size());
    INFO("bytes per value at 1e-3: smooth " << smooth_bytes << ", noise " << noisy_bytes);
    CHECK(smooth_bytes < 0.5 * noisy_bytes);
    CHECK(zfp_encode(smooth, 1e-3).payload_bytes() < encode_float32_deflate(smooth).payload_bytes());
}

TEST_CASE("zfp with per-dof tolerances bounds each dof by its own", "[codec][zfp]") {
    const Eigen::Index D = 9;
    const Tensor3 a = test::smooth_tensor3(D, 50, 8, 33);
    VecX eps(D);
    for (Eigen::Index d = 0; d < D; ++d) eps[d] = 1e-4 * std::pow(3.0, static_cast<double>(d));
    const EncodedStream s = zfp_encode(a, eps);
    const Tensor3 back = zfp_decode(s.bytes);
    for (Eigen::Index i = 0; i < a.size(); ++i)
        REQUIRE(std::abs(a.data()[i] - back.data()[i]) <= eps[i % D] * (1 + 1e-12));
    // Loosening the tolerances of some dofs lowers the bytes; uniform eps = min costs more.
    CHECK(s.payload_bytes() < zfp_encode(a, VecX::Constant(D, eps.minCoeff())).payload_bytes());
    CHECK(s.payload_bytes() >= static_cast<std::size_t>(4 * D));
}

TEST_CASE("zfp codec refuses bad arguments and bad streams", "[codec][zfp]") {
    const Tensor3 a = test::smooth_tensor3(8, 16, 4, 34);
    CHECK_THROWS_AS(zfp_encode(a, 0.0), InvalidArgument);
    CHECK_THROWS_AS(zfp_encode(a, -1.0), InvalidArgument);
    CHECK_THROWS_AS(zfp_encode(a, std::nan("")), InvalidArgument);
    CHECK_THROWS_AS(zfp_encode(Tensor3(0, 4, 4), 0.1), InvalidArgument);
    CHECK_THROWS_AS(zfp_encode(a, VecX::Constant(7, 0.1)), InvalidArgument);
    CHECK_THROWS_AS(zfp_encode(a, VecX::Zero(8)), InvalidArgument);
    Tensor3 bad = a;
    bad(3, 3, 3) = std::numeric_limits<double>::infinity();
    CHECK_THROWS_AS(zfp_encode(bad, 0.1), InvalidArgument);

    auto decode_finite = [](const Bytes& s) {
        const Tensor3 t = zfp_decode(s);
        for (Eigen::Index i = 0; i < t.size(); ++i) REQUIRE(std::isfinite(t.data()[i]));
    };
    CHECK(test::mutate_and_decode(zfp_encode(a, 1e-3), decode_finite, 35) > 0);
    CHECK(test::mutate_and_decode(zfp_encode(a, VecX::Constant(8, 1e-3)), decode_finite, 36) > 0);
    const EncodedStream s = zfp_encode(a, 1e-3);
    Bytes cut(s.bytes.begin(), s.bytes.end() - 8);
    CHECK_THROWS_WITH(zfp_decode(cut), Catch::Contains("zfp stream") && Catch::Contains("payload size"));
}
