// BVH position channels: the local translation replacing OFFSET (the ecosystem's reading, default),
// or added to it (reader option); a static ROOT whose only child carries the body.
#include <catch2/catch.hpp>
#include <cmath>
#include <sstream>

#include "mocapdb/dataset/param_extractors.hpp"
#include "mocapdb/io/bvh.hpp"
#include "mocapdb/motion/figure_height.hpp"
#include "mocapdb/motion/forward_kinematics.hpp"
#include "mocapdb/motion/pose_vector.hpp"
#include "shared_data.hpp"

using namespace mocapdb;

namespace {

std::filesystem::path fixture(const std::string& name) { return test::test_data_dir() / "bvh" / name; }

Clip read_fixture(const std::string& name, PositionChannels mode) {
    BvhReadOptions o;
    o.position_channels = mode;
    return read_bvh(fixture(name), o);
}

double max_position_difference(const Clip& a, const Clip& b) {
    return (joint_positions(a) - joint_positions(b)).cwiseAbs().maxCoeff();
}

std::vector<ParameterExtractor> turn_and_speed() {
    return {ParameterExtractor::parse("turn"), ParameterExtractor::parse("speed")};
}

}  // namespace

TEST_CASE("BVH position channels replace OFFSET by default", "[io][bvh]") {
    const Clip clip = read_fixture("six_channels_replace.bvh", PositionChannels::replace_offset);
    const Skeleton& s = *clip.skeleton;
    CHECK(s.position_channels() == PositionChannels::replace_offset);
    // The default options read the same way.
    CHECK(read_bvh(fixture("six_channels_replace.bvh")).skeleton->position_channels() ==
          PositionChannels::replace_offset);
    // A static ROOT over one child: the child carries the body.
    REQUIRE(s.joint(s.motion_root()).name == "Hips");
    CHECK(s.motion_root_chain() == std::vector<std::size_t>{0, 1});
    // Frame 0 stands at rest: feet at 0, head end site at 140 cm (not 2x as an adding reader makes it).
    CHECK(figure_height(s, clip.frame(0)) == Approx(140.0).margin(1e-9));
    CHECK(figure_height_warning(figure_height(s, clip.frame(0))).empty());
    GlobalPose pose;
    forward_kinematics(s, clip.frame(0), pose);
    CHECK(pose.positions[*s.find("Head")].y() == Approx(120.0).margin(1e-9));
    // Every joint's OFFSET is replaced by its position channels.
    for (std::size_t j = 0; j < s.size(); ++j) CHECK(s.offset_replaced(j) == !s.joint(j).end_site);
}

TEST_CASE("BVH files written for the adding convention read right with the option", "[io][bvh]") {
    const Clip replaced = read_fixture("six_channels_replace.bvh", PositionChannels::replace_offset);
    const Clip added = read_fixture("six_channels_add.bvh", PositionChannels::add_to_offset);
    CHECK(added.skeleton->position_channels() == PositionChannels::add_to_offset);
    CHECK(max_position_difference(replaced, added) < 1e-9);
    CHECK(replaced.skeleton->same_structure(*added.skeleton) == false);  // rows mean different things

    // Each file read with the wrong convention: every bone doubles (replace file) or collapses (add file),
    // and the height check says so.
    const Clip doubled = read_fixture("six_channels_replace.bvh", PositionChannels::add_to_offset);
    const double tall = figure_height(*doubled.skeleton, doubled.frame(0));
    CHECK(tall > 250.0);
    CHECK_FALSE(figure_height_warning(tall).empty());
    const Clip collapsed = read_fixture("six_channels_add.bvh", PositionChannels::replace_offset);
    const double small = figure_height(*collapsed.skeleton, collapsed.frame(0));
    CHECK(small < kPlausibleFigureMinCm);
    CHECK_THAT(figure_height_warning(small), Catch::Matchers::Contains("whether position channels replace OFFSET"));
}

TEST_CASE("Turn and speed come from the joint that carries the body", "[io][bvh]") {
    const Clip clip = read_fixture("six_channels_replace.bvh", PositionChannels::replace_offset);
    const VecX p = extract_parameters(clip, 0, clip.frame_count(), turn_and_speed());
    // Hips: +2 cm along Z and 3 degrees left a frame, at 1 / 0.0333333 Hz.
    CHECK(p[0] == Approx(4 * 3.0 * kPi / 180.0).margin(1e-12));
    CHECK(p[1] == Approx(2.0 / 0.0333333).epsilon(1e-9));
}

TEST_CASE("Pose vectors of a static-ROOT clip round-trip through the channels", "[io][bvh][pose]") {
    const Clip clip = read_fixture("six_channels_replace.bvh", PositionChannels::replace_offset);
    const Skeleton& s = *clip.skeleton;
    const PoseLayout layout(s);
    CHECK(layout.rotation_joints().front() == s.motion_root());
    CHECK(layout.exp_map_row(0) == -1);  // the static ROOT has no rows
    const Canonicalization c = canonicalization_of(clip);
    const MatX poses = to_pose_vectors(clip, c);
    Clip back = clip;
    back.channels = from_pose_vectors(s, poses, c);
    // Channels equal to their offsets and the static ROOT are restored exactly, so is the motion.
    CHECK((back.channels - clip.channels).cwiseAbs().maxCoeff() < 1e-9);
    CHECK(max_position_difference(back, clip) < 1e-9);
}

TEST_CASE("Written BVH reads back as the same motion in either convention", "[io][bvh]") {
    for (const auto& [name, mode] : {std::pair{"six_channels_replace.bvh", PositionChannels::replace_offset},
                                     std::pair{"six_channels_add.bvh", PositionChannels::add_to_offset}}) {
        const Clip clip = read_fixture(name, mode);
        std::ostringstream text;
        write_bvh(text, clip, BvhWriteOptions{17, 1.0});
        const Clip back = parse_bvh(text.str(), "written.bvh");  // default reader: replace
        INFO(name);
        CHECK(max_position_difference(back, clip) < 1e-9);
        CHECK(back.skeleton->position_channels() == PositionChannels::replace_offset);
    }
}
