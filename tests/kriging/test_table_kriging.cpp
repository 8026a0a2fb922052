// Table kriging as library steps (kriging/table_kriging.hpp, issue #17; `mocapdb variogram` / `krige`)
// on the Meuse data: the table, the residual variogram against gstat's pair counts and distances, the
// fits, and universal kriging at gstat's query points with its predictions and variances.
#include <catch2/catch.hpp>

#include <fstream>
#include <sstream>

#include "mocapdb/core/error.hpp"
#include "csv_fixture.hpp"
#include "mocapdb/kriging/table_kriging.hpp"
#include "shared_data.hpp"
#include "test_support.hpp"

using namespace mocapdb;
using namespace mocapdb::kriging;

namespace {

std::filesystem::path gstat_dir() { return test::reference_dir() / "gstat"; }

}  // namespace

TEST_CASE("table kriging on Meuse: residual variogram, fits and universal kriging match gstat", "[kriging][shared]") {
    MOCAPDB_REQUIRE_SHARED(gstat_dir() / "meuse_logzinc.csv");
    const ScalarTable t = read_scalar_table(gstat_dir() / "meuse_logzinc.csv", {"x", "y"}, "logzinc", false);
    REQUIRE(t.coords.rows() == 155);
    REQUIRE(t.coords.cols() == 2);
    CHECK_FALSE(t.scaling.has_value());

    VariogramOptions vo;
    vo.bins = 10;
    vo.cutoff = 1600;
    const ExperimentalVariogram ev = table_variogram(t, TrendKind::Linear, vo);
    const Eigen::MatrixXd ref = test::read_csv(gstat_dir() / "meuse_residual_variogram_bins.csv").matrix({"np", "dist"});
    REQUIRE(ev.bins() == 10);
    for (int u = 0; u < ev.bins(); ++u) {
        CHECK(static_cast<double>(ev.npairs[static_cast<std::size_t>(u)]) == ref(u, 0));
        CHECK(ev.dist(u) == Approx(ref(u, 1)).epsilon(1e-9));
    }

    KrigingOptions ko;
    ko.trend = TrendKind::Linear;
    ko.trend_fit = TrendFit::GLS;  // gstat's universal kriging
    VariogramFitRequest by_loo;
    by_loo.by_loo = true;
    by_loo.grid = {0.0, 1.0, 2.0};
    const VariogramChoice chosen = fit_table_variogram(by_loo, ev, t, ko, VariogramFitOptions{});
    REQUIRE(chosen.selection.has_value());
    const Eigen::Index best = static_cast<Eigen::Index>(chosen.selection->best);
    CHECK(chosen.selection->loo_mse(best) == chosen.selection->loo_mse.minCoeff());
    CHECK(chosen.fit.model.paper_p() == chosen.selection->grid[chosen.selection->best]);
    VariogramFitRequest sph;
    const VariogramChoice fixed = fit_table_variogram(sph, ev, t, ko, VariogramFitOptions{});
    CHECK_FALSE(fixed.selection.has_value());
    CHECK(fixed.fit.model.family == VariogramFamily::Spherical);
    CHECK(fixed.fit.model.sill > 0.0);

    // gstat's universal kriging with the fixed spherical model at its query points.
    const auto q = test::read_csv(gstat_dir() / "meuse_kriging_fixed_models.csv");
    const auto rows = q.select("model", "sph");
    REQUIRE(!rows.empty());
    const Eigen::MatrixXd queries = q.matrix({"x", "y"}, rows);
    const VariogramModel model = VariogramModel::spherical(0.05, 0.55, 900);
    const TableKriging uk = krige_table(t, model, ko, queries, true);
    for (std::size_t k = 0; k < rows.size(); ++k) {
        const auto i = static_cast<Eigen::Index>(k);
        CHECK(uk.prediction(i) == Approx(q.number(rows[k], "uk_pred")).epsilon(1e-6));
        CHECK(uk.batch.variance(i) == Approx(q.number(rows[k], "uk_var")).epsilon(1e-6));
    }
    REQUIRE(uk.loo.has_value());
    CHECK(uk.loo->prediction.rows() == 155);
    CHECK(uk.loo->mse > 0.0);
    CHECK(uk.status.duplicates_merged == 0);
}

TEST_CASE("table kriging: normalized coordinates scale the queries alike, too few rows refused", "[kriging][shared]") {
    MOCAPDB_REQUIRE_SHARED(gstat_dir() / "meuse_logzinc.csv");
    const ScalarTable t = read_scalar_table(gstat_dir() / "meuse_logzinc.csv", {"x", "y"}, "logzinc", true);
    REQUIRE(t.scaling.has_value());
    CHECK(t.coords.colwise().mean().norm() < 1e-9);
    // Kriging without nugget interpolates exactly: at the table's own (unscaled) points it returns the values.
    const ScalarTable raw = read_scalar_table(gstat_dir() / "meuse_logzinc.csv", {"x", "y"}, "logzinc", false);
    const TableKriging k = krige_table(t, VariogramModel::spherical(0.0, 0.6, 1.0), KrigingOptions{}, raw.coords.topRows(5), false);
    for (Eigen::Index i = 0; i < 5; ++i) CHECK(k.prediction(i) == Approx(t.values(i)).epsilon(1e-8));
    CHECK_FALSE(k.loo.has_value());

    test::TempDir dir("table-kriging");
    const auto one = dir / "one.csv";
    std::ofstream(one) << "x,y,v\n1,2,3\n";
    CHECK_THROWS_AS(read_scalar_table(one, {"x", "y"}, "v", false), InvalidArgument);
}
