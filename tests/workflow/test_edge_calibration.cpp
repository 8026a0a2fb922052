// rho's warning calibrated on a set (workflow/edge_calibration.hpp, issue #38 item 4): the threshold
// flags the share of misses asked for and no more than needed; probes lie inside the samples' box or
// beyond it on one axis; a miss is a measured parameter beyond its tolerance; compress stores the
// calibration and synthesis warnings use it.
#include <catch2/catch.hpp>

#include <cmath>

#include "mocapdb/core/error.hpp"
#include "mocapdb/store/database.hpp"
#include "mocapdb/workflow/edge_calibration.hpp"
#include "mocapdb/workflow/load_model.hpp"
#include "mocapdb/workflow/synthesis_warnings.hpp"
#include "walk_database.hpp"

using namespace mocapdb;
using namespace mocapdb::test;

namespace {

workflow::EdgeProbe probe(double ratio, double beyond, bool miss) {
    workflow::EdgeProbe p;
    p.variance_ratio = ratio;
    p.beyond_sd = beyond;
    p.rho = std::clamp(1.0 - ratio, 0.0, 1.0);
    p.miss = miss;
    p.inside = beyond == 0.0;
    return p;
}

/// A set of one numeric parameter x, samples at 0 .. n - 1.
MotionSet line_set(int n) {
    MotionSet set;
    set.parameter_names = {"x"};
    set.parameter_units = {""};
    set.parameters = VecX::LinSpaced(n, 0.0, n - 1.0);
    return set;
}

/// The probes' requests on the line: the misses at every 4th position, the hits between them, so that
/// no probe's five nearest others hold more than two misses (the vote rule cannot find the misses).
void spread(std::vector<workflow::EdgeProbe>& probes) {
    int miss_at = 0, hit_at = 1;
    for (workflow::EdgeProbe& p : probes) {
        int& at = p.miss ? miss_at : hit_at;
        p.requested = VecX::Constant(1, at);
        at += p.miss ? 4 : (at % 4 == 3 ? 2 : 1);
    }
}

const WalkDatabase& edge_walks() {
    static const WalkDatabase w = make_walk_database("workflow_edge", WalkStage::Compressed);
    return w;
}

}  // namespace

TEST_CASE("edge calibration: the variance rule keeps false alarms inside, the distance rule finds the misses",
          "[workflow]") {
    std::vector<workflow::EdgeProbe> probes;
    // Twenty hits inside at ratios 0.05 .. 1.00; two misses inside at 1.2 and 0.3; eight misses beyond
    // at 0.1 .. 0.8 SD (ratios 0.5); ten hits beyond at 0.05 SD.
    for (int k = 1; k <= 20; ++k) probes.push_back(probe(0.05 * k, 0.0, false));
    probes.push_back(probe(1.2, 0.0, true));
    probes.push_back(probe(0.3, 0.0, true));
    for (int k = 1; k <= 8; ++k) probes.push_back(probe(0.5, 0.1 * k, true));
    for (int k = 0; k < 10; ++k) probes.push_back(probe(0.2, 0.05, false));
    spread(probes);
    const MotionSet set = line_set(40);
    workflow::EdgeCalibrationOptions o;
    o.false_alarms = 0.05;  // floor(0.05 x 20) = 1 hit inside may lie above the variance threshold
    o.detection = 0.9;      // ceil(0.9 x 10) = 9 misses
    const synthesis::EdgeWarning w = workflow::calibrate_edge_warning(probes, set, o);
    CHECK(w.variance_ratio == Approx(0.95));  // the 19th hit: only 1.00 above
    CHECK(w.misses == 10);
    CHECK(w.probes == 40);
    // The variance rule flags the miss at 1.2; eight more from the beyond misses: all of them, so the
    // distance threshold lies just below the nearest (0.1 SD), above the beyond hits' 0.05.
    CHECK(w.beyond_sd < 0.1);
    CHECK(w.beyond_sd > 0.05);
    CHECK(w.votes == 0);  // spread out, the misses have no missing neighbours to vote
    CHECK(w.probe_requests.size() == 0);
    CHECK(w.detection == Approx(0.9));     // the inside miss at 0.3 is left
    CHECK(w.false_alarms == Approx(0.05));  // the hit at 1.00
    const workflow::FlagRates r = workflow::flag_rates(probes, w, set);
    CHECK(r.flagged_misses == 9);
    CHECK(r.inside_hits == 20);
    CHECK(r.flagged_inside_hits == 1);

    o.detection = 0.5;  // 5 misses: the variance rule's one and the four furthest beyond
    const synthesis::EdgeWarning half = workflow::calibrate_edge_warning(probes, set, o);
    CHECK(half.beyond_sd < 0.5);
    CHECK(half.beyond_sd > 0.4);
    CHECK(workflow::flag_rates(probes, half, set).flagged_misses == 5);

    o.detection = 1.0;  // the inside miss at 0.3 cannot be reached by distance: everything beyond is flagged
    const synthesis::EdgeWarning all = workflow::calibrate_edge_warning(probes, set, o);
    CHECK(all.beyond_sd == 0.0);
    CHECK(all.detection == Approx(0.9));
    CHECK(all.false_alarms == Approx(0.05));  // the distance rule never flags inside the box
}

