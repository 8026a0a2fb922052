// Oracle tests: the engine against R gstat 2.1.0 results in ../shared/reference/gstat (README there).
#include <algorithm>
#include <cmath>

#include <catch2/catch.hpp>

#include "csv_fixture.hpp"
#include "mocapdb/kriging/kriging.hpp"
#include "mocapdb/kriging/trend.hpp"
#include "mocapdb/kriging/variogram.hpp"
#include "shared_data.hpp"

using namespace mocapdb::kriging;
using mocapdb::test::read_csv;
using mocapdb::test::reference_dir;
using mocapdb::test::rel_err;

namespace {

std::filesystem::path gstat_dir() { return reference_dir() / "gstat"; }

// The fixed models of make_meuse_reference.R / make_synth3d_reference.R.
VariogramModel meuse_model(const std::string& name) {
    if (name == "sph") return VariogramModel::spherical(0.05, 0.55, 900);
    if (name == "stable_p1") return VariogramModel::stable(1.0, 0.05, 0.55, 400);
    if (name == "stable_p15") return VariogramModel::stable(1.5, 0.05, 0.55, 500);
    if (name == "stable_p2") return VariogramModel::stable(2.0, 0.05, 0.55, 600);
    throw std::runtime_error("unknown model " + name);
}

VariogramModel synth_model(const std::string& name) {
    if (name == "sph") return VariogramModel::spherical(0.01, 2.0, 6);
    if (name == "stable_p08") return VariogramModel::stable(0.8, 0.01, 2.0, 3);
    if (name == "stable_p2") return VariogramModel::stable(2.0, 0.0, 2.0, 3);
    throw std::runtime_error("unknown model " + name);
}

struct Residuals {
    double pred = 0.0;
    double var = 0.0;
};

Residuals compare_fixed_models(const std::filesystem::path& data_csv, const std::filesystem::path& result_csv,
                               const std::vector<std::string>& coord_names, const std::string& value_name,
                               const std::vector<std::string>& models, VariogramModel (*model_of)(const std::string&)) {
    const auto data = read_csv(data_csv);
    const auto res = read_csv(result_csv);
    const Eigen::MatrixXd coords = data.matrix(coord_names);
    const Eigen::VectorXd values = data.matrix({value_name}).col(0);
    Residuals worst;
    for (const auto& name : models) {
        const auto rows = res.select("model", name);
        REQUIRE(!rows.empty());
        const Eigen::MatrixXd queries = res.matrix(coord_names, rows);
        for (TrendKind trend : {TrendKind::None, TrendKind::Linear}) {
            KrigingOptions opt;
            opt.trend = trend;
            opt.trend_fit = TrendFit::GLS;  // gstat's universal kriging
            const Kriging k = Kriging::build(coords, model_of(name), opt);
            CHECK(k.status().exact());
            const KrigingBatch b = k.estimate_batch(queries);
            const Eigen::VectorXd pred = b.weights.transpose() * values;
            const std::string pc = trend == TrendKind::None ? "ok_pred" : "uk_pred";
            const std::string vc = trend == TrendKind::None ? "ok_var" : "uk_var";
            for (std::size_t q = 0; q < rows.size(); ++q) {
                const auto qi = static_cast<Eigen::Index>(q);
                const double ep = rel_err(pred(qi), res.number(rows[q], pc));
                const double ev = rel_err(b.variance(qi), res.number(rows[q], vc));
                INFO(result_csv.filename().string() << " model " << name << " " << pc << " query " << q << ": ours "
                                                    << pred(qi) << " gstat " << res.number(rows[q], pc)
                                                    << " rel " << ep << "; var ours " << b.variance(qi)
                                                    << " gstat " << res.number(rows[q], vc) << " rel " << ev
                                                    << " rcond " << k.status().rcond);
                CHECK(ep <= 1e-8);
                CHECK(ev <= 1e-8);
                worst.pred = std::max(worst.pred, ep);
                worst.var = std::max(worst.var, ev);
            }
        }
    }
    return worst;
}

}  // namespace

