// Local (moving-neighbourhood) kriging: equal to the exact kriging when the neighbourhood holds every
// point, exact interpolation and unbiasedness with a small one, the right neighbours, and gstat's nmax.
#include <algorithm>
#include <cmath>
#include <set>
#include <string>

#include <catch2/catch.hpp>

#include "csv_fixture.hpp"
#include "mocapdb/core/error.hpp"
#include "mocapdb/kriging/kriging.hpp"
#include "mocapdb/kriging/local_kriging.hpp"
#include "random_points.hpp"
#include "shared_data.hpp"

using namespace mocapdb::kriging;
using mocapdb::kriging::test::uniform;
using mocapdb::test::read_csv;

namespace {

KrigingOptions local_test_options(TrendFit fit, bool filter) {
    KrigingOptions o;
    o.trend = TrendKind::Linear;
    o.trend_fit = fit;
    o.filter_nugget = filter;
    return o;
}

}  // namespace

TEST_CASE("local kriging with every point in the neighbourhood equals the exact kriging") {
    const Eigen::MatrixXd x = uniform(60, 3, 7, -1.0, 1.0);
    const Eigen::MatrixXd q = uniform(25, 3, 8, -1.2, 1.2);
    const VariogramModel model = VariogramModel::stable(1.5, 0.05, 1.0, 0.8);
    for (const TrendFit fit : {TrendFit::OLS, TrendFit::GLS}) {
        for (const bool filter : {false, true}) {
            const KrigingOptions o = local_test_options(fit, filter);
            const Kriging exact = Kriging::build(x, model, o);
            for (const Eigen::Index k : {Eigen::Index{60}, Eigen::Index{500}}) {
                const LocalKriging local = LocalKriging::build(x, model, o, k);
                REQUIRE(local.neighbours() == 60);
                const KrigingBatch a = exact.estimate_batch(q);
                const KrigingBatch b = local.estimate_batch(q);
                INFO(to_string(fit) << " filter " << filter << " k " << k);
                CHECK((a.weights - b.weights).cwiseAbs().maxCoeff() < 1e-9);
                CHECK((a.variance - b.variance).cwiseAbs().maxCoeff() < 1e-9);
                CHECK((a.paper_variance - b.paper_variance).cwiseAbs().maxCoeff() < 1e-9);
                CHECK((a.reliability - b.reliability).cwiseAbs().maxCoeff() < 1e-9);
                // the single-query paths too
                const Eigen::VectorXd c = q.row(3).transpose();
                const KrigingEstimate ea = exact.estimate(c);
                const KrigingEstimate eb = local.estimate(c);
                CHECK((ea.kernel - eb.kernel).cwiseAbs().maxCoeff() < 1e-9);
                CHECK((exact.weights(c) - local.weights(c)).cwiseAbs().maxCoeff() < 1e-9);
                CHECK((exact.weights_batch(q) - local.weights_batch(q)).cwiseAbs().maxCoeff() < 1e-9);
                CHECK((exact.reliability(q) - local.reliability(q)).cwiseAbs().maxCoeff() < 1e-9);
            }
        }
    }
}

TEST_CASE("local kriging with a small neighbourhood interpolates the samples and reproduces the trend") {
    const Eigen::MatrixXd x = uniform(200, 2, 11, 0.0, 4.0);
    const VariogramModel model = VariogramModel::stable(1.0, 0.0, 1.0, 1.5);
    for (const TrendFit fit : {TrendFit::OLS, TrendFit::GLS}) {
        const LocalKriging local = LocalKriging::build(x, model, local_test_options(fit, false), 12);
        INFO(to_string(fit));
        // At a sample: its own weight 1, every other 0, variance 0, rho 1.
        for (const Eigen::Index j : {Eigen::Index{0}, Eigen::Index{77}, Eigen::Index{199}}) {
            const KrigingEstimate e = local.estimate(x.row(j).transpose());
            Eigen::VectorXd unit = Eigen::VectorXd::Zero(200);
            unit(j) = 1.0;
            CHECK((e.weights - unit).cwiseAbs().maxCoeff() < 1e-9);
            CHECK(e.variance < 1e-9);
            CHECK(e.reliability > 1.0 - 1e-9);
        }
        // Anywhere: the weights sum to one and reproduce the linear trend (sum w_i x_i = c); GLS: nonzero
        // only in the neighbourhood.
        const Eigen::MatrixXd q = uniform(20, 2, 12, -0.5, 4.5);
        const Eigen::MatrixXd w = local.weights_batch(q);
        for (Eigen::Index k = 0; k < q.rows(); ++k) {
            CHECK(std::abs(w.col(k).sum() - 1.0) < 1e-10);
            CHECK((x.transpose() * w.col(k) - q.row(k).transpose()).norm() < 1e-9);
            if (fit == TrendFit::GLS) {
                const Eigen::VectorXi nb = local.neighbourhood(q.row(k).transpose());
                std::set<int> in(nb.data(), nb.data() + nb.size());
                for (Eigen::Index i = 0; i < 200; ++i)
                    if (in.count(static_cast<int>(i)) == 0) CHECK(w(i, k) == 0.0);
            }
        }
        // GLS (gstat's local universal kriging): rho is the one of the exact kriging of the 12 neighbours
        // alone. (OLS keeps the global trend: its weights reach every sample, tested above.)
        if (fit != TrendFit::GLS) continue;
        const Eigen::VectorXd c = q.row(4).transpose();
        const Eigen::VectorXi nb = local.neighbourhood(c);
        Eigen::MatrixXd xn(nb.size(), 2);
        for (Eigen::Index j = 0; j < nb.size(); ++j) xn.row(j) = x.row(nb(j));
        const Kriging alone = Kriging::build(xn, model, local_test_options(fit, false));
        CHECK(std::abs(alone.estimate(c).reliability - local.estimate(c).reliability) < 1e-12);
        CHECK(std::abs(alone.estimate(c).variance - local.estimate(c).variance) < 1e-12);
    }
}

