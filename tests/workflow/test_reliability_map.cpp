// The reliability map in-process (workflow/reliability_map.hpp, issue #17): rho over a slice of the
// walks' turn × speed plane is 1 at a sample and lower far outside the samples; the grid's layout.
#include <catch2/catch.hpp>

#include "mocapdb/store/database.hpp"
#include "mocapdb/workflow/load_model.hpp"
#include "mocapdb/workflow/reliability_map.hpp"
#include "walk_database.hpp"

using namespace mocapdb;
using namespace mocapdb::test;

namespace {

const WalkDatabase& reliability_map_walks() {
    static const WalkDatabase w = make_walk_database("workflow_reliability", WalkStage::Compressed);
    return w;
}

}  // namespace

TEST_CASE("workflow: reliability_map is 1 at a sample and falls off outside the samples", "[workflow][shared]") {
    MOCAPDB_REQUIRE_SHARED(datasets_dir() / "cmu-asfamc");
    const WalkDatabase& w = reliability_map_walks();
    const Database db(w.path);
    // Exact kriging (the nugget not filtered), so that rho is 1 at the samples.
    synthesis::SynthesisOptions exact;
    exact.kriging.filter_nugget = false;
    const auto model = workflow::load_motion_model(db, "walks", exact);
    const MatX& samples = model->sample_parameters();
    REQUIRE(samples.cols() == 2);

    // The grid starts at sample 0 (cell 0 is exactly its parameters) and reaches far beyond the
    // samples' turn and speed.
    const double turn_span = samples.col(0).maxCoeff() - samples.col(0).minCoeff();
    const double speed_span = samples.col(1).maxCoeff() - samples.col(1).minCoeff();
    const workflow::SliceAxis gx{0, samples(0, 0), samples.col(0).maxCoeff() + 4.0 * turn_span, 9};
    const workflow::SliceAxis gy{1, samples(0, 1), samples.col(1).maxCoeff() + 4.0 * speed_span, 7};
    const VecX base = samples.colwise().mean().transpose();
    const workflow::ReliabilityMap m = workflow::reliability_map(*model, gx, gy, base);

    REQUIRE(m.queries.rows() == 63);
    REQUIRE(m.queries.cols() == 2);
    REQUIRE(m.rho.size() == 63);
    REQUIRE(m.values.rows() == 7);
    REQUIRE(m.values.cols() == 9);
    CHECK(m.queries(0, 0) == samples(0, 0));
    CHECK(m.queries(0, 1) == samples(0, 1));
    CHECK(m.queries(8, 0) == Approx(gx.hi));  // x fastest
    CHECK(m.queries(9, 1) == Approx(gy.at(1)));
    for (Eigen::Index j = 0; j < 7; ++j)
        for (Eigen::Index i = 0; i < 9; ++i) CHECK(m.values(j, i) == m.rho(j * 9 + i));
    // Each cell's rho is the model's at that point.
    CHECK(m.rho(20) == Approx(model->reliability(m.queries.row(20).transpose())).margin(1e-12));

    CHECK(m.rho(0) == Approx(1.0).margin(1e-9));  // at a sample
    CHECK(m.rho(62) < 0.5);                       // far beyond every sample in both parameters
    CHECK(m.rho(62) < m.rho(0));
    CHECK((m.rho.array() >= 0.0).all());
    CHECK((m.rho.array() <= 1.0 + 1e-12).all());
    const double trusted = static_cast<double>((m.rho.array() >= workflow::kTrustedReliability).count()) / 63.0;
    CHECK(m.fraction_trusted == Approx(trusted));
    CHECK(m.fraction_trusted > 0.0);
    CHECK(m.fraction_trusted < 1.0);
}