TEST_CASE("Meuse experimental variogram matches gstat bins", "[kriging][gstat][variogram]") {
    MOCAPDB_REQUIRE_SHARED(gstat_dir());
    const auto data = read_csv(gstat_dir() / "meuse_logzinc.csv");
    const auto ref = read_csv(gstat_dir() / "meuse_variogram_bins.csv");
    const Eigen::MatrixXd coords = data.matrix({"x", "y"});
    const Eigen::VectorXd z = data.matrix({"logzinc"}).col(0);
    REQUIRE(coords.rows() == 155);

    VariogramOptions vo;
    vo.bins = 10;
    vo.cutoff = 1600;
    vo.estimator = VariogramEstimator::Matheron;
    const ExperimentalVariogram mat = experimental_variogram_scalar(coords, z, vo);
    vo.estimator = VariogramEstimator::Cressie;
    const ExperimentalVariogram cre = experimental_variogram_scalar(coords, z, vo);
    REQUIRE(ref.rows.size() == 10);
    double worst_dist = 0.0, worst_mat = 0.0, worst_cre = 0.0;
    for (std::size_t u = 0; u < 10; ++u) {
        const auto ui = static_cast<Eigen::Index>(u);
        const auto np = static_cast<std::size_t>(ref.number(u, "np"));
        INFO("bin " << u + 1 << " np ours " << cre.npairs[u] << " gstat " << np);
        CHECK(mat.npairs[u] == np);
        CHECK(cre.npairs[u] == np);
        const double ed = rel_err(cre.dist(ui), ref.number(u, "dist"));
        const double em = rel_err(mat.gamma(ui), ref.number(u, "gamma_matheron"));
        const double ec = rel_err(cre.gamma(ui), cressie_gstat_to_three_term(ref.number(u, "gamma_cressie_gstat"), np));
        INFO("dist rel " << ed << " matheron rel " << em << " cressie rel " << ec);
        CHECK(ed <= 1e-12);
        CHECK(em <= 1e-10);
        CHECK(ec <= 1e-10);
        worst_dist = std::max(worst_dist, ed);
        worst_mat = std::max(worst_mat, em);
        worst_cre = std::max(worst_cre, ec);
    }
    WARN("Meuse bins: max rel dist " << worst_dist << ", Matheron " << worst_mat << ", Cressie (3-term) " << worst_cre);
}

TEST_CASE("Residual variograms of an OLS linear trend match gstat", "[kriging][gstat][variogram]") {
    MOCAPDB_REQUIRE_SHARED(gstat_dir());
    struct Case {
        const char* data;
        const char* bins;
        std::vector<std::string> coords;
        const char* value;
        double cutoff;
    };
    const std::vector<Case> cases = {
        {"meuse_logzinc.csv", "meuse_residual_variogram_bins.csv", {"x", "y"}, "logzinc", 1600.0},
        {"synth3d_points.csv", "synth3d_residual_variogram_bins.csv", {"x", "y", "z"}, "v", 6.0},
    };
    for (const auto& c : cases) {
        const auto data = read_csv(gstat_dir() / c.data);
        const auto ref = read_csv(gstat_dir() / c.bins);
        const Eigen::MatrixXd coords = data.matrix(c.coords);
        const Eigen::MatrixXd z = data.matrix({c.value});
        const TrendBasis basis = TrendBasis::build(coords, TrendKind::Linear);
        const OlsTrend fit = fit_trend_ols(basis, z);
        VariogramOptions vo;
        vo.bins = 10;
        vo.cutoff = c.cutoff;
        const ExperimentalVariogram ev = experimental_variogram_scalar(coords, fit.residuals.col(0), vo);
        double worst = 0.0;
        for (std::size_t u = 0; u < ref.rows.size(); ++u) {
            const auto np = static_cast<std::size_t>(ref.number(u, "np"));
            const auto ui = static_cast<Eigen::Index>(u);
            const double e = rel_err(ev.gamma(ui), cressie_gstat_to_three_term(ref.number(u, "gamma_cressie_gstat"), np));
            INFO(c.bins << " bin " << u + 1 << " np ours " << ev.npairs[u] << " gstat " << np << " gamma rel " << e);
            CHECK(ev.npairs[u] == np);
            CHECK(rel_err(ev.dist(ui), ref.number(u, "dist")) <= 1e-12);
            CHECK(e <= 1e-10);
            worst = std::max(worst, e);
        }
        WARN(c.bins << ": max rel residual-variogram error " << worst);
    }
}

