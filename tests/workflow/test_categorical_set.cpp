// Categorical parameters end to end on subject 16's walks and runs (issue #38 item 3, acceptance 3):
// `gait` from the clip ids by a regex (walks 16_1x, runs 16_4x) beside the measured turn; synthesized at
// the same turn, each gait's measured-back speed lies among its own samples' speeds, so the two differ
// as the samples do. Also: the levels survive the store, an unknown level is refused, a CSV column of
// names is categorical beside extracted parameters, and a level with one sample is refused.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>

#include "mocapdb/core/error.hpp"
#include "mocapdb/dataset/param_extractors.hpp"
#include "mocapdb/dataset/motion_set.hpp"
#include "mocapdb/dataset/set_builder.hpp"
#include "mocapdb/store/database.hpp"
#include "mocapdb/workflow/load_model.hpp"
#include "mocapdb/workflow/synthesis_step.hpp"
#include "walk_database.hpp"

using namespace mocapdb;
using namespace mocapdb::test;
using Catch::Matchers::Contains;

namespace {

// Walks 16_11 .. 16_19 and runs 16_40 .. 16_46 of cmu-asfamc, imported once per test process.
const WalkDatabase& gait_database() {
    static const WalkDatabase g = [] {
        WalkDatabase r;
        r.dir = std::make_unique<TempDir>("categorical_gaits");
        r.path = r.dir->path() / "gaits.h5";
        std::vector<std::filesystem::path> files;
        for (int t : {11, 12, 13, 14, 15, 16, 17, 18, 19, 40, 41, 42, 43, 44, 45, 46})
            files.push_back(datasets_dir() / "cmu-asfamc" / ("16_" + std::to_string(t) + ".amc"));
        r.imported = workflow::import_clips(r.path, files, workflow::ImportOptions{}, false);
        return r;
    }();
    return g;
}

double measurement(const workflow::SynthOutcome& o, const std::string& name) {
    for (const workflow::Measurement& m : o.measurements)
        if (m.name == name) return m.value;
    FAIL("no measurement '" << name << "'");
    return 0.0;
}

}  // namespace

TEST_CASE("workflow: walk vs run as a category: the measured-back speed follows the category's samples",
          "[workflow][shared]") {
    MOCAPDB_REQUIRE_SHARED(datasets_dir() / "cmu-asfamc");
    const WalkDatabase& g = gait_database();
    workflow::SetRequest r;
    r.name = "gaits";
    r.clips = {"16_1?", "16_4?"};
    r.segment = "gait:1";
    r.extract = {"turn"};
    r.categories = {{"gait", "^16_([14])[0-9]$"}};
    const workflow::SetOutcome created = workflow::create_set(g.path, r);
    REQUIRE(created.set.parameter_names == std::vector<std::string>{"turn", "gait"});
    REQUIRE(created.set.parameter_source == "extract:turn; category:gait=^16_([14])[0-9]$");

    // The samples' own speeds per level (the set's frames, as every later step sees them).
    const Database db(g.path);
    const MotionSet set = db.load_set("gaits");
    REQUIRE(set.parameter_levels.size() == 2);
    REQUIRE(set.parameter_levels[1] == std::vector<std::string>{"1", "4"});  // walks, runs
    CHECK(set.parameters == created.set.parameters);
    std::map<int, std::vector<double>> speeds;
    for (std::size_t i = 0; i < set.samples.size(); ++i) {
        const Clip sample = sample_frames(set, i, db.load_clip(set.samples[i].clip));
        const ParameterExtractor speed = ParameterExtractor::parse("speed");
        speeds[static_cast<int>(set.parameters(static_cast<Eigen::Index>(i), 1))].push_back(
            extract_parameters(sample, 0, sample.frame_count(), {speed})(0));
    }
    REQUIRE(speeds[0].size() >= 5);
    REQUIRE(speeds[1].size() >= 5);
    auto mean = [](const std::vector<double>& v) {
        double s = 0.0;
        for (double x : v) s += x;
        return s / static_cast<double>(v.size());
    };
    const double walk_mean = mean(speeds[0]), run_mean = mean(speeds[1]);
    INFO("sample speeds: walks " << walk_mean << " cm/s (" << speeds[0].size() << "), runs " << run_mean << " cm/s ("
                                 << speeds[1].size() << ")");
    REQUIRE(run_mean > 1.5 * walk_mean);  // the data: runs are much faster

    align_and_compress(g.path, "gaits", 40);
    const Database done(g.path);
    const auto model = workflow::load_motion_model(done, "gaits");

    // Both gaits at the same turn (the samples' mean): only the category differs.
    const double turn = set.parameters.col(0).mean();
    std::map<int, double> measured;
    for (const int level : {0, 1}) {
        const std::string name = set.parameter_levels[1][static_cast<std::size_t>(level)];
        const VecX c = parameter_request(set, {"gait=" + name, "turn=" + std::to_string(turn)});
        REQUIRE(c(1) == level);
        const workflow::SynthOutcome o = workflow::synthesize(*model, set, c);
        measured[level] = measurement(o, "speed");
        const auto [lo, hi] = std::minmax_element(speeds[level].begin(), speeds[level].end());
        INFO("gait " << name << " at turn " << turn << ": measured speed " << measured[level] << " cm/s, samples "
                     << *lo << " to " << *hi << "; reliability " << o.reliability);
        CHECK(measured[level] >= 0.9 * *lo);
        CHECK(measured[level] <= 1.1 * *hi);
        // Every applicable extractor is measured; the set's extracted parameter has its measurement.
        for (const char* n : {"dx", "dz", "turn", "speed"}) CHECK(std::isfinite(measurement(o, n)));
        REQUIRE(o.parameter_measured.size() == 2);
        REQUIRE(o.parameter_measured[0].has_value());
        CHECK(*o.parameter_measured[0] == measurement(o, "turn"));
        CHECK_FALSE(o.parameter_measured[1].has_value());  // a category is not measured
        CHECK(o.measured.size() == 0);
    }
    INFO("measured speeds: walk " << measured[0] << ", run " << measured[1] << "; sample means " << walk_mean << ", "
                                  << run_mean);
    CHECK(measured[1] - measured[0] > 0.5 * (run_mean - walk_mean));
    WARN("walk vs run at turn " << turn << " rad: measured speeds " << measured[0] << " and " << measured[1]
                                << " cm/s; the samples' mean speeds " << walk_mean << " and " << run_mean << " cm/s");

    // An unknown level: refused, listing the known ones; a level index that is not one: refused.
    CHECK_THROWS_WITH(parameter_request(set, {"gait=skip", "turn=0"}), Contains("no level 'skip'") && Contains("1, 4"));
    VecX between(2);
    between << turn, 0.5;
    CHECK_THROWS_AS(model->motion(between), InvalidArgument);
}