TEST_CASE("edge calibration: without misses only what lies beyond every probe is flagged", "[workflow]") {
    std::vector<workflow::EdgeProbe> probes{probe(0.2, 0.0, false), probe(0.7, 0.0, false), probe(1.3, 0.4, false)};
    spread(probes);
    const MotionSet set = line_set(3);
    workflow::EdgeCalibrationOptions o;
    o.false_alarms = 0.0;
    const synthesis::EdgeWarning w = workflow::calibrate_edge_warning(probes, set, o);
    CHECK(w.variance_ratio == 0.7);
    CHECK(w.beyond_sd == o.shell_sd);
    CHECK(w.misses == 0);
    CHECK(w.detection == 1.0);
    CHECK(w.false_alarms == 0.0);
    CHECK(w.flags(0.5, 1.5 * o.shell_sd, 0));
    CHECK_FALSE(w.flags(0.5, 0.5 * o.shell_sd, 5));  // no vote rule
}

TEST_CASE("edge calibration: misses together inside the box are found by the votes of their neighbours",
          "[workflow]") {
    // 100 probes inside on a line: hits at 0 .. 79 with variance ratios spread over [0, 1), misses at
    // 80 .. 99 whose ratios are the hits' (no variance threshold tells them apart).
    std::vector<workflow::EdgeProbe> probes;
    for (int k = 0; k < 100; ++k) {
        probes.push_back(probe((k * 37 % 80) / 80.0, 0.0, k >= 80));
        probes.back().requested = VecX::Constant(1, k);
    }
    const MotionSet set = line_set(100);
    workflow::EdgeCalibrationOptions o;  // 5 neighbours; floor(0.05 x 80) = 4 false alarms allowed
    const synthesis::EdgeWarning w = workflow::calibrate_edge_warning(probes, set, o);
    // Judged by its five nearest others, every miss has at least 2 missing neighbours (the miss at 80:
    // 81, 82, perhaps 83), the hits at 78 and 79 at most 2 and 3 and the hits below them none: a vote of
    // 2 finds every miss at 2 false alarms, within the 4 allowed.
    REQUIRE(w.votes > 0);
    CHECK(w.neighbours == 5);
    CHECK(w.votes >= 2);
    CHECK(w.probe_requests.rows() == 100);
    CHECK(w.probe_missed.size() == 100);
    CHECK(w.detection >= 0.95);
    CHECK(w.false_alarms <= 0.05);
    // A new request among the misses is flagged, one among the hits is not.
    CHECK(workflow::nearby_misses(w, set, VecX::Constant(1, 90.5)) == 5);
    CHECK(workflow::nearby_misses(w, set, VecX::Constant(1, 10.5)) == 0);
    CHECK(w.flags(0.0, 0.0, workflow::nearby_misses(w, set, VecX::Constant(1, 90.5))));
    CHECK_FALSE(w.flags(0.0, 0.0, workflow::nearby_misses(w, set, VecX::Constant(1, 10.5))));
    // Leaving a probe out: the miss at 99 sees 94 .. 98.
    CHECK(workflow::nearby_misses(w, set, VecX::Constant(1, 99.0), std::size_t{99}) == 5);
    CHECK_THROWS_AS(workflow::nearby_misses(w, set, VecX::Constant(2, 1.0)), InvalidArgument);
}

