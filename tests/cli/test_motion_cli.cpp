// The motion-file commands through the built CLI: info and convert.
#include <catch2/catch.hpp>

#include <algorithm>

#include "shared_data.hpp"
#include "test_support.hpp"
#include "mini_json.hpp"
#include "mocapdb/io/bvh.hpp"
#include "mocapdb/io/clip_file.hpp"
#include "mocapdb/motion/forward_kinematics.hpp"

using namespace mocapdb;
using namespace mocapdb::test;
using Catch::Matchers::Contains;

namespace {
std::string amc(const std::string& trial) { return (datasets_dir() / "cmu-asfamc" / (trial + ".amc")).string(); }
std::string asf(const std::string& subject) { return (datasets_dir() / "cmu-asfamc" / (subject + ".asf")).string(); }
}  // namespace

TEST_CASE("info --json reports 16_15: 471 frames at 120 Hz", "[cli][shared]") {
    MOCAPDB_REQUIRE_SHARED(datasets_dir() / "cmu-asfamc");
    const CommandResult r = run_cli("info " + quoted(amc("16_15")) + " --asf " + quoted(asf("16")) + " --json");
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    const Json j = parse_json(r.out);
    CHECK(j["frames"].number == 471);
    CHECK(j["frame_rate"].number == 120);
    CHECK(j["channels"].number == 62);
    CHECK(j["joints"].items.size() == 38);
    CHECK(j["joints"][0]["name"].text == "root");
    CHECK(j["joints"][0]["parent"].kind == Json::Null);
}

TEST_CASE("info on a PFNN BVH warns about the short file, --strict refuses it", "[cli][shared]") {
    MOCAPDB_REQUIRE_SHARED(datasets_dir() / "cmu-walkrun-pfnn");
    const std::string file = quoted((datasets_dir() / "cmu-walkrun-pfnn" / "16_13_60fps.bvh").string());
    CommandResult r = run_cli("info " + file + " --fps 60");
    CHECK(r.exit_code == 0);
    CHECK_THAT(r.output, Contains("222") && Contains("60 Hz"));
    CHECK_THAT(r.output, Contains("warning") && Contains("declares 223 frames but 222"));
    r = run_cli("info " + file + " --strict");
    CHECK(r.exit_code == 1);
    CHECK_THAT(r.output, Contains("16_13_60fps.bvh") && Contains("declares 223 frames"));
}

TEST_CASE("a --fps the BVH's Frame Time contradicts warns with both, <= 0, absurd or NaN is a one-line error",
          "[cli][shared]") {
    MOCAPDB_REQUIRE_SHARED(datasets_dir() / "cmu-walkrun-pfnn");
    const std::string file = quoted((datasets_dir() / "cmu-walkrun-pfnn" / "16_13_60fps.bvh").string());
    const TempDir dir("cli_fps");
    const std::filesystem::path never = dir.path() / "never.h5";
    // The PFNN files say 1/15 s per frame; the true rate is 60 Hz: the override is used and flagged.
    CommandResult r = run_cli("info " + file + " --fps 60");
    CHECK(r.exit_code == 0);
    CHECK_THAT(r.output, Contains("warning") && Contains("60 Hz") && Contains("(15 Hz)"));
    for (const char* bad : {"0", "-5", "1e6", "nan", "inf", "fast"}) {
        for (const std::string& command : {"info " + file, "import " + file + " -o " + quoted(never.string())}) {
            r = run_cli(command + " --fps " + bad);
            CHECK(r.exit_code != 0);
            CHECK_THAT(r.output, Contains("--fps") && Contains(std::string(bad) == "fast" ? "expected a frame rate in Hz"
                                                                             : "must be > 0 and <= 10000 Hz"));
            CHECK(r.output.size() < 200);  // one line, not CLI11's 309-digit range
            CHECK(std::count(r.output.begin(), r.output.end(), '\n') <= 2);
        }
    }
    CHECK_FALSE(std::filesystem::exists(never));
}

TEST_CASE("convert writes a BVH with the AMC's joint positions, and never overwrites without --force", "[cli][shared]") {
    MOCAPDB_REQUIRE_SHARED(datasets_dir() / "cmu-asfamc");
    TempDir dir("convert");
    const std::string out = (dir / "16_15.bvh").string();
    CommandResult r = run_cli("convert " + quoted(amc("16_15")) + " -o " + quoted(out));
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    const Clip source = read_clip(amc("16_15"));
    const Clip written = read_bvh(out);
    CHECK(written.frame_count() == 471);
    CHECK(written.frame_rate == Approx(120.0));
    CHECK((joint_positions(written) - joint_positions(source)).cwiseAbs().maxCoeff() < 1e-3);

    r = run_cli("convert " + quoted(amc("16_15")) + " -o " + quoted(out));
    CHECK(r.exit_code == 1);
    CHECK_THAT(r.output, Contains("exists") && Contains("--force"));
    CHECK(run_cli("convert " + quoted(amc("16_15")) + " -o " + quoted(out) + " --force").exit_code == 0);
}

TEST_CASE("bad input gives one line naming the file, never a crash", "[cli]") {
    TempDir dir("bad");
    const std::string bad = (dir / "bad.bvh").string();
    std::FILE* f = std::fopen(bad.c_str(), "w");
    std::fputs("HIERARCHY\nROOT hip\n{\n OFFSET 0 0 x\n", f);
    std::fclose(f);
    CommandResult r = run_cli("info " + quoted(bad));
    CHECK(r.exit_code == 1);
    CHECK_THAT(r.output, Contains("bad.bvh:4:") && Contains("expected OFFSET component"));
    const std::string txt = (dir / "notes.txt").string();
    f = std::fopen(txt.c_str(), "w");
    std::fputs("hello\n", f);
    std::fclose(f);
    r = run_cli("info " + quoted(txt));
    CHECK(r.exit_code == 1);
    CHECK_THAT(r.output, Contains("unsupported file type"));
    r = run_cli("info " + quoted((dir / "missing.bvh").string()));
    CHECK(r.exit_code != 0);
    CHECK(r.output.find("Segmentation") == std::string::npos);
    // "Frames: 0" with a data row (found by the BVH fuzzer): read with a warning, no height, no crash.
    const std::string zero = (test_data_dir().parent_path() / "fuzz" / "corpus" / "bvh" / "zero_frames_with_data.bvh").string();
    r = run_cli("info " + quoted(zero) + " --json");
    INFO(r.output);
    CHECK(r.exit_code == 0);
    CHECK(parse_json(r.out)["frames"].number == 0);
    CHECK(parse_json(r.out)["figure_height_cm"].kind == Json::Null);
    CHECK_THAT(r.err, Contains("data rows beyond the 0 declared"));
    r = run_cli("info " + quoted(zero));
    CHECK(r.exit_code == 0);
    CHECK_THAT(r.out, Contains("height      - (no frames)"));
}