TEST_CASE("workflow: a CSV column of names is categorical beside extracted parameters", "[workflow][shared]") {
    MOCAPDB_REQUIRE_SHARED(datasets_dir() / "cmu-asfamc");
    const WalkDatabase& g = gait_database();
    const std::filesystem::path csv = g.dir->path() / "effort.csv";
    {
        std::ofstream out(csv);
        out << "sample,effort,tempo[bpm]\n";
        for (int t : {11, 12, 13, 14, 15, 16})
            out << "16_" << t << "," << (t % 2 ? "easy" : "brisk") << "," << 100 + t << "\n";
    }
    workflow::SetRequest r;
    r.name = "efforts";
    r.clips = {"16_1[1-6]"};
    r.segment = "none";
    r.extract = {"turn", "speed"};
    r.params_csv = csv;
    const MotionSet set = workflow::create_set(g.path, r).set;
    REQUIRE(set.parameter_names == std::vector<std::string>{"turn", "speed", "effort", "tempo"});
    CHECK(set.parameter_units == std::vector<std::string>{"rad", "cm/s", "", "bpm"});
    CHECK(set.parameter_source == "extract:turn,speed; csv:effort.csv");
    REQUIRE(set.parameter_levels.size() == 4);
    CHECK(set.parameter_levels[2] == std::vector<std::string>{"brisk", "easy"});
    CHECK(set.parameter_levels[3].empty());
    CHECK(set.parameters(0, 2) == 1.0);  // 16_11: easy
    CHECK(set.parameters(1, 2) == 0.0);  // 16_12: brisk
    CHECK(set.parameters(5, 3) == 116.0);
    CHECK(workflow::source_extractors(set.parameter_source).size() == 2);
    const MotionSet stored = Database(g.path).load_set("efforts");
    CHECK(stored.parameter_levels == set.parameter_levels);

    // A column mixing numbers and names, and a level with one sample: refused, nothing stored.
    {
        std::ofstream out(csv);
        out << "sample,effort\n16_11,easy\n16_12,3\n16_13,easy\n16_14,brisk\n16_15,brisk\n16_16,easy\n";
    }
    r.name = "mixed";
    CHECK_THROWS_WITH(workflow::create_set(g.path, r), Contains("mixes numbers") && Contains("effort.csv:2"));
    {
        std::ofstream out(csv);
        out << "sample,effort\n16_11,easy\n16_12,easy\n16_13,easy\n16_14,brisk\n16_15,easy\n16_16,easy\n";
    }
    CHECK_THROWS_WITH(workflow::create_set(g.path, r), Contains("level 'brisk'") && Contains("1 sample"));
    CHECK_FALSE(Database(g.path).has_set("mixed"));
}
