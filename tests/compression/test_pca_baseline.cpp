#include <catch2/catch.hpp>

#include <Eigen/SVD>

#include "codec_fixtures.hpp"
#include "mocapdb/compression/codecs/pca_baseline.hpp"

using namespace mocapdb;
using namespace mocapdb::compression::codecs;

namespace {
double sq_diff(const Tensor3& a, const Tensor3& b) {
    double s = 0;
    for (Eigen::Index i = 0; i < a.size(); ++i) s += (a.data()[i] - b.data()[i]) * (a.data()[i] - b.data()[i]);
    return s;
}
}  // namespace

TEST_CASE("per-sample PCA matches an SVD of the centred samples", "[codec][pca]") {
    // N < D T (the Gram path) and N >= D T (the covariance path).
    for (const auto& shape : {std::array<Eigen::Index, 3>{6, 20, 15}, std::array<Eigen::Index, 3>{2, 3, 9}}) {
        const Tensor3 a = test::smooth_tensor3(shape[0], shape[1], shape[2], 8);
        Tensor3 noisy = a;
        const Tensor3 noise = test::random_tensor3(shape[0], shape[1], shape[2], 9, 0.05);
        for (Eigen::Index i = 0; i < a.size(); ++i) noisy.data()[i] += noise.data()[i];
        const SamplePca pca(noisy);
        const Eigen::Index L = shape[0] * shape[1], N = shape[2];
        CHECK(pca.max_components() == std::min(L, N));

        // Oracle: singular values of the centred L by N matrix by Jacobi SVD.
        const Eigen::Map<const MatX> x(noisy.data(), L, N);
        const MatX x0 = x.colwise() - x.rowwise().mean();
        const Eigen::JacobiSVD<MatX> svd(x0);
        const Eigen::Index m = std::min(svd.singularValues().size(), pca.max_components());
        const double s1 = svd.singularValues()[0];
        INFO("shape " << shape[0] << "x" << shape[1] << "x" << shape[2]);
        CHECK((pca.singular_values().head(m) - svd.singularValues().head(m)).cwiseAbs().maxCoeff() <= 1e-6 * s1);

        double previous = 1e300;
        for (Eigen::Index k = 0; k <= pca.max_components(); ++k) {
            const double err = sq_diff(noisy, pca.reconstruct(k, false));
            // Eckart-Young: the error of k components is the discarded energy.
            CHECK(err == Approx(pca.discarded_energy(k)).margin(1e-9 * s1 * s1));
            CHECK(err <= previous + 1e-9 * s1 * s1);
            previous = err;
            CHECK(pca.stored_bytes(k) == static_cast<std::size_t>(4 * (L + k * L + N * k)));
        }
        // Full components: exact in double, float32-exact when stored as float32.
        CHECK(std::sqrt(sq_diff(noisy, pca.reconstruct(std::min(N - 1, pca.max_components()), false))) <= 1e-10 * s1);
        const double f32 = std::sqrt(test::max_abs_diff(noisy, pca.reconstruct(pca.max_components())));
        CHECK(f32 <= 1e-3);
        // The basis is orthonormal.
        const MatX g = pca.basis().transpose() * pca.basis();
        CHECK((g - MatX::Identity(g.rows(), g.cols())).cwiseAbs().maxCoeff() <= 1e-10);
    }
}

TEST_CASE("per-sample PCA refuses bad arguments", "[codec][pca]") {
    CHECK_THROWS_AS(SamplePca(Tensor3(0, 2, 2)), InvalidArgument);
    Tensor3 a = test::random_tensor3(3, 4, 5, 1);
    a(0, 0, 4) = std::nan("");
    CHECK_THROWS_AS(SamplePca(a), InvalidArgument);
    const SamplePca pca(test::random_tensor3(3, 4, 5, 2));
    CHECK_THROWS_AS(pca.reconstruct(-1), InvalidArgument);
    CHECK_THROWS_AS(pca.reconstruct(6), InvalidArgument);
    CHECK_THROWS_AS(pca.stored_bytes(6), InvalidArgument);
    // One sample: only the mean (k = 0 .. 1), reconstructed exactly.
    const Tensor3 one = test::random_tensor3(3, 4, 1, 3);
    const SamplePca single(one);
    CHECK(test::max_abs_diff(one, single.reconstruct(0, false)) <= 1e-15);
}
