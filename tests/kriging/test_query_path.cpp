// The single-query path of Kriging::weights against the batch path, for every shape the single-query
// kernels special-case (lib/src/kriging/query_kernels.hpp: sizes padded to a multiple of 4, trend bases
// of 1 to 8 columns, merged duplicates), and the variogram values of the general stable exponent
// (computed with their own logarithm and exponentials) against a long double reference.
//
// With AVX2 + FMA, weights() uses the packed symmetric block of the operator and weights_batch() one
// Eigen product with the full operator: the same sums in different orders, so they may differ by the
// rounding bound of a sum of M + K products, (M + K) eps sum_j |A_ij x_j|, and no more.
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "mocapdb/kriging/kriging.hpp"
#include "random_points.hpp"

using namespace mocapdb::kriging;
using mocapdb::kriging::test::uniform;

namespace {

// gamma(|c - c_i|) over the unique points.
Eigen::VectorXd gamma_at(const Kriging& k, const Eigen::VectorXd& c) {
    const Eigen::MatrixXd& pts = k.unique_points();
    Eigen::VectorXd g(pts.rows());
    for (Eigen::Index i = 0; i < pts.rows(); ++i) g(i) = k.model()((pts.row(i).transpose() - c).norm());
    return g;
}

}  // namespace

TEST_CASE("Single-query weights equal the batch weights for every size, trend and model", "[kriging][query]") {
    const std::vector<VariogramModel> models = {
        VariogramModel::spherical(0.05, 1.0, 0.8), VariogramModel::stable(2.0, 0.05, 1.0, 0.5),
        VariogramModel::stable(1.0, 0.0, 2.0, 0.7), VariogramModel::stable(1.4, 0.01, 1.0, 0.5),
        VariogramModel::stable(0.3, 0.0, 1.0, 0.9)};
    const double eps = std::numeric_limits<double>::epsilon();
    double worst_ratio = 0.0;  // difference / its rounding bound, reported below
    for (const Eigen::Index n : {1, 2, 3, 4, 5, 6, 7, 9, 13, 30, 92, 93}) {
        for (const Eigen::Index p : {1, 2, 4, 7}) {  // trend bases of 2, 3, 5 and 8 columns
            Eigen::MatrixXd pts = uniform(n, p, static_cast<unsigned>(100 * n + p), 0.0, 1.0);
            const bool with_duplicate = n >= 5;
            if (with_duplicate) pts.row(n - 1) = pts.row(1);  // merged: M = N - 1 unique points
            Eigen::MatrixXd queries(40 + n + 3, p);
            queries << uniform(40, p, 7, -0.3, 1.3), pts, uniform(3, p, 8, 4.0, 9.0);
            for (const auto& model : models) {
                for (int variant = 0; variant < 3; ++variant) {
                    KrigingOptions opt;
                    if (variant == 0) opt.trend = TrendKind::None;
                    opt.trend_fit = variant == 2 ? TrendFit::GLS : TrendFit::OLS;
                    const Kriging k = Kriging::build(pts, model, opt);
                    INFO("N = " << n << ", P = " << p << ", " << model.to_string() << ", trend "
                                << to_string(opt.trend) << " " << to_string(opt.trend_fit));
                    REQUIRE(k.unique_points().rows() == (with_duplicate ? n - 1 : n));
                    const Eigen::MatrixXd wb = k.weights_batch(queries);
                    const Eigen::MatrixXd& wc = k.data_block_inverse();
                    const Eigen::Index m = k.unique_points().rows();
                    const Eigen::Index kk = k.trend_basis().size();
                    QueryWorkspace ws;
                    Eigen::VectorXd w(n);
                    for (Eigen::Index q = 0; q < queries.rows(); ++q) {
                        const Eigen::VectorXd c = queries.row(q).transpose();
                        k.weights(c, w, ws);
                        REQUIRE(w.allFinite());
                        // Partition of unity (also where the OLS trend correction, applied by the
                        // projection on this path, is of the size of the weights).
                        INFO("query " << q << ": sum(w) - 1 = " << w.sum() - 1.0 << " (batch "
                                      << wb.col(q).sum() - 1.0 << "), |w|_1 = " << w.cwiseAbs().sum());
                        CHECK(std::abs(w.sum() - 1.0) <= 1e-12);
                        // The rounding bound of the sums: (M + K) eps (|Wc| |gamma| + |G| |g(c)| + 1) per
                        // entry (the data part, the trend part with G = [1, U] the sample basis, and
                        // weights of order 1), times 4 for the projection and the merging of duplicates.
                        Eigen::VectorXd g(kk);
                        k.trend_basis().evaluate(c, g);
                        const Eigen::VectorXd scale = (wc.cwiseAbs() * gamma_at(k, c).cwiseAbs() +
                                                       k.trend_basis().sample_basis().cwiseAbs() * g.cwiseAbs())
                                                          .array() +
                                                      1.0;
                        const double bound = 4.0 * static_cast<double>(m + kk) * eps * scale.maxCoeff();
                        const double diff = (w - wb.col(q)).cwiseAbs().maxCoeff();
                        CHECK(diff <= bound);
                        worst_ratio = std::max(worst_ratio, diff / bound);
                    }
                    // Exact interpolation at the samples (a merged pair shares its weight), unless the
                    // system had to be regularized (e.g. the spherical model in 7 dimensions).
                    for (Eigen::Index j = 0; j < n && k.status().exact(); ++j) {
                        k.weights(pts.row(j).transpose(), w, ws);
                        Eigen::VectorXd expect = Eigen::VectorXd::Unit(n, j);
                        if (with_duplicate && (j == 1 || j == n - 1)) {
                            expect.setZero();
                            expect(1) = expect(n - 1) = 0.5;
                        }
                        CHECK((w - expect).cwiseAbs().maxCoeff() <= 1e-9);
                    }
                }
            }
        }
    }
    WARN("single-query against batch weights: largest difference " << worst_ratio << " of its rounding bound");
}