TEST_CASE("local kriging's OLS variance is the error variance of the weights it uses") {
    // OLS keeps the global trend, so its weights reach every sample: V = 2 w^T gamma(c) - w^T Gamma w
    // (+ the nugget when filtered), computed here directly with the whole variogram matrix.
    const Eigen::MatrixXd x = uniform(80, 2, 31, 0.0, 3.0);
    const VariogramModel model = VariogramModel::stable(1.2, 0.05, 1.0, 1.0);
    Eigen::MatrixXd gamma(80, 80);
    for (Eigen::Index i = 0; i < 80; ++i)
        for (Eigen::Index j = 0; j < 80; ++j) gamma(i, j) = model((x.row(i) - x.row(j)).norm());
    for (const bool filter : {false, true}) {
        VariogramModel query = model;
        if (filter) query.nugget = 0.0;
        const LocalKriging local = LocalKriging::build(x, model, local_test_options(TrendFit::OLS, filter), 10);
        const Eigen::MatrixXd q = uniform(6, 2, 32, -0.5, 3.5);
        for (Eigen::Index k = 0; k < q.rows(); ++k) {
            const KrigingEstimate e = local.estimate(q.row(k).transpose());
            Eigen::VectorXd gq(80);
            for (Eigen::Index i = 0; i < 80; ++i) gq(i) = query((x.row(i) - q.row(k)).norm());
            const double v = 2.0 * e.weights.dot(gq) - e.weights.dot(gamma * e.weights) + (filter ? model.nugget : 0.0);
            INFO("filter " << filter << " query " << k);
            CHECK(std::abs(e.variance - std::max(v, 0.0)) < 1e-10);
            CHECK(std::abs(e.reliability - std::clamp(1.0 - e.variance / model.total_sill(), 0.0, 1.0)) < 1e-12);
            CHECK(std::abs(e.paper_variance - e.kernel.dot(gq)) < 1e-10);
        }
    }
}

TEST_CASE("local kriging chooses the nearest points, ties in sample order") {
    Eigen::MatrixXd x(10, 2);
    for (int i = 0; i < 10; ++i) x.row(i) << static_cast<double>(i), 0.0;  // 0, 1, ..., 9 on a line
    const VariogramModel model = VariogramModel::stable(1.0, 0.0, 1.0, 3.0);
    const LocalKriging three = LocalKriging::build(x, model, local_test_options(TrendFit::GLS, false), 3);
    const Eigen::Vector2d c(3.4, 0.7);
    CHECK(three.neighbourhood(c) == Eigen::Vector3i(3, 4, 2));
    // 3 and 4 are 0.5 away, 2 and 5 are 1.5 away: the earlier sample first.
    const Eigen::Vector2d mid(3.5, 0.0);
    CHECK(three.neighbourhood(mid) == Eigen::Vector3i(3, 4, 2));
    const Eigen::Vector2d far_left(-100.0, 0.0);
    CHECK(three.neighbourhood(far_left) == Eigen::Vector3i(0, 1, 2));
    // Only the neighbourhood gets weight.
    const Eigen::VectorXd w = three.weights(c);
    CHECK(w(0) == 0.0);
    CHECK(w(5) == 0.0);
    CHECK(w(9) == 0.0);
    CHECK(std::abs(w(2) + w(3) + w(4) - 1.0) < 1e-12);
}

