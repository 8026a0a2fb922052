// Variogram fitting: gstat's fit as a sanity range (its README), recovery of known variograms from
// simulated Gaussian random fields, and exponent selection by closed-form leave-one-out.
#include <cmath>
#include <random>

#include <Eigen/Cholesky>
#include <catch2/catch.hpp>

#include "csv_fixture.hpp"
#include "mocapdb/core/error.hpp"
#include "mocapdb/kriging/variogram_fit.hpp"
#include "shared_data.hpp"

using namespace mocapdb::kriging;
using mocapdb::test::read_csv;
using mocapdb::test::reference_dir;

namespace {

ExperimentalVariogram gstat_bins(const mocapdb::test::CsvTable& bins) {
    ExperimentalVariogram ev;
    const auto n = static_cast<Eigen::Index>(bins.rows.size());
    ev.gamma.resize(n);
    ev.dist.resize(n);
    ev.center.resize(n);
    ev.width = 160.0;
    ev.cutoff = 1600.0;
    for (Eigen::Index u = 0; u < n; ++u) {
        const auto r = static_cast<std::size_t>(u);
        ev.npairs.push_back(static_cast<std::size_t>(bins.number(r, "np")));
        ev.dist(u) = bins.number(r, "dist");
        ev.gamma(u) = bins.number(r, "gamma_cressie_gstat");
        ev.center(u) = 160.0 * (static_cast<double>(u) + 0.5);
    }
    return ev;
}

// Points uniform in [0, L]^2 and M realizations of a zero-mean Gaussian field with the given model.
Eigen::MatrixXd simulate_fields(const Eigen::MatrixXd& pts, const VariogramModel& model, int realizations,
                                unsigned seed) {
    const Eigen::Index n = pts.rows();
    Eigen::MatrixXd cov(n, n);
    for (Eigen::Index j = 0; j < n; ++j) {
        for (Eigen::Index i = 0; i < n; ++i) cov(i, j) = model.covariance((pts.row(i) - pts.row(j)).norm());
    }
    cov.diagonal().array() += 1e-10;
    Eigen::LLT<Eigen::MatrixXd> llt(cov);
    REQUIRE(llt.info() == Eigen::Success);
    std::mt19937 rng(seed);
    std::normal_distribution<double> nd(0.0, 1.0);
    Eigen::MatrixXd z(n, realizations);
    for (Eigen::Index k = 0; k < z.size(); ++k) z.data()[k] = nd(rng);
    return llt.matrixL() * z;
}

}  // namespace

