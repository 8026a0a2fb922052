// glTF export read back by a second, independent reader (Debian's assimp): every joint's and end site's
// world position at every frame equals our FK within 1e-3 cm, for the ASF rig and the PFNN BVH rig,
// in both containers; and a clip without frames or an unwritable path is a clear error.
#include <catch2/catch.hpp>

#include "mocapdb/core/error.hpp"
#include "mocapdb/io/gltf_writer.hpp"
#include "mocapdb/motion/forward_kinematics.hpp"
#include "../shared_clips.hpp"
#include "gltf_reader.hpp"
#include "shared_data.hpp"
#include "test_support.hpp"

using namespace mocapdb;


namespace {

void check_round_trip(const Clip& clip, GltfContainer container) {
    test::TempDir dir("gltf");
    const auto path = dir / (container == GltfContainer::Glb ? "clip.glb" : "clip.gltf");
    write_gltf(path, clip, container);
    const test::GltfDifference d = test::gltf_difference(path, clip);
    INFO("largest difference " << d.max_cm << " cm (" << d.where << ")");
    CHECK(d.max_cm <= 1e-3);
}

}  // namespace

TEST_CASE("glTF export: assimp reads back our FK on the ASF rig (glb and gltf)", "[io][gltf]") {
    MOCAPDB_REQUIRE_SHARED(test::datasets_dir() / "cmu-asfamc");
    const Clip clip = test::read_shared_clips("cmu-asfamc", {"16_15"}, 300)[0];
    check_round_trip(clip, GltfContainer::Glb);
    check_round_trip(clip, GltfContainer::Gltf);
}

TEST_CASE("glTF export: assimp reads back our FK on the PFNN BVH rig", "[io][gltf]") {
    MOCAPDB_REQUIRE_SHARED(test::datasets_dir() / "cmu-walkrun-pfnn");
    check_round_trip(test::read_shared_clips("cmu-walkrun-pfnn", {"02_01_60fps"}, 300)[0], GltfContainer::Glb);
}

TEST_CASE("glTF export: errors name the problem and leave no file", "[io][gltf]") {
    MOCAPDB_REQUIRE_SHARED(test::datasets_dir() / "cmu-asfamc");
    Clip clip = test::read_shared_clips("cmu-asfamc", {"16_15"}, 10)[0];
    test::TempDir dir("gltf_errors");
    CHECK_THROWS_AS(write_gltf(dir / "no_such_folder" / "x.glb", clip, GltfContainer::Glb), IoError);
    clip.channels.resize(0, clip.channels.cols());
    CHECK_THROWS_WITH(write_gltf(dir / "empty.glb", clip, GltfContainer::Glb), Catch::Contains("no frames"));
    CHECK(!std::filesystem::exists(dir / "empty.glb"));
}