TEST_CASE("local kriging merges coincident samples as the exact kriging does") {
    Eigen::MatrixXd x = uniform(30, 2, 21, 0.0, 1.0);
    x.row(29) = x.row(4);  // a duplicate of sample 4
    const VariogramModel model = VariogramModel::stable(1.5, 0.01, 1.0, 0.6);
    const KrigingOptions o = local_test_options(TrendFit::OLS, true);
    const Kriging exact = Kriging::build(x, model, o);
    const LocalKriging all = LocalKriging::build(x, model, o, 100);
    CHECK(all.status().duplicates_merged == 1);
    CHECK(all.neighbours() == 29);
    const Eigen::Vector2d c(0.3, 0.6);
    CHECK((exact.weights(c) - all.weights(c)).cwiseAbs().maxCoeff() < 1e-9);
    const LocalKriging few = LocalKriging::build(x, model, local_test_options(TrendFit::OLS, false), 8);
    const Eigen::VectorXd w = few.weights(x.row(4).transpose());
    CHECK(std::abs(w(4) - 0.5) < 1e-9);
    CHECK(std::abs(w(29) - 0.5) < 1e-9);
}

TEST_CASE("local kriging refuses bad input") {
    const Eigen::MatrixXd x = uniform(10, 2, 3, 0.0, 1.0);
    const VariogramModel model = VariogramModel::stable(1.0, 0.0, 1.0, 1.0);
    CHECK_THROWS_AS(LocalKriging::build(x, model, {}, 0), mocapdb::InvalidArgument);
    VariogramModel zero = model;
    zero.sill = 0.0;
    CHECK_THROWS_AS(LocalKriging::build(x, zero, {}, 5), mocapdb::InvalidArgument);
    const LocalKriging lk = LocalKriging::build(x, model, {}, 5);
    CHECK_THROWS_AS(lk.weights(Eigen::Vector3d(0.0, 0.0, 0.0)), mocapdb::InvalidArgument);
    CHECK_THROWS_AS(lk.estimate_batch(Eigen::MatrixXd::Zero(2, 3)), mocapdb::InvalidArgument);
}

// gstat's krige(..., nmax = k) on the Meuse data (tests/data/gstat_local/make_meuse_local_reference.R):
// ordinary and universal kriging, the trend fitted in each neighbourhood.
TEST_CASE("local kriging matches gstat's nmax on the Meuse data") {
    const auto data_path = mocapdb::test::reference_dir() / "gstat" / "meuse_logzinc.csv";
    MOCAPDB_REQUIRE_SHARED(data_path);
    const auto data = read_csv(data_path);
    const auto ref = read_csv(mocapdb::test::test_data_dir() / "gstat_local" / "meuse_local_kriging.csv");
    const Eigen::MatrixXd coords = data.matrix({"x", "y"});
    const Eigen::VectorXd values = data.matrix({"logzinc"}).col(0);
    const auto model_of = [](const std::string& name) {
        if (name == "sph") return VariogramModel::spherical(0.05, 0.55, 900);
        if (name == "stable_p1") return VariogramModel::stable(1.0, 0.05, 0.55, 400);
        return VariogramModel::stable(2.0, 0.05, 0.55, 600);
    };
    std::size_t compared = 0;
    for (const std::string name : {"sph", "stable_p1", "stable_p2"}) {
        for (const int k : {10, 30}) {
            std::vector<std::size_t> rows;
            for (const std::size_t r : ref.select("model", name))
                if (static_cast<int>(ref.number(r, "nmax")) == k) rows.push_back(r);
            REQUIRE(rows.size() == 10);
            const Eigen::MatrixXd q = ref.matrix({"x", "y"}, rows);
            for (const TrendKind trend : {TrendKind::None, TrendKind::Linear}) {
                KrigingOptions o;
                o.trend = trend;
                o.trend_fit = TrendFit::GLS;
                const LocalKriging lk = LocalKriging::build(coords, model_of(name), o, k);
                const KrigingBatch b = lk.estimate_batch(q);
                const Eigen::VectorXd pred = b.weights.transpose() * values;
                const std::string pc = trend == TrendKind::None ? "ok_pred" : "uk_pred";
                const std::string vc = trend == TrendKind::None ? "ok_var" : "uk_var";
                for (std::size_t j = 0; j < rows.size(); ++j) {
                    const auto qi = static_cast<Eigen::Index>(j);
                    INFO(name << " nmax " << k << " " << pc << " query " << j << ": ours " << pred(qi) << " gstat "
                              << ref.number(rows[j], pc) << "; var ours " << b.variance(qi) << " gstat "
                              << ref.number(rows[j], vc));
                    CHECK(mocapdb::test::rel_err(pred(qi), ref.number(rows[j], pc)) < 1e-8);
                    CHECK(mocapdb::test::rel_err(b.variance(qi), ref.number(rows[j], vc)) < 1e-8);
                    ++compared;
                }
            }
        }
    }
    CHECK(compared == 120);
}