TEST_CASE("Cressie-weighted fit of the Meuse variogram is in gstat's range", "[kriging][gstat][fit]") {
    const auto dir = reference_dir() / "gstat";
    MOCAPDB_REQUIRE_SHARED(dir);
    const auto bins = read_csv(dir / "meuse_variogram_bins.csv");
    const auto ref = read_csv(dir / "meuse_fit_cressie_weights.csv");
    const ExperimentalVariogram ev = gstat_bins(bins);  // gstat's own robust estimates, as gstat fitted them
    for (const std::string name : {"Sph", "Exc"}) {
        const auto row = ref.select("model", name).at(0);
        const bool sph = name == "Sph";
        const VariogramModel start =
            sph ? VariogramModel::spherical(0.1, 0.5, 800) : VariogramModel::stable(1.2, 0.1, 0.5, 400);
        const VariogramModel gstat = sph ? VariogramModel::spherical(ref.number(row, "nugget"), ref.number(row, "psill"),
                                                                     ref.number(row, "range"))
                                         : VariogramModel::stable(1.2, ref.number(row, "nugget"),
                                                                  ref.number(row, "psill"), ref.number(row, "range"));
        // (a) gstat's convention: weights from the start model, held fixed.
        VariogramFitOptions fixed;
        fixed.weighting = FitWeighting::CressieFixed;
        fixed.start = start;
        const VariogramFit ff = fit_variogram(ev, start.family, start.exponent, fixed);
        const double obj_gstat_fixed = fit_objective(ev, gstat, fixed);
        // (b) the true Cressie objective, weights re-evaluated.
        VariogramFitOptions full;
        const VariogramFit fc = fit_variogram(ev, start.family, start.exponent, full);
        const double obj_gstat_full = fit_objective(ev, gstat, full);
        INFO(name << " gstat: " << gstat.to_string() << " SSErr " << ref.number(row, "sserr"));
        INFO("fixed-start weights: " << ff.model.to_string() << " objective " << ff.objective
                                     << " (gstat's parameters score " << obj_gstat_fixed << ")");
        INFO("re-evaluated weights: " << fc.model.to_string() << " objective " << fc.objective
                                      << " (gstat's parameters score " << obj_gstat_full << ")");
        // Our minimizer is at least as good as gstat's answer on either objective.
        CHECK(ff.objective <= obj_gstat_fixed * (1.0 + 1e-9));
        CHECK(fc.objective <= obj_gstat_full * (1.0 + 1e-9));
        // Sanity range: the total sill and range within 25% of gstat's.
        CHECK(std::abs(ff.model.total_sill() - gstat.total_sill()) <= 0.25 * gstat.total_sill());
        CHECK(std::abs(ff.model.range - gstat.range) <= 0.25 * gstat.range);
        CHECK(std::abs(fc.model.total_sill() - gstat.total_sill()) <= 0.25 * gstat.total_sill());
        CHECK(std::abs(fc.model.range - gstat.range) <= 0.25 * gstat.range);
        WARN(name << ": gstat " << gstat.to_string() << " | fixed-start " << ff.model.to_string() << " obj "
                  << ff.objective << " vs gstat " << obj_gstat_fixed << " (gstat SSErr " << ref.number(row, "sserr")
                  << ") | re-evaluated " << fc.model.to_string() << " obj " << fc.objective);
    }
}

TEST_CASE("Known variograms are recovered from simulated Gaussian fields", "[kriging][fit][simulation]") {
    // 300 points uniform in [0, 10]^2; 40 independent realizations; the Cressie estimates are averaged
    // bin by bin over the realizations and the model is fitted with the true Cressie objective.
    // Stated tolerances: pooled estimates within 10% of the true gamma at the bin distances; fitted
    // total sill within 10%, range within 20%, nugget within 0.1 (absolute, sill 1).
    std::mt19937 rng(12345);
    std::uniform_real_distribution<double> ud(0.0, 10.0);
    const Eigen::Index n = 300;
    Eigen::MatrixXd pts(n, 2);
    for (Eigen::Index k = 0; k < pts.size(); ++k) pts.data()[k] = ud(rng);
    const std::vector<VariogramModel> truths = {VariogramModel::spherical(0.1, 1.0, 4.0),
                                                VariogramModel::stable(1.0, 0.0, 1.0, 1.5),
                                                VariogramModel::stable(2.0, 0.05, 1.0, 2.0)};
    unsigned seed = 7;
    for (const auto& truth : truths) {
        const int realizations = 40;
        const Eigen::MatrixXd z = simulate_fields(pts, truth, realizations, seed++);
        VariogramOptions vo;
        vo.bins = 12;
        ExperimentalVariogram pooled;
        for (int r = 0; r < realizations; ++r) {
            const ExperimentalVariogram ev = experimental_variogram_scalar(pts, z.col(r), vo);
            if (r == 0) {
                pooled = ev;
            } else {
                pooled.gamma += ev.gamma;
            }
        }
        pooled.gamma /= realizations;
        double worst = 0.0;
        for (Eigen::Index u = 0; u < pooled.gamma.size(); ++u) {
            const double g = truth(pooled.dist(u));
            worst = std::max(worst, std::abs(pooled.gamma(u) - g) / g);
        }
        const VariogramFit fit = fit_variogram(pooled, truth.family, truth.exponent);
        INFO("truth " << truth.to_string() << " fitted " << fit.model.to_string() << " objective " << fit.objective
                      << " worst bin rel error " << worst);
        CHECK(worst <= 0.10);
        CHECK(fit.converged);
        CHECK(std::abs(fit.model.total_sill() - truth.total_sill()) <= 0.10 * truth.total_sill());
        CHECK(std::abs(fit.model.range - truth.range) <= 0.20 * truth.range);
        CHECK(std::abs(fit.model.nugget - truth.nugget) <= 0.10);
        WARN("recovery: truth " << truth.to_string() << " -> fitted " << fit.model.to_string()
                                << "; worst pooled-bin rel error " << worst);
    }
}

