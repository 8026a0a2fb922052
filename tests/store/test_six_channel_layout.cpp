// Issue #16, found 1: real CMU walks rewritten in the layout commercial pipelines export (a static
// ROOT "Reference", the body's translation in its child Hips, 6 channels on every joint whose position
// channels equal OFFSET: six_channel_rig.hpp), read as the ecosystem reads them, and two performers in
// one set.
#include <catch2/catch.hpp>

#include "fk_error.hpp"
#include "mini_json.hpp"
#include "mocapdb/dataset/param_extractors.hpp"
#include "mocapdb/io/bvh.hpp"
#include "mocapdb/motion/figure_height.hpp"
#include "mocapdb/motion/forward_kinematics.hpp"
#include "mocapdb/motion/pose_vector.hpp"
#include "mocapdb/store/database.hpp"
#include "shared_data.hpp"
#include "six_channel_rig.hpp"
#include "test_support.hpp"

using namespace mocapdb;
using namespace mocapdb::test;

namespace {

// Same rig, two performers (PFNN 16_13 and 16_15): only the Hips OFFSET (a constant the position
// channels replace) differs. Written as perf_a.bvh and perf_b.bvh into `clips` (created).
void write_two_performers(const std::filesystem::path& clips) {
    const auto folder = datasets_dir() / "cmu-walkrun-pfnn";
    std::filesystem::create_directories(clips);
    BvhReadOptions pfnn;
    pfnn.frame_rate = 60.0;
    write_bvh(clips / "perf_a.bvh", six_channel_layout(read_bvh(folder / "16_13_60fps.bvh", pfnn), Vec3(0, 92.5, 1.5)),
              BvhWriteOptions{17, 1.0});
    write_bvh(clips / "perf_b.bvh", six_channel_layout(read_bvh(folder / "16_15_60fps.bvh", pfnn), Vec3(0, 101.0, -2.0)),
              BvhWriteOptions{17, 1.0});
}

}  // namespace

TEST_CASE("six-channel layout: bone lengths, turn and speed as with rotation-only channels", "[store][bvh][shared]") {
    const auto folder = datasets_dir() / "cmu-walkrun-pfnn";
    MOCAPDB_REQUIRE_SHARED(folder);
    TempDir dir("sixch");
    BvhReadOptions pfnn;
    pfnn.frame_rate = 60.0;
    const std::vector<ParameterExtractor> extractors = {ParameterExtractor::parse("turn"),
                                                        ParameterExtractor::parse("speed")};
    for (const char* name : {"16_13_60fps.bvh", "02_01_60fps.bvh"}) {
        const Clip source = read_bvh(folder / name, pfnn);
        const Clip layout = six_channel_layout(source, Vec3(0.0, 92.5, 1.5));
        // Written as a file and read by the default reader, as a user's export would be.
        write_bvh(dir / name, layout, BvhWriteOptions{17, 1.0});
        const Clip read = read_bvh(dir / name, pfnn);
        INFO(name);
        REQUIRE(read.skeleton->joint(read.skeleton->motion_root()).name == "Hips");

        const double source_height = figure_height(*source.skeleton, source.frame(0));
        const double read_height = figure_height(*read.skeleton, read.frame(0));
        INFO("height source " << source_height << " cm, six-channel " << read_height << " cm");
        CHECK(std::abs(read_height - source_height) <= 0.01 * source_height);
        // Every source joint lands where it was, every frame (the static ROOT is row block 0).
        const MatX a = joint_positions(source);
        const MatX b = joint_positions(read).bottomRows(a.rows());
        CHECK((a - b).cwiseAbs().maxCoeff() < 1e-6);

        const VecX expected = extract_parameters(source, 0, source.frame_count(), extractors);
        const VecX got = extract_parameters(read, 0, read.frame_count(), extractors);
        INFO("turn " << expected[0] << " vs " << got[0] << ", speed " << expected[1] << " vs " << got[1]);
        CHECK(std::abs(got[0] - expected[0]) < 1e-9);
        CHECK(std::abs(got[1] - expected[1]) < 1e-6 * expected[1]);
        CHECK(std::abs(expected[1]) > 10.0);  // the clip really walks

        // Pose vectors: the same rows as the source's (root = Hips), and back to the same motion.
        const MatX source_poses = to_pose_vectors(source, canonicalization_of(source));
        const Canonicalization c = canonicalization_of(read);
        const MatX poses = to_pose_vectors(read, c);
        REQUIRE(poses.rows() == source_poses.rows());
        CHECK((poses - source_poses).cwiseAbs().maxCoeff() < 1e-6);
        Clip back = read;
        back.channels = from_pose_vectors(*read.skeleton, poses, c);
        CHECK((joint_positions(back) - joint_positions(read)).cwiseAbs().maxCoeff() < 1e-6);

        // The old reading (positions added to OFFSET) doubles every bone: the importer's check names it.
        BvhReadOptions adding = pfnn;
        adding.position_channels = PositionChannels::add_to_offset;
        const Clip wrong = read_bvh(dir / name, adding);
        CHECK(figure_height(*wrong.skeleton, wrong.frame(0)) > 1.8 * source_height);
    }
}