TEST_CASE("edge calibration: nearby misses prefer requests of the same level", "[workflow]") {
    MotionSet set;
    set.parameter_names = {"x", "style"};
    set.parameter_units = {"", ""};
    set.parameters = MatX(4, 2);
    set.parameters << 0, 0, 1, 1, 2, 0, 3, 1;
    set.parameter_levels = {{}, {"happy", "sad"}};
    synthesis::EdgeWarning w;
    w.neighbours = 3;
    w.votes = 2;
    w.probes = 8;
    w.probe_requests = MatX(8, 2);
    for (int k = 0; k < 8; ++k) {
        w.probe_requests.row(k) << k % 4, k / 4;  // x 0..3 of level 0, then of level 1
        w.probe_missed.push_back(k < 4 ? 1 : 0);  // every request of level 0 missed
    }
    CHECK(workflow::nearby_misses(w, set, (VecX(2) << 1.0, 0.0).finished()) == 3);
    CHECK(workflow::nearby_misses(w, set, (VecX(2) << 1.0, 1.0).finished()) == 0);
}

TEST_CASE("edge calibration: bad options and no probes are refused", "[workflow]") {
    std::vector<workflow::EdgeProbe> probes{probe(0.2, 0.0, true)};
    spread(probes);
    const MotionSet set = line_set(3);
    workflow::EdgeCalibrationOptions o;
    o.detection = 0.0;
    CHECK_THROWS_AS(workflow::calibrate_edge_warning(probes, set, o), InvalidArgument);
    o = {};
    o.tolerance_share = -1.0;
    CHECK_THROWS_AS(workflow::calibrate_edge_warning(probes, set, o), InvalidArgument);
    o = {};
    o.shell_sd = std::nan("");
    CHECK_THROWS_AS(workflow::calibrate_edge_warning(probes, set, o), InvalidArgument);
    o = {};
    o.false_alarms = 1.0;
    CHECK_THROWS_AS(workflow::calibrate_edge_warning(probes, set, o), InvalidArgument);
    CHECK_THROWS_AS(workflow::calibrate_edge_warning({}, set, {}), InvalidArgument);
    o = {};
    o.neighbours = 0;
    CHECK_THROWS_AS(workflow::calibrate_edge_warning(probes, set, o), InvalidArgument);
}

TEST_CASE("edge calibration: tolerances and distances", "[workflow]") {
    MatX x(4, 2);
    x << 0, 5, 1, 5, 2, 5, 3, 5;  // SD of 0..3 = sqrt(5/3); second column constant
    const auto t = workflow::sd_tolerance(x, 0.25);
    REQUIRE(t[0]);
    CHECK(*t[0] == Approx(0.25 * std::sqrt(5.0 / 3.0)));
    CHECK_FALSE(t[1]);
    CHECK(workflow::parameter_distance(0.1, 6.2, 2 * M_PI) == Approx(2 * M_PI - 6.1));
    CHECK(workflow::parameter_distance(0.1, 6.2, 0.0) == Approx(6.1));

    MotionSet set;
    set.parameter_names = {"turn", "style"};
    set.parameter_units = {"rad", ""};
    set.parameters = MatX(4, 2);
    set.parameters << 0, 0, 1, 1, 2, 0, 3, 1;
    set.parameter_levels = {{}, {"happy", "sad"}};
    set.parameter_source = "extract:turn; category:style";
    const auto pt = workflow::parameter_tolerance(set, 0.25);
    CHECK(pt[0]);
    CHECK_FALSE(pt[1]);  // a category is not measured back
    set.parameter_source = "csv:p.csv";
    CHECK_FALSE(workflow::parameter_tolerance(set, 0.25)[0]);  // nor a CSV column
    // Beyond the samples: in the numeric axis's SDs; a category has no "beyond".
    const double sd = std::sqrt(5.0 / 3.0);
    CHECK(workflow::beyond_samples_sd(set, (VecX(2) << 1.5, 1).finished()) == 0.0);
    CHECK(workflow::beyond_samples_sd(set, (VecX(2) << 3.0 + sd, 0).finished()) == Approx(1.0));
    CHECK(workflow::beyond_samples_sd(set, (VecX(2) << -0.5 * sd, 1).finished()) == Approx(0.5));
    CHECK_THROWS_AS(workflow::beyond_samples_sd(set, VecX(1)), InvalidArgument);
}