TEST_CASE("Exponent selection: closed-form LOO per candidate equals N refits", "[kriging][fit][loo]") {
    std::mt19937 rng(99);
    std::uniform_real_distribution<double> ud(0.0, 10.0);
    const Eigen::Index n = 60;
    Eigen::MatrixXd pts(n, 2);
    for (Eigen::Index k = 0; k < pts.size(); ++k) pts.data()[k] = ud(rng);
    const VariogramModel truth = VariogramModel::stable(1.5, 0.02, 1.0, 3.0);
    Eigen::MatrixXd z = simulate_fields(pts, truth, 1, 3);
    z.col(0) += 0.3 * pts.col(0) - 0.2 * pts.col(1);  // a linear trend
    for (TrendFit tf : {TrendFit::OLS, TrendFit::GLS}) {
        KrigingOptions ko;
        ko.trend = TrendKind::Linear;
        ko.trend_fit = tf;
        const TrendBasis basis = TrendBasis::build(pts, TrendKind::Linear);
        const OlsTrend trend = fit_trend_ols(basis, z);
        const ExperimentalVariogram ev = experimental_variogram_scalar(pts, trend.residuals.col(0));
        const ExponentSelection sel = select_exponent(ev, pts, z, ko);
        REQUIRE(sel.grid.size() == 11);
        CHECK(sel.grid.front() == 0.0);
        CHECK(sel.grid.back() == 2.0);
        for (Eigen::Index k = 0; k < sel.loo_mse.size(); ++k) {
            CHECK(sel.loo_mse(static_cast<Eigen::Index>(sel.best)) <= sel.loo_mse(k));
        }
        // Brute force for the chosen model: N refits without the sample.
        const VariogramModel& model = sel.model();
        double mse = 0.0;
        for (Eigen::Index i = 0; i < n; ++i) {
            Eigen::MatrixXd c(n - 1, 2);
            Eigen::VectorXd v(n - 1);
            for (Eigen::Index j = 0, r = 0; j < n; ++j) {
                if (j == i) continue;
                c.row(r) = pts.row(j);
                v(r) = tf == TrendFit::OLS ? trend.residuals(j, 0) : z(j, 0);
                ++r;
            }
            KrigingOptions kk = ko;
            if (tf == TrendFit::OLS) kk.trend = TrendKind::None;  // the paper: residuals of the full trend, OK
            const Kriging k = Kriging::build(c, model, kk);
            const double pred = k.weights(pts.row(i).transpose()).dot(v);
            const double obs = tf == TrendFit::OLS ? trend.residuals(i, 0) : z(i, 0);
            mse += (obs - pred) * (obs - pred);
        }
        mse /= static_cast<double>(n);
        const double closed = sel.loo_mse(static_cast<Eigen::Index>(sel.best));
        INFO(to_string(tf) << ": chosen p = " << sel.grid[sel.best] << " closed-form MSE " << closed << " brute force "
                           << mse);
        CHECK(std::abs(closed - mse) <= 1e-9 * mse);
    }
}

TEST_CASE("fit_variogram rejects bad arguments and flags degenerate input", "[kriging][fit]") {
    ExperimentalVariogram ev;
    ev.gamma = Eigen::VectorXd::Zero(3);
    ev.dist = Eigen::VectorXd::Constant(3, 1.0);
    ev.center = ev.dist;
    ev.npairs = {1, 2, 3};
    CHECK_THROWS_AS(fit_variogram(ev, VariogramFamily::Stable, 2.5), mocapdb::InvalidArgument);
    VariogramFitOptions o;
    o.weighting = FitWeighting::CressieFixed;
    CHECK_THROWS_AS(fit_variogram(ev, VariogramFamily::Stable, 1.0, o), mocapdb::InvalidArgument);
    const VariogramFit f = fit_variogram(ev, VariogramFamily::Spherical, 1.0);
    CHECK(f.status == FitStatus::Degenerate);
    CHECK(std::isfinite(f.model.range));
}
