#include <catch2/catch.hpp>

#include "codec_fixtures.hpp"
#include "mocapdb/compression/codecs/residual_layer.hpp"

using namespace mocapdb;
using namespace mocapdb::compression::codecs;

TEST_CASE("residual layer keeps every element within its dof's tolerance", "[codec][residual]") {
    const Eigen::Index D = 12, T = 40, N = 7;
    const Tensor3 r = test::random_tensor3(D, T, N, 21, 0.5);
    VecX eps(D);
    for (Eigen::Index d = 0; d < D; ++d) eps[d] = 0.001 * std::pow(1.9, static_cast<double>(d));  // 0.001 .. 1.2
    for (ResidualOrder order : {ResidualOrder::DofMajor, ResidualOrder::Storage}) {
        ResidualOptions options;
        options.order = order;
        const ResidualEncoding enc = encode_residual(r, eps, options);
        const Tensor3 back = decode_residual(enc.stream.bytes);
        CHECK(test::max_abs_diff(back, enc.decoded) == 0.0);
        for (Eigen::Index i = 0; i < r.size(); ++i) {
            const Eigen::Index d = i % D;
            REQUIRE(enc.tolerance[d] <= eps[d]);
            REQUIRE(std::abs(r.data()[i] - back.data()[i]) <= enc.tolerance[d]);
        }
        CHECK(enc.max_abs_error <= eps.maxCoeff());
        CHECK(enc.nonzero > 0);
        // Payload: 4 D tolerances, the varint length, the deflated codes.
        CHECK(enc.stream.payload_bytes() > static_cast<std::size_t>(4 * D));
        CHECK(enc.stream.header_bytes + enc.stream.payload_bytes() == enc.stream.bytes.size());
        CHECK(encode_residual(r, eps, options).stream.bytes == enc.stream.bytes);  // deterministic
    }
}

TEST_CASE("residual layer: bytes fall with the tolerance, a large one stores nothing", "[codec][residual]") {
    const Tensor3 r = test::random_tensor3(20, 50, 10, 22, 0.01);  // a good lossy stage: small residual
    std::size_t previous = std::numeric_limits<std::size_t>::max();
    for (double eps : {1e-5, 1e-4, 1e-3, 1e-2}) {
        const ResidualEncoding enc = encode_residual(r, eps);
        INFO("eps " << eps << ": " << enc.stream.payload_bytes() << " B, " << enc.nonzero << " nonzero codes");
        CHECK(enc.stream.payload_bytes() < previous);
        previous = enc.stream.payload_bytes();
        CHECK(test::max_abs_diff(r, decode_residual(enc.stream.bytes)) <= eps);
    }
    const ResidualEncoding zero = encode_residual(r, 1.0);  // every |R| < 1: all codes 0
    CHECK(zero.nonzero == 0);
    CHECK(zero.stream.payload_bytes() == 0);
    CHECK(zero.stream.bytes.size() < 40);
    const Tensor3 z = decode_residual(zero.stream.bytes);
    CHECK(test::max_abs_diff(z, Tensor3(Tensor3(20, 50, 10).setZero())) == 0.0);
    CHECK(test::max_abs_diff(r, z) <= 1.0);
}

TEST_CASE("residual layer at the rounding edges", "[codec][residual]") {
    // Values on half-steps, far out (2^30 tolerances), and tiny tolerances.
    Tensor3 r(3, 4, 2);
    const double eps = 0.1;
    const double step = 2 * static_cast<double>(static_cast<float>(eps)) * (1 - std::ldexp(1.0, -20));
    for (Eigen::Index i = 0; i < r.size(); ++i) r.data()[i] = (static_cast<double>(i) - 11.5) * step;
    r(0, 0, 0) = std::ldexp(1.0, 30) * eps;
    r(1, 0, 0) = -std::ldexp(1.0, 30) * eps + 0.5 * step;
    r(2, 0, 0) = eps;
    const ResidualEncoding enc = encode_residual(r, eps);
    CHECK(test::max_abs_diff(r, decode_residual(enc.stream.bytes)) <= eps);
    CHECK(enc.max_abs_code > (std::int64_t{1} << 29));
    CHECK_THROWS_WITH(encode_residual(r, 1e-30), Catch::Contains("2^31"));  // |R| / eps beyond 2^31
}

TEST_CASE("residual layer refuses bad arguments and bad streams", "[codec][residual]") {
    const Tensor3 r = test::random_tensor3(5, 6, 3, 23, 0.2);
    CHECK_THROWS_AS(encode_residual(r, VecX::Constant(4, 0.1)), InvalidArgument);  // 4 tolerances for 5 dofs
    CHECK_THROWS_AS(encode_residual(r, 0.0), InvalidArgument);
    CHECK_THROWS_AS(encode_residual(r, -1.0), InvalidArgument);
    CHECK_THROWS_AS(encode_residual(r, std::nan("")), InvalidArgument);
    CHECK_THROWS_AS(encode_residual(Tensor3(0, 2, 2), 0.1), InvalidArgument);
    Tensor3 bad = r;
    bad(4, 5, 2) = std::numeric_limits<double>::infinity();
    CHECK_THROWS_AS(encode_residual(bad, 0.1), InvalidArgument);

    VecX eps(5);
    eps << 0.01, 0.02, 0.05, 0.1, 0.3;
    const ResidualEncoding enc = encode_residual(r, eps);
    const int errors = test::mutate_and_decode(enc.stream, [](const Bytes& s) {
        const Tensor3 t = decode_residual(s);
        for (Eigen::Index i = 0; i < t.size(); ++i) REQUIRE(std::isfinite(t.data()[i]));
    }, 24);
    CHECK(errors > 0);
    Bytes cut(enc.stream.bytes.begin(), enc.stream.bytes.begin() + 10);
    CHECK_THROWS_WITH(decode_residual(cut), Catch::Contains("residual stream") && Catch::Contains("truncated"));
}
