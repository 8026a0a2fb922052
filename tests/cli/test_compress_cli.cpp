// mocapdb compress and report on subject 16's runs (issue #4 end to end through the CLI).
#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include "mini_json.hpp"
#include "mocapdb/io/text_file.hpp"
#include "mocapdb/io/clip_file.hpp"
#include "mocapdb/motion/forward_kinematics.hpp"
#include "mocapdb/store/database.hpp"
#include "shared_data.hpp"
#include "test_support.hpp"

using namespace mocapdb;
using namespace mocapdb::test;
using Catch::Matchers::Contains;

namespace {

// Eight of subject 16's runs, imported, grouped with measured turn and speed, and aligned to 40 frames
// (small, so the report's searches stay quick under the sanitizers).
std::string build_runs_db(const TempDir& dir) {
    std::string files;
    for (int t : {36, 37, 38, 39, 40, 41, 42, 43})
        files += " " + quoted((datasets_dir() / "cmu-asfamc" / ("16_" + std::to_string(t) + ".amc")).string());
    const std::string db = quoted((dir / "runs.h5").string());
    CommandResult r = run_cli("import" + files + " -o " + db);
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    r = run_cli("set create " + db + " --name runs --clips '16_*' --segment none --extract turn speed");  // whole clips
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    r = run_cli("align " + db + " --set runs --frames 40");
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    return db;
}

}  // namespace

TEST_CASE("compress stores a model that meets its max-error target", "[cli][compress][shared]") {
    MOCAPDB_REQUIRE_SHARED(datasets_dir() / "cmu-asfamc");
    TempDir dir("compress");
    const std::string db = build_runs_db(dir);

    CommandResult r = run_cli("compress " + db + " --set runs --max-error-cm 2 --json");
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    const Json j = parse_json(r.out);
    CHECK(j["target_met"].boolean);
    CHECK(j["max_cm"].number <= 2.0);
    CHECK(j["max_cm"].number > 0.0);
    CHECK(j["ratio"].number > 1.0);
    CHECK(j["relative_error"].number <= j["relative_error_bound"].number + 1e-12);
    CHECK(j["dims"][2].number == 8);

    const Database database((dir / "runs.h5"));
    const auto stored = database.load_model("runs");
    REQUIRE(stored);
    CHECK(stored->model.tucker.ranks[0] == static_cast<Eigen::Index>(j["ranks"][0].number));
    CHECK(stored->figures.max_cm == Approx(j["max_cm"].number).epsilon(1e-12));

    // Explicit ranks out of range, and an unaligned set, are clear errors.
    r = run_cli("compress " + db + " --set runs --ranks 1000,2,2");
    CHECK(r.exit_code != 0);
    CHECK_THAT(r.output, Contains("--ranks") && Contains("must be in [1,"));
    r = run_cli("set create " + db + " --name one --clips 16_36 16_37 --extract speed");
    REQUIRE(r.exit_code == 0);
    r = run_cli("compress " + db + " --set one");
    CHECK(r.exit_code != 0);
    CHECK_THAT(r.output, Contains("is not aligned") && Contains("mocapdb align"));

    // HOOI at explicit ranks is never worse (in the Frobenius sense) than HOSVD at the same ranks.
    r = run_cli("compress " + db + " --set runs --ranks 12,8,6 --json");
    REQUIRE(r.exit_code == 0);
    const double hosvd_error = parse_json(r.out)["relative_error"].number;
    r = run_cli("compress " + db + " --set runs --ranks 12,8,6 --method hooi --json");
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    CHECK(parse_json(r.out)["relative_error"].number <= hosvd_error + 1e-12);
}