TEST_CASE("six-channel layout: two performers whose Hips offsets differ build one set", "[store][bvh][shared][cli]") {
    MOCAPDB_REQUIRE_SHARED(datasets_dir() / "cmu-walkrun-pfnn");
    MOCAPDB_REQUIRE_CLI();
    TempDir dir("sixch_set");
    write_two_performers(dir / "clips");
    const auto db = dir / "db.h5";
    const CommandResult imported = run_cli("import " + quoted((dir / "clips").string()) + " --fps 60 -o " + quoted(db.string()));
    INFO(imported.output);
    REQUIRE(imported.exit_code == 0);
    CHECK(imported.output.find("warning") == std::string::npos);  // plausible heights, read right
    {
        const Database d(db);
        CHECK(d.skeletons().size() == 2);  // each performer's OFFSET lines are kept as written
        CHECK(d.load_skeleton(d.skeletons()[0])->same_structure(*d.load_skeleton(d.skeletons()[1])));
    }
    const CommandResult set = run_cli("set create " + quoted(db.string()) +
                                      " --name walks --clips perf_a perf_b --extract turn speed");
    INFO(set.output);
    REQUIRE(set.exit_code == 0);
    const CommandResult shown = run_cli("set show " + quoted(db.string()) + " walks --json");
    INFO(shown.output);
    REQUIRE(shown.exit_code == 0);
    CHECK(shown.out.find("perf_b") != std::string::npos);
    const CommandResult valid = run_cli("validate " + quoted(db.string()));
    INFO(valid.output);
    CHECK(valid.exit_code == 0);
    // The old reading of the same files is flagged at import.
    const CommandResult wrong = run_cli("import " + quoted((dir / "clips/perf_a.bvh").string()) +
                                        " --fps 60 --bvh-positions add -o " + quoted((dir / "wrong.h5").string()));
    INFO(wrong.output);
    CHECK(wrong.output.find("tall at frame 0") != std::string::npos);
}

TEST_CASE("six-channel layout: imported with either --bvh-positions, the collection packs within E on 1 and 2 threads",
          "[store][packed][bvh][shared][cli]") {
    // Issue #36: every clip of this layout failed in `mocapdb pack` (436.9 cm off with replace, a bad
    // skeleton index with add). Measured from the file: the packed tier decoded against the lossless
    // tier (exact to the imported file), FK of every joint and end site at every frame.
    MOCAPDB_REQUIRE_SHARED(datasets_dir() / "cmu-walkrun-pfnn");
    MOCAPDB_REQUIRE_CLI();
    TempDir dir("sixch_pack");
    write_two_performers(dir / "clips");  // 222 and 235 frames
    for (const char* positions : {"replace", "add"}) {
        INFO("--bvh-positions " << positions);
        const std::string db = (dir / (std::string(positions) + ".h5")).string();
        const CommandResult imported = run_cli("import " + quoted((dir / "clips").string()) + " --fps 60 --bvh-positions " +
                                               positions + " -o " + quoted(db));
        INFO(imported.output);
        REQUIRE(imported.exit_code == 0);
        for (const double E : {1.0, 0.5, 0.1}) {
            double bytes = -1.0;
            for (const int threads : {1, 2}) {
                INFO("E = " << E << ", " << threads << " threads");
                const CommandResult packed = run_cli("pack " + quoted(db) + " --max-error-cm " + std::to_string(E) +
                                                     " --threads " + std::to_string(threads) + " --force --json");
                INFO(packed.output);
                REQUIRE(packed.exit_code == 0);
                const Json j = parse_json(packed.out);
                CHECK(j["clips"].number == 2);
                CHECK(j["max_cm"].number <= E);
                if (bytes >= 0.0) CHECK(j["bytes"].number == bytes);  // the thread count changes no byte
                bytes = j["bytes"].number;
                const Database view(db);
                for (const ClipRecord& r : view.clips()) {
                    const double err = max_position_error(view.load_clip(r.id), view.load_clip_packed(r.id));
                    INFO(r.id << ": decoded max " << err << " cm");
                    CHECK(err <= E);
                    CHECK(err > 0.0);
                }
            }
        }
    }
}