TEST_CASE("edge calibration: probes on the shared walks, stored by compress and used by synthesis",
          "[workflow][shared]") {
    MOCAPDB_REQUIRE_SHARED(datasets_dir() / "cmu-asfamc");
    const WalkDatabase& w = edge_walks();
    const Database db(w.path);
    const MotionSet set = db.load_set("walks");
    const auto model = workflow::load_motion_model(db, "walks");

    workflow::EdgeCalibrationOptions o;
    o.inside = 12;
    o.beyond = 12;
    const std::vector<workflow::EdgeProbe> probes = workflow::edge_probes(*model, set, o);
    REQUIRE(probes.size() == 24);
    const VecX lo = set.parameters.colwise().minCoeff().transpose(), hi = set.parameters.colwise().maxCoeff().transpose();
    const auto sd = workflow::sd_tolerance(set.parameters, 1.0);
    const auto tolerance = workflow::parameter_tolerance(set, o.tolerance_share);
    for (std::size_t k = 0; k < probes.size(); ++k) {
        const workflow::EdgeProbe& p = probes[k];
        INFO("probe " << k << " at " << p.requested.transpose());
        CHECK(p.inside == (k < o.inside));
        Eigen::Index outside = 0;
        for (Eigen::Index a = 0; a < 2; ++a) {
            const double beyond = std::max(lo(a) - p.requested(a), p.requested(a) - hi(a));
            if (beyond > 0.0) {
                ++outside;
                CHECK(beyond <= o.shell_sd * *sd[static_cast<std::size_t>(a)] + 1e-12);
            }
        }
        CHECK(outside == (p.inside ? 0 : 1));
        CHECK(p.rho == Approx(std::clamp(1.0 - p.variance_ratio, 0.0, 1.0)));
        CHECK(p.beyond_sd == Approx(workflow::beyond_samples_sd(set, p.requested)));
        CHECK((p.beyond_sd > 0.0) == !p.inside);
        // The judgement is the synthesis step's: measured back against the tolerance.
        const workflow::SynthOutcome out = workflow::synthesize(*model, set, p.requested);
        CHECK(p.miss == !workflow::missed_parameters(out, set, tolerance).empty());
    }
    // The same seed, the same probes.
    const std::vector<workflow::EdgeProbe> again = workflow::edge_probes(*model, set, o);
    CHECK(again[5].requested == probes[5].requested);

    // compress stored a calibration with the kernel; the model loaded from it warns by it.
    REQUIRE(w.compressed.kernel_edge_warning);
    const synthesis::EdgeWarning& stored = *w.compressed.kernel_edge_warning;
    CHECK(stored.probes == 600);
    REQUIRE(model->kernel_fit().edge_warning);
    CHECK(model->kernel_fit().edge_warning->variance_ratio == stored.variance_ratio);
    CHECK(workflow::edge_warning(*model).beyond_sd == stored.beyond_sd);
    // At a sample: nothing flagged; three SDs beyond the fastest walk: flagged, by rho or by measurement.
    const VecX at_sample = set.parameters.row(3).transpose();
    const workflow::SynthesisWarnings near =
        workflow::synthesis_warnings(*model, workflow::synthesize(*model, set, at_sample), set);
    CHECK(near.calibrated);
    CHECK_FALSE(near.flagged());
    VecX far = at_sample;
    far(1) = hi(1) + 3.0 * *sd[1];
    const workflow::SynthesisWarnings out = workflow::synthesis_warnings(*model, workflow::synthesize(*model, set, far), set);
    CHECK(out.variance_ratio > near.variance_ratio);
    CHECK(out.flagged());
}
