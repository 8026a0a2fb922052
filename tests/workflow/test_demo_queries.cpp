// The demo's choices and measurements in-process (workflow/demo_queries.hpp, issue #17): points between
// samples and at the reach grid's cells, the least trusted point outside the samples on subject 16's
// walks, what measures a synthesized motion, where a procedural reach lands, and the padded map axes.
#include <catch2/catch.hpp>

#include <cmath>

#include "mocapdb/procedural/humanoid.hpp"
#include "mocapdb/store/database.hpp"
#include "mocapdb/workflow/demo_queries.hpp"
#include "mocapdb/workflow/load_model.hpp"
#include "mocapdb/workflow/reliability_map.hpp"
#include "walk_database.hpp"

using namespace mocapdb;
using namespace mocapdb::test;

namespace {

const WalkDatabase& demo_queries_walks() {
    static const WalkDatabase w = make_walk_database("workflow_demo_queries", WalkStage::Compressed);
    return w;
}

}  // namespace

TEST_CASE("workflow: demo points between samples and at the reach grid's cells", "[workflow]") {
    MatX samples(4, 2);
    samples << 0, 0, 1, 0, 0, 10, 1, 10;
    const std::vector<VecX> between = workflow::between_samples(samples, 4);
    REQUIRE(!between.empty());
    for (const VecX& c : between) {
        CHECK(workflow::inside_box(samples, c));
        for (Eigen::Index i = 0; i < samples.rows(); ++i) CHECK((samples.row(i).transpose() - c).norm() > 1e-9);
    }
    CHECK(workflow::between_samples(samples.topRows(1), 3).empty());
    VecX out(2);
    out << 2, 5;
    CHECK_FALSE(workflow::inside_box(samples, out));

    procedural::ReachGrid grid;  // angle -90..90 (5), height 60..160 (3)
    const std::vector<VecX> cells = workflow::reach_cell_centres(grid);
    REQUIRE(cells.size() == 5);
    CHECK(cells[0](0) == Approx(-67.5));
    CHECK(cells[0](1) == Approx(85.0));
    grid.height.count = 1;
    CHECK(workflow::reach_cell_centres(grid).empty());

    const std::vector<VecX> points{out};
    const workflow::SliceAxis x = workflow::padded_axis(samples, points, 0, 41);
    CHECK(x.axis == 0);
    CHECK(x.count == 41);
    CHECK(x.lo == Approx(-0.3));
    CHECK(x.hi == Approx(2.3));
}

TEST_CASE("workflow: the demo's outside point and measurement on subject 16's walks", "[workflow][shared]") {
    MOCAPDB_REQUIRE_SHARED(datasets_dir() / "cmu-asfamc");
    const WalkDatabase& w = demo_queries_walks();
    const Database db(w.path);
    const auto model = workflow::load_motion_model(db, "walks");
    const MatX& samples = model->sample_parameters();
    const VecX outside = workflow::least_trusted_outside(*model);
    CHECK_FALSE(workflow::inside_box(samples, outside));
    CHECK(model->reliability(outside) < model->reliability(workflow::samples_mean(*model)));
    // It differs from the samples' mean on exactly one axis.
    CHECK(((outside - workflow::samples_mean(*model)).array().abs() > 1e-12).count() == 1);

    const MotionSet& set = w.set.set;
    const workflow::DemoMeasurement m = workflow::choose_measurement(set, *model->skeleton());
    CHECK(m.kind == workflow::DemoMeasure::Extractors);
    CHECK(m.extractors.size() == 2);
    CHECK(m.extractor_names == set.parameter_source);
    // Measuring a captured clip gives its stored parameters back.
    const Clip clip = db.load_clip(set.samples[0].clip);
    const VecX measured = workflow::measure_synthesis(m, clip, set.parameter_names);
    REQUIRE(measured.size() == 2);
    CHECK(measured(0) == Approx(set.parameters(0, 0)).margin(1e-6));
    CHECK(measured(1) == Approx(set.parameters(0, 1)).margin(1e-6));

    const workflow::DemoMeasurement none = workflow::choose_measurement(MotionSet{}, *model->skeleton());
    CHECK(none.kind == workflow::DemoMeasure::None);  // no extractors, and a CMU skeleton has no humanoid hand
}

TEST_CASE("workflow: a procedural reach is measured where it lands", "[workflow]") {
    procedural::ReachGrid grid;
    procedural::apply_grid_specs(grid, {"angle=30", "height=110"});
    const procedural::ParametricSet reaches = procedural::generate_reach_set(grid);
    REQUIRE(reaches.clips.size() == 1);
    const VecX landed = workflow::measure_reach_target(reaches.clips[0], reaches.parameter_names);
    REQUIRE(landed.size() == 3);
    CHECK(landed(0) == Approx(30.0).margin(3.0));
    CHECK(landed(1) == Approx(110.0).margin(5.0));
    CHECK(workflow::measure_reach_target(reaches.clips[0], {"angle", "speed"}).size() == 0);

    MotionSet set;
    set.parameter_names = reaches.parameter_names;
    set.parameter_units = reaches.parameter_units;
    set.parameter_source = "csv:params.csv";
    const workflow::DemoMeasurement m = workflow::choose_measurement(set, *reaches.clips[0].skeleton);
    CHECK(m.kind == workflow::DemoMeasure::ReachTarget);
    CHECK(workflow::measure_synthesis(m, reaches.clips[0], set.parameter_names).size() == 3);
}
