// Issue #36 item 1: any skeleton that imports packs and meets E against its own source frames. The
// layout many exporters write (six_channel_rig.hpp: a static ROOT, 6 channels on every joint, the
// travel in Hips) read with both position-channel conventions, a moving root whose OFFSET the
// position channels replace, end sites and constant channels, on the PFNN rig, the procedural
// humanoid and a 100-joint rig, on 1 and 2 threads. Measured by decoding the packed bytes and
// comparing forward kinematics of every joint and end site with the source clip at every frame.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "mocapdb/motion/clip.hpp"
#include "mocapdb/packing/group_decoder.hpp"
#include "mocapdb/packing/packed_group.hpp"
#include "fk_error.hpp"
#include "rig_clips.hpp"
#include "shared_clips.hpp"
#include "shared_data.hpp"
#include "six_channel_rig.hpp"

using namespace mocapdb;
using namespace mocapdb::packing;
using namespace mocapdb::test;

namespace {

const char* name_of(PositionChannels p) { return p == PositionChannels::replace_offset ? "replace" : "add"; }

/// Packs `clips` (one group) in both formats at every E on every thread count: decoded max <= E on
/// every clip (and the encoder's figure is the decoded one), the decoder's skeletons are the sources' (structure, motion
/// root, convention), and the bytes do not depend on the thread count.
void check_packs(const std::vector<Clip>& clips, const std::vector<double>& errors, const std::vector<int>& threads) {
    std::vector<const Clip*> ptrs;
    for (const Clip& c : clips) ptrs.push_back(&c);
    REQUIRE(group_clips(ptrs).size() == 1);
    for (PackFormat format : {PackFormat::Runtime, PackFormat::Archive})
    for (double E : errors) {
        std::vector<std::uint8_t> first_bytes;
        for (int t : threads) {
            PackOptions options;
            options.format = format;
            options.max_error_cm = E;
            options.threads = t;
            const PackedGroup packed = pack_group(ptrs, options);
            INFO((format == PackFormat::Runtime ? "runtime" : "archive")
                 << ", E " << E << ", " << t << " threads: " << packed.stats.bytes << " bytes, "
                 << packed.stats.raw_windows << " raw windows, encode-time max " << packed.stats.error.max_cm);
            CHECK(packed.stats.format == format);
            CHECK(packed.stats.error.max_cm <= E);
            if (first_bytes.empty())
                first_bytes = packed.bytes;
            else
                CHECK(packed.bytes == first_bytes);
            const GroupDecoder decoder(packed.bytes);
            REQUIRE(decoder.clip_count() == clips.size());
            double decoded_max = 0.0;
            for (std::size_t k = 0; k < clips.size(); ++k) {
                const Skeleton& source = *clips[k].skeleton;
                const Skeleton& stored = *decoder.skeleton(k);
                CHECK(stored.motion_root() == source.motion_root());
                CHECK(stored.position_channels() == source.position_channels());
                CHECK(stored.same_structure(source, 1e-5));
                const double err = max_position_error(clips[k], decoder.decode_clip(k));
                INFO("clip " << clips[k].name << " max " << err << " cm");
                CHECK(err <= E);
                decoded_max = std::max(decoded_max, err);
            }
            CHECK(decoded_max == packed.stats.error.max_cm);
        }
    }
}

/// `sources` in the six-channel layout (two performers: Hips offsets differ), read back as BVH with
/// `positions`.
std::vector<Clip> six_channel_clips(const std::vector<Clip>& sources, PositionChannels positions, bool static_root) {
    std::vector<Clip> out;
    for (std::size_t i = 0; i < sources.size(); ++i) {
        const Vec3 hips = i % 2 == 0 ? Vec3(0.0, 92.5, 1.5) : Vec3(0.0, 101.0, -2.0);
        out.push_back(through_bvh_text(six_channel_layout(sources[i], hips, static_root), positions));
        // The reader puts the pose vector's root on Hips below the static ROOT.
        REQUIRE(out.back().skeleton->motion_root() == (static_root ? 1u : 0u));
    }
    return out;
}

}  // namespace