TEST_CASE("report: one run, every baseline, JSON, CSV and SVG", "[cli][compress][shared]") {
    MOCAPDB_REQUIRE_SHARED(datasets_dir() / "cmu-asfamc");
    TempDir dir("report");
    const std::string db = build_runs_db(dir);
    const auto csv = dir / "rd.csv", svg = dir / "rd.svg";
    CommandResult r = run_cli("report " + db + " --set runs --targets 2,0.5 --no-hooi --json --csv " +
                              quoted(csv.string()) + " --svg " + quoted(svg.string()));
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    const Json j = parse_json(r.out);
    CHECK(j["set"].text == "runs");
    CHECK(j["raw_bytes"].number == 4.0 * j["dims"][0].number * j["dims"][1].number * j["dims"][2].number);
    std::set<std::string> methods;
    for (const Json& row : j["rows"].items) {
        methods.insert(row["method"].text);
        for (const char* key : {"bytes", "ratio", "rmse_cm", "max_cm", "p99_cm", "precompute_s", "us_per_pose"})
            CHECK(std::isfinite(row[key].number));
        CHECK(row["ratio"].number == Approx(j["raw_bytes"].number / row["bytes"].number));
        if (row["target_cm"].number > 0 && row["target_met"].boolean) CHECK(row["max_cm"].number <= row["target_cm"].number);
        CHECK(row["p99_cm"].number <= row["max_cm"].number);
    }
    for (const char* m : {"raw-float32", "deflate", "tucker", "tucker+residual", "pca", "pca+residual", "zfp"})
        CHECK(methods.count(m) == 1);
    CHECK(methods.count("tucker-q12") == 1);
    // 2 lossless rows + 2 targets x 6 methods.
    CHECK(j["rows"].items.size() == 14);

    const std::string table = read_text_file(csv);
    CHECK_THAT(table, Contains("method,target_cm"));
    CHECK(std::count(table.begin(), table.end(), '\n') == 15);
    const std::string picture = read_text_file(svg);
    CHECK_THAT(picture, Contains("<svg") && Contains("tucker+residual") && Contains("zfp") && Contains("</svg>"));
    // #16: the CSV and SVG are not overwritten without --force.
    r = run_cli("report " + db + " --set runs --targets 2 --no-hooi --csv " + quoted(csv.string()));
    CHECK(r.exit_code == 1);
    CHECK_THAT(r.err, Contains("rd.csv: exists") && Contains("--force"));
    r = run_cli("report " + db + " --set runs --targets 2 --no-hooi --svg " + quoted(svg.string()) + " --force");
    CHECK(r.exit_code == 0);
}

TEST_CASE("export a set sample from the aligned tensor and from the model, at its own timing", "[cli][compress][shared]") {
    MOCAPDB_REQUIRE_SHARED(datasets_dir() / "cmu-asfamc");
    TempDir dir("export-sample");
    const std::string db = build_runs_db(dir);
    CommandResult r = run_cli("compress " + db + " --set runs --max-error-cm 2 --json");
    REQUIRE(r.exit_code == 0);
    const double model_max = parse_json(r.out)["max_cm"].number;

    const auto aligned_bvh = dir / "aligned.bvh", model_bvh = dir / "model.bvh";
    r = run_cli("export " + db + " --set runs --sample 2 -o " + quoted(aligned_bvh.string()));
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    r = run_cli("export " + db + " --set runs --sample 2 --from-model -o " + quoted(model_bvh.string()));
    INFO(r.output);
    REQUIRE(r.exit_code == 0);

    const Clip original = read_clip(datasets_dir() / "cmu-asfamc" / "16_38.amc");  // sample 2
    const Clip from_aligned = read_clip(aligned_bvh), from_model = read_clip(model_bvh);
    REQUIRE(from_aligned.frame_count() == original.frame_count());
    REQUIRE(from_model.frame_count() == original.frame_count());
    const MatX p_original = joint_positions(original), p_aligned = joint_positions(from_aligned),
               p_model = joint_positions(from_model);
    // First and last frames sit exactly on aligned frames: the pose (and its place in the world) is exact.
    for (Eigen::Index f : {Eigen::Index{0}, p_original.cols() - 1})
        CHECK((p_original.col(f) - p_aligned.col(f)).cwiseAbs().maxCoeff() < 1e-4);
    // The model's sample differs from the aligned one by at most about its stored max error.
    double worst = 0.0;
    for (Eigen::Index f = 0; f < p_model.cols(); ++f)
        for (Eigen::Index j = 0; j < p_model.rows() / 3; ++j)
            worst = std::max(worst, (p_model.block<3, 1>(3 * j, f) - p_aligned.block<3, 1>(3 * j, f)).norm());
    INFO("model export vs aligned export: " << worst << " cm (model max on aligned frames " << model_max << " cm)");
    CHECK(worst <= 1.5 * model_max);
    CHECK(worst > 0.0);

    r = run_cli("export " + db + " --set runs --sample 99 -o " + quoted((dir / "x.bvh").string()));
    CHECK(r.exit_code != 0);
    CHECK_THAT(r.output, Contains("--sample 99") && Contains("samples 0..7"));
}