TEST_CASE("Fixed-model ordinary and universal kriging match gstat (Meuse)", "[kriging][gstat]") {
    MOCAPDB_REQUIRE_SHARED(gstat_dir());
    const Residuals r = compare_fixed_models(gstat_dir() / "meuse_logzinc.csv", gstat_dir() / "meuse_kriging_fixed_models.csv",
                                             {"x", "y"}, "logzinc", {"sph", "stable_p1", "stable_p15", "stable_p2"},
                                             &meuse_model);
    WARN("Meuse OK/UK: max rel prediction error " << r.pred << ", variance " << r.var);
}

TEST_CASE("Fixed-model ordinary and universal kriging match gstat (3-D synthetic)", "[kriging][gstat]") {
    MOCAPDB_REQUIRE_SHARED(gstat_dir());
    const Residuals r = compare_fixed_models(gstat_dir() / "synth3d_points.csv", gstat_dir() / "synth3d_kriging_fixed_models.csv",
                                             {"x", "y", "z"}, "v", {"sph", "stable_p08", "stable_p2"}, &synth_model);
    WARN("synth3d OK/UK: max rel prediction error " << r.pred << ", variance " << r.var);
}

TEST_CASE("Closed-form leave-one-out universal kriging matches gstat krige.cv", "[kriging][gstat][loo]") {
    MOCAPDB_REQUIRE_SHARED(gstat_dir());
    const auto data = read_csv(gstat_dir() / "meuse_logzinc.csv");
    const auto ref = read_csv(gstat_dir() / "meuse_uk_loo_fixed_models.csv");
    const Eigen::MatrixXd coords = data.matrix({"x", "y"});
    const Eigen::MatrixXd z = data.matrix({"logzinc"});
    double worst_pred = 0.0, worst_var = 0.0, worst_res = 0.0, worst_z = 0.0;
    for (const std::string name : {"sph", "stable_p1", "stable_p15", "stable_p2"}) {
        KrigingOptions opt;
        opt.trend = TrendKind::Linear;
        opt.trend_fit = TrendFit::GLS;
        const Kriging k = Kriging::build(coords, meuse_model(name), opt);
        const LooResult loo = k.leave_one_out(z);
        const auto rows = ref.select("model", name);
        REQUIRE(rows.size() == 155);
        for (std::size_t r = 0; r < rows.size(); ++r) {
            const auto i = static_cast<Eigen::Index>(ref.number(rows[r], "idx")) - 1;
            const double ep = rel_err(loo.prediction(i, 0), ref.number(rows[r], "pred"));
            const double ev = rel_err(loo.variance(i), ref.number(rows[r], "var"));
            // Residuals can be near zero: compare them relative to the observed value's scale.
            const double er = std::abs(loo.residual(i, 0) - ref.number(rows[r], "residual")) /
                              std::max(std::abs(ref.number(rows[r], "residual")), 1e-3);
            const double ez = std::abs(loo.zscore(i, 0) - ref.number(rows[r], "zscore")) /
                              std::max(std::abs(ref.number(rows[r], "zscore")), 1e-3);
            INFO("model " << name << " idx " << i + 1 << " pred rel " << ep << " var rel " << ev << " residual rel "
                          << er << " zscore rel " << ez);
            CHECK(ep <= 1e-8);
            CHECK(ev <= 1e-8);
            CHECK(er <= 1e-8);
            CHECK(ez <= 1e-8);
            worst_pred = std::max(worst_pred, ep);
            worst_var = std::max(worst_var, ev);
            worst_res = std::max(worst_res, er);
            worst_z = std::max(worst_z, ez);
        }
    }
    WARN("Meuse UK LOO: max rel pred " << worst_pred << ", var " << worst_var << ", residual " << worst_res
                                       << ", zscore " << worst_z);
}
