// Synthesis through the CLI on subject 16's walks (issue #6): synth (acceptance 2: the measured turn and
// speed of the written BVH match the requested ones), query, reliability map, reduce.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <sstream>

#include "mini_json.hpp"
#include "mocapdb/dataset/param_extractors.hpp"
#include "mocapdb/io/bvh.hpp"
#include "mocapdb/kriging/trend.hpp"
#include "mocapdb/store/database.hpp"
#include "shared_data.hpp"
#include "test_support.hpp"

using namespace mocapdb;
using namespace mocapdb::test;
using Catch::Matchers::Contains;

namespace {

// One database per test process: import, set create (measured turn, speed), align, compress.
struct WalkDb {
    std::unique_ptr<TempDir> dir;
    std::string db;  // quoted path
    std::filesystem::path path;
};

const WalkDb& walk_db() {
    static const WalkDb w = [] {
        WalkDb r;
        r.dir = std::make_unique<TempDir>("synth-cli");
        r.path = r.dir->path() / "walks.h5";
        r.db = quoted(r.path.string());
        std::string files;
        for (int t = 11; t <= 34; ++t)
            files += " " + quoted((datasets_dir() / "cmu-asfamc" / ("16_" + std::to_string(t) + ".amc")).string());
        files += " " + quoted((datasets_dir() / "cmu-asfamc" / "16_47.amc").string());
        const std::vector<std::string> steps{
            "import" + files + " -o " + r.db,
            "set create " + r.db + " --name walks --clips '16_*' --segment none --extract turn speed",  // 25 whole clips
            "align " + r.db + " --set walks --frames 60",
            "compress " + r.db + " --set walks --max-error-cm 1",
        };
        for (const std::string& s : steps) {
            const CommandResult c = run_cli(s);
            if (c.exit_code != 0) throw std::runtime_error("mocapdb " + s + " failed: " + c.output);
        }
        return r;
    }();
    return w;
}

std::string file_text(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

std::string csv_of(const VecX& c) {
    std::ostringstream s;
    s.precision(17);
    for (Eigen::Index k = 0; k < c.size(); ++k) s << (k ? "," : "") << c(k);
    return s.str();
}

}  // namespace

TEST_CASE("synth between the samples: the BVH's measured turn and speed match the request", "[cli][synthesis][shared]") {
    MOCAPDB_REQUIRE_SHARED(datasets_dir() / "cmu-asfamc");
    const WalkDb& w = walk_db();
    const MatX p = Database(w.path).load_set("walks").parameters;  // N by 2: turn [rad], speed [cm/s]
    REQUIRE(p.cols() == 2);
    // Targets between the samples: the midpoint of each sample and its nearest neighbour (normalized
    // parameters), i.e. parameters no sample has.
    const MatX xn = kriging::ControlScaling::from_data(p).apply(p);
    double worst_turn = 0.0, worst_speed = 0.0, sum_turn = 0.0, sum_speed = 0.0, sum_separate = 0.0, worst_separate = 0.0;
    int count = 0;
#ifdef MOCAPDB_SANITIZED_BUILD
    const Eigen::Index stride = 6;
#else
    const Eigen::Index stride = 2;
#endif
    for (Eigen::Index i = 0; i < p.rows(); i += stride) {
        Eigen::Index nearest = -1;
        double best = 1e300;
        for (Eigen::Index j = 0; j < p.rows(); ++j)
            if (j != i && (xn.row(i) - xn.row(j)).norm() < best) {
                best = (xn.row(i) - xn.row(j)).norm();
                nearest = j;
            }
        const VecX c = 0.5 * (p.row(i) + p.row(nearest)).transpose();
        const std::string out = (w.dir->path() / ("synth_" + std::to_string(i) + ".bvh")).string();
        const CommandResult r = run_cli("synth " + w.db + " --set walks --param " + csv_of(c) + " -o " + quoted(out) + " --json");
        INFO(r.output);
        REQUIRE(r.exit_code == 0);
        const Json j = parse_json(r.out);
        CHECK(j["model"].text == "tucker");
        CHECK(j["reliability"].number > 0.0);
        CHECK(j["reliability"].number <= 1.0);

        const Clip clip = read_bvh(out);
        REQUIRE(static_cast<double>(clip.frame_count()) == j["frames"].number);
        const VecX m = extract_parameters(clip, 0, clip.frame_count(),
                                          {ParameterExtractor::parse("turn"), ParameterExtractor::parse("speed")});
        const double e_turn = std::abs(m(0) - c(0)), e_speed = std::abs(m(1) - c(1));
        INFO("target turn " << c(0) << " rad, speed " << c(1) << " cm/s; measured " << m(0) << ", " << m(1));
        CHECK(e_turn <= 0.02);            // rad (1.1 degrees)
        // 10 % of the speed (measured 2026-12-02 with the residual variogram and filtered kriging of issue
        // #15: mean 3.4 %, max 7.8 %; before, exact interpolation of a raw-value variogram: max under 5 %).
        CHECK(e_speed <= 0.10 * c(1));
        // The paper's separate timing kernel, for the record (not asserted).
        const std::string out_s = (w.dir->path() / ("separate_" + std::to_string(i) + ".bvh")).string();
        const CommandResult rs = run_cli("synth " + w.db + " --set walks --param " + csv_of(c) + " -o " + quoted(out_s) +
                                         " --timing separate");
        REQUIRE(rs.exit_code == 0);
        const Clip cs = read_bvh(out_s);
        const double e_sep = std::abs(extract_parameters(cs, 0, cs.frame_count(), {ParameterExtractor::parse("speed")})(0) - c(1)) / c(1);
        sum_separate += e_sep;
        worst_separate = std::max(worst_separate, e_sep);
        worst_turn = std::max(worst_turn, e_turn);
        worst_speed = std::max(worst_speed, e_speed / c(1));
        sum_turn += e_turn;
        sum_speed += e_speed / c(1);
        ++count;
    }
    WARN("synth at " << count << " targets between the samples: turn error mean " << sum_turn / count << " rad, max "
                     << worst_turn << " rad; speed error mean " << 100.0 * sum_speed / count << " %, max "
                     << 100.0 * worst_speed << " %; with --timing separate: speed error mean "
                     << 100.0 * sum_separate / count << " %, max " << 100.0 * worst_separate << " %");

    // The naive model and a level of detail run through the same command.
    const VecX c = p.colwise().mean().transpose();
    CommandResult r = run_cli("synth " + w.db + " --set walks --param " + csv_of(c) + " -o " +
                              quoted((w.dir->path() / "naive.bvh").string()) + " --naive --json");
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    CHECK(parse_json(r.out)["model"].text == "naive");
    r = run_cli("synth " + w.db + " --set walks --param " + csv_of(c) + " -o " +
                quoted((w.dir->path() / "lod.bvh").string()) + " --lod 4x3x2");
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    CHECK_THAT(r.out, Contains("ranks 4x3x2") && Contains("reliability"));
    // #16: errors speak of what the user asked for, not of internal classes.
    r = run_cli("synth " + w.db + " --set walks --param " + csv_of(c) + " -o " + quoted((w.dir->path() / "lod99.bvh").string()) +
                " --lod 99x1x1");
    CHECK(r.exit_code == 1);
    CHECK_THAT(r.err, Contains("synthesis model: level-of-detail ranks 99x1x1"));
    CHECK(r.err.find("MotionModel") == std::string::npos);
    // #16: an existing output is kept unless --force.
    r = run_cli("synth " + w.db + " --set walks --param " + csv_of(c) + " -o " + quoted((w.dir->path() / "lod.bvh").string()));
    CHECK(r.exit_code == 1);
    CHECK_THAT(r.err, Contains("lod.bvh: exists") && Contains("--force"));
    r = run_cli("synth " + w.db + " --set walks --param " + csv_of(c) + " -o " + quoted((w.dir->path() / "lod.bvh").string()) +
                " --force");
    CHECK(r.exit_code == 0);
    // Wrong parameter count: the message names the set's parameters.
    r = run_cli("synth " + w.db + " --set walks --param 0.1 -o " + quoted((w.dir->path() / "x.bvh").string()));
    CHECK(r.exit_code == 1);
    CHECK_THAT(r.err, Contains("expected 2 values") && Contains("turn [rad]") && Contains("speed [cm/s]"));
}

TEST_CASE("query prints a synthesized pose, at a sample it is the sample's pose", "[cli][synthesis][shared]") {
    MOCAPDB_REQUIRE_SHARED(datasets_dir() / "cmu-asfamc");
    const WalkDb& w = walk_db();
    const Database db(w.path);
    const MatX p = db.load_set("walks").parameters;
    const AlignedSet aligned = *db.load_aligned("walks");
    // The naive model at a sample: filtered kriging (issue #15) treats the walks' nugget (about a fifth of
    // the total sill here: dropout glitches and gait-phase scatter) as noise, so the pose is near the
    // sample's, not equal to it, and rho is below 1 (1 - nugget share at most). Measured 2026-12-02:
    // rho 0.80, largest pose-vector difference 24 (cm, the root's position; radians elsewhere).
    CommandResult r = run_cli("query " + w.db + " --set walks --param " + csv_of(p.row(4).transpose()) +
                              " --frame 10 --naive --json");
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    Json j = parse_json(r.out);
    CHECK(j["reliability"].number > 0.5);
    CHECK(j["reliability"].number < 1.0);
    REQUIRE(static_cast<Eigen::Index>(j["pose_vector"].items.size()) == aligned.dofs());
    double worst = 0.0;
    for (Eigen::Index k = 0; k < aligned.dofs(); ++k)
        worst = std::max(worst, std::abs(j["pose_vector"][static_cast<std::size_t>(k)].number - aligned.tensor(k, 10, 4)));
    CHECK(worst < 40.0);
    CHECK(j["channels"].items.size() > 10);

    r = run_cli("query " + w.db + " --set walks --param " + csv_of(p.colwise().mean().transpose()) +
                " --frame 12.5 --joints --json");
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    j = parse_json(r.out);
    CHECK(j["unit"].text == "cm");
    REQUIRE(j["joints"].items.size() > 20);
    CHECK(j["joints"][std::size_t{0}]["name"].text == "root");
    CHECK(j["joints"][std::size_t{0}]["position"][std::size_t{1}].number > 50.0);  // the hips are about a metre above the floor

    r = run_cli("query " + w.db + " --set walks --param 0,100 --frame 60");
    CHECK(r.exit_code == 1);
    CHECK_THAT(r.err, Contains("[0, 59]"));
}

TEST_CASE("reliability map: SVG with samples marked, CSV of the grid", "[cli][synthesis][shared]") {
    MOCAPDB_REQUIRE_SHARED(datasets_dir() / "cmu-asfamc");
    const WalkDb& w = walk_db();
    const std::string svg = (w.dir->path() / "rho.svg").string(), csv = (w.dir->path() / "rho.csv").string();
    const CommandResult r = run_cli("reliability " + w.db + " --set walks --grid turn=-2:2:21,speed=60:200:11 --svg " +
                                    quoted(svg) + " --csv " + quoted(csv) + " --json");
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    const Json j = parse_json(r.out);
    CHECK(j["cells"].number == 231);
    CHECK(j["max"].number <= 1.0);
    CHECK(j["min"].number >= 0.0);
    CHECK(j["min"].number < j["max"].number);
    std::ifstream in(svg);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    CHECK_THAT(text, Contains("<svg") && Contains("<circle") && Contains("turn [rad]") && Contains("samples (25)"));
    std::ifstream c(csv);
    std::string line;
    int lines = 0;
    while (std::getline(c, line)) ++lines;
    CHECK(lines == 232);
    // Errors name what is wrong.
    const std::string other = (w.dir->path() / "rho_bad.svg").string();
    const CommandResult bad = run_cli("reliability " + w.db + " --set walks --grid pace=0:1:5,speed=60:200:11 --svg " + quoted(other));
    CHECK(bad.exit_code == 1);
    CHECK_THAT(bad.err, Contains("no parameter 'pace'") && Contains("turn, speed"));
    // #16: existing outputs are not overwritten without --force (the SVG, then the CSV alone).
    const std::string grid = " --set walks --grid turn=-2:2:5,speed=60:200:5 --svg ";
    CommandResult again = run_cli("reliability " + w.db + grid + quoted(svg));
    CHECK(again.exit_code == 1);
    CHECK_THAT(again.err, Contains(svg) && Contains("exists") && Contains("--force"));
    again = run_cli("reliability " + w.db + grid + quoted(other) + " --csv " + quoted(csv));
    CHECK(again.exit_code == 1);
    CHECK_THAT(again.err, Contains(csv) && Contains("--force"));
    CHECK(!std::filesystem::exists(other));  // refused before any output
    again = run_cli("reliability " + w.db + grid + quoted(svg) + " --csv " + quoted(csv) + " --force");
    INFO(again.output);
    CHECK(again.exit_code == 0);
}

TEST_CASE("reduce reports the greedy reduction and --apply stores an aligned reduced set", "[cli][synthesis][shared]") {
    MOCAPDB_REQUIRE_SHARED(datasets_dir() / "cmu-asfamc");
    const WalkDb& w = walk_db();
    // tau 0.3: the walks' residual variogram has a large nugget (about a fifth of the total sill) and a
    // range bounded by the largest lag, so leave-one-out reliabilities stay below ~0.4 (measured
    // 2026-12-02: 0.37 at most) and the paper's 0.85 removes nothing here.
    CommandResult r = run_cli("reduce " + w.db + " --set walks --tau 0.3 --json");
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    const Json j = parse_json(r.out);
    const auto kept = static_cast<std::size_t>(j["kept"].number);
    CHECK(kept + j["removed"].items.size() == 25);
    CHECK(!j["removed"].items.empty());
    CHECK(kept >= 4);
    for (const Json& e : j["removed"].items) CHECK(e["reliability"].number >= 0.3);
    if (j["stopped_on_threshold"].boolean) CHECK(j["max_reliability"].items.back().number < 0.3);

    r = run_cli("reduce " + w.db + " --set walks --tau 0.3 --apply --name small");
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    CHECK_THAT(r.out, Contains("'small' stored and aligned"));
    const Database db(w.path);
    REQUIRE(db.has_set("small"));
    CHECK(db.load_set("small").samples.size() == kept);
    const auto aligned = db.load_aligned("small");
    REQUIRE(aligned);
    CHECK(aligned->frames() == 60);
    CHECK(aligned->samples() == static_cast<Eigen::Index>(kept));
    // #16: a reduced set synthesizes like the original (it failed on its parameter source before).
    r = run_cli("synth " + w.db + " --set small --naive --param 0,120 -o " + quoted((w.dir->path() / "small.bvh").string()));
    INFO(r.output);
    CHECK(r.exit_code == 0);
    CHECK(db.load_set("small").parameter_source == db.load_set("walks").parameter_source);
    // Existing name without --force.
    r = run_cli("reduce " + w.db + " --set walks --tau 0.3 --apply --name small");
    CHECK(r.exit_code == 1);
    CHECK_THAT(r.err, Contains("exists"));
}

TEST_CASE("synth with the kernel compress stored writes the same BVH as fitting the kernel", "[cli][synthesis][shared]") {
    MOCAPDB_REQUIRE_SHARED(datasets_dir() / "cmu-asfamc");
    const WalkDb& w = walk_db();
    TempDir dir("synth-kernel");
    const auto path = dir / "walks.h5";
    copy_database(w.path, path);
    const std::string db = quoted(path.string());
    const MatX p = Database(path).load_set("walks").parameters;
    const std::string c = csv_of(0.5 * (p.row(0) + p.row(1)).transpose());
    REQUIRE(Database(path).load_kernel_fit("walks").has_value());  // compress stored it

    // (Kriging, as a model fitted at load uses: the stored choice of predictor goes with the stored kernel.)
    CommandResult r = run_cli("synth " + db + " --set walks --param " + c + " -o " + quoted((dir / "a.bvh").string()) +
                              " --json --predictor kriging");
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    CHECK(parse_json(r.out)["kernel_stored"].boolean);

    // The same model stored again without its kernel: synth fits it and writes the same file.
    {
        DatabaseWriter writer(path);
        const auto stored = writer.view().load_model("walks");
        writer.put_model("walks", stored->model, stored->figures);
        writer.commit();
    }
    REQUIRE_FALSE(Database(path).load_kernel_fit("walks").has_value());
    r = run_cli("synth " + db + " --set walks --param " + c + " -o " + quoted((dir / "b.bvh").string()) + " --json");
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    CHECK_FALSE(parse_json(r.out)["kernel_stored"].boolean);
    CHECK(file_text(dir / "a.bvh") == file_text(dir / "b.bvh"));
}

TEST_CASE("compress chooses the predictor by cross-validation, set show shows it, synth and query use it",
          "[cli][synthesis][shared]") {
    MOCAPDB_REQUIRE_SHARED(datasets_dir() / "cmu-asfamc");
    const WalkDb& w = walk_db();
    TempDir dir("synth-predictor");
    const MatX p = Database(w.path).load_set("walks").parameters;
    const std::string c = csv_of(0.5 * (p.row(2) + p.row(3)).transpose());

    CommandResult r = run_cli("set show " + w.db + " walks --json");
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    const Json shown = parse_json(r.out)["predictor"];
    const std::string chosen = shown["chosen"].text;
    CHECK(shown["folds"].number == 15);  // 25 whole clips: no twins, 15 evenly spread folds
    CHECK(shown["samples"].number == 25);
    // The lowest is chosen, or averaged with those within one paired standard error of it.
    const std::string lowest = shown["members"].items.front().text;
    for (const char* name : {"kriging", "rbf", "trend"}) {
        CHECK(shown["cv_rms"][name].number >= 0.0);
        CHECK(shown["cv_se"][name].number >= 0.0);
    }
    CHECK((chosen == "average") == (shown["members"].items.size() >= 2));
    if (chosen != "average") {
        CHECK(lowest == chosen);
        for (const char* name : {"kriging", "rbf", "trend"})
            CHECK(shown["cv_rms"][name].number >= shown["cv_rms"][chosen].number);
    }
    r = run_cli("set show " + w.db + " walks");
    CHECK_THAT(r.out, Contains("synthesis predictor: " + chosen + (chosen == "average" ? " of " : " (cv ")));

    r = run_cli("synth " + w.db + " --set walks --param " + c + " -o " + quoted((dir / "default.bvh").string()) + " --json");
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    Json j = parse_json(r.out);
    CHECK(j["predictor"].text == chosen);
    CHECK(j["predictor_choice"]["chosen"].text == chosen);
    const double rho = j["reliability"].number;
    const std::string other = chosen == "trend" ? "rbf" : "trend";
    r = run_cli("synth " + w.db + " --set walks --param " + c + " -o " + quoted((dir / "other.bvh").string()) +
                " --json --predictor " + other);
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    j = parse_json(r.out);
    CHECK(j["predictor"].text == other);
    CHECK(j["reliability"].number == rho);  // rho is the kriging kernel's whichever blends
    CHECK(file_text(dir / "default.bvh") != file_text(dir / "other.bvh"));

    r = run_cli("query " + w.db + " --set walks --param " + c + " --frame 3 --json");
    REQUIRE(r.exit_code == 0);
    CHECK(parse_json(r.out)["predictor"].text == chosen);
    r = run_cli("synth " + w.db + " --set walks --param " + c + " -o " + quoted((dir / "x.bvh").string()) +
                " --predictor spline");
    CHECK(r.exit_code != 0);
    CHECK_THAT(r.err, Contains("--predictor"));
}