TEST_CASE("every rig packs: PFNN walks with a static ROOT and 6 channels on every joint, both conventions, "
          "E = 1, 0.5, 0.1 on 1 and 2 threads",
          "[packing][shared]") {
    MOCAPDB_REQUIRE_SHARED(datasets_dir() / "cmu-walkrun-pfnn");
    const std::vector<Clip> sources = read_shared_clips("cmu-walkrun-pfnn", {"16_13_60fps", "02_01_60fps"}, 240);
    for (PositionChannels positions : {PositionChannels::replace_offset, PositionChannels::add_to_offset}) {
        INFO("position channels " << name_of(positions));
        const std::vector<Clip> clips = six_channel_clips(sources, positions, true);
        CHECK(clips[0].skeleton->size() == sources[0].skeleton->size() + 1);
        check_packs(clips, {1.0, 0.5, 0.1}, {1, 2});
    }
}

TEST_CASE("every rig packs: the procedural humanoid with 6 channels on every joint, static ROOT or moving root "
          "whose OFFSET is replaced, both conventions",
          "[packing]") {
    std::vector<Clip> sources = procedural_walks();
    sources.resize(3);
    for (bool static_root : {true, false})
        for (PositionChannels positions : {PositionChannels::replace_offset, PositionChannels::add_to_offset}) {
            INFO((static_root ? "static ROOT" : "moving root") << ", position channels " << name_of(positions));
            check_packs(six_channel_clips(sources, positions, static_root), {1.0, 0.1}, {2});
        }
}

TEST_CASE("every rig packs: 100 joints with position channels on every one (hinges, static joints, end sites), "
          "static ROOT or moving root, both conventions",
          "[packing]") {
    const std::vector<Clip> sources = {hundred_joint_clip(24.0, 8.0, 3), hundred_joint_clip(24.0, 5.0, 4)};
    for (bool static_root : {true, false})
        for (PositionChannels positions : {PositionChannels::replace_offset, PositionChannels::add_to_offset}) {
            INFO((static_root ? "static ROOT" : "moving root") << ", position channels " << name_of(positions));
            const std::vector<Clip> clips = six_channel_clips(sources, positions, static_root);
            CHECK(clips[0].skeleton->size() == (static_root ? 101u : 100u));
            check_packs(clips, {1.0, 0.1}, {2});
        }
}

TEST_CASE("every rig packs: clips of one rig whose motion roots differ form separate groups", "[packing]") {
    // The same joints, once with a static ROOT (motion root Hips) and once with the ROOT moving.
    const Clip walk = procedural_walks()[1];
    const Clip still_root = through_bvh_text(six_channel_layout(walk, Vec3(0.0, 92.5, 0.0)), PositionChannels::replace_offset);
    Clip moving_root = still_root;
    for (Eigen::Index f = 0; f < moving_root.channels.rows(); ++f) moving_root.channels(f, 0) = 0.1 * static_cast<double>(f);
    moving_root.skeleton = std::make_shared<const Skeleton>(still_root.skeleton->with_motion_root(0));
    moving_root.name = "moving_root";
    REQUIRE(still_root.skeleton->motion_root() == 1);
    const std::vector<const Clip*> both{&still_root, &moving_root};
    CHECK(group_clips(both).size() == 2);
    CHECK_THROWS_AS(pack_group(both, PackOptions{}), InvalidArgument);
    for (const Clip* c : both) {
        PackOptions o;
        o.max_error_cm = 0.5;
        const GroupDecoder decoder(pack_group({c}, o).bytes);
        CHECK(decoder.skeleton(0)->motion_root() == c->skeleton->motion_root());
        CHECK(max_position_error(*c, decoder.decode_clip(0)) <= 0.5);
    }
}