TEST_CASE("A NaN query coordinate gives NaN weights, never finite ones", "[kriging][query]") {
    const Eigen::MatrixXd pts = uniform(30, 3, 21, 0.0, 1.0);
    for (const auto& model : {VariogramModel::spherical(0.0, 1.0, 0.8), VariogramModel::stable(2.0, 0.0, 1.0, 0.5),
                              VariogramModel::stable(1.4, 0.0, 1.0, 0.5)}) {
        const Kriging k = Kriging::build(pts, model);
        Eigen::VectorXd c(3);
        c << 0.5, std::nan(""), 0.5;
        INFO(model.to_string());
        CHECK(k.weights(c).array().isNaN().all());
    }
}

TEST_CASE("Variogram values of general stable exponents match a long double reference", "[kriging][variogram]") {
    // Distances over 16 decades, plus 0, a subnormal square (blended towards gamma(0) = 0, see
    // gamma_of_squared), one whose square overflows, and infinity; lengths that leave 1 to 3 values after
    // the last full vector and that cross the 128-value chunks.
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> decade(-12.0, 4.0);
    for (const Eigen::Index n : {1, 2, 3, 5, 127, 128, 129, 301}) {
        Eigen::VectorXd d2(n);
        for (Eigen::Index i = 0; i < n; ++i) d2(i) = std::pow(10.0, 2.0 * decade(rng));
        if (n > 4) {
            d2(0) = 0.0;
            d2(1) = 4.9e-324;
            d2(2) = std::numeric_limits<double>::infinity();
            d2(3) = 1e300;
        }
        for (const double p : {0.2, 0.4, 0.6, 0.8, 1.2, 1.4, 1.6, 1.8, 1.99}) {
            for (const double nugget : {0.0, 0.1}) {
                const VariogramModel m = VariogramModel::stable(p, nugget, 2.0, 0.7);
                Eigen::VectorXd g(n);
                m.gamma_of_squared(d2, g);
                Eigen::VectorXd in_place = d2;
                m.gamma_of_squared(in_place, in_place);
                INFO("n = " << n << ", " << m.to_string());
                CHECK((in_place.array() == g.array()).all());
                for (Eigen::Index i = 0; i < n; ++i) {
                    INFO("squared distance " << d2(i));
                    REQUIRE(std::isfinite(g(i)));
                    if (d2(i) == 0.0) {
                        CHECK(g(i) == 0.0);
                    } else if (d2(i) < std::numeric_limits<double>::min()) {
                        CHECK((g(i) >= 0.0 && g(i) <= m.total_sill()));
                    } else {
                        const long double h = std::sqrt(static_cast<long double>(d2(i)));
                        const long double ref =
                            nugget + 2.0L * -std::expm1(-std::pow(h / 0.7L, static_cast<long double>(p)));
                        CHECK(std::abs(static_cast<double>(g(i) - ref)) <= 1e-15 * m.total_sill());
                    }
                }
            }
        }
    }
}
