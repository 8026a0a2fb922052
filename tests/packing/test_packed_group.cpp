#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <random>

#include "mocapdb/core/float32.hpp"
#include "mocapdb/io/clip_file.hpp"
#include "mocapdb/motion/forward_kinematics.hpp"
#include "mocapdb/packing/byte_parts.hpp"
#include "mocapdb/packing/group_decoder.hpp"
#include "mocapdb/packing/packed_group.hpp"
#include "mocapdb/procedural/walk.hpp"
#include "fk_error.hpp"
#include "rig_clips.hpp"
#include "shared_clips.hpp"
#include "shared_data.hpp"

using namespace mocapdb;
using namespace mocapdb::packing;
using mocapdb::test::hundred_joint_clip;
using mocapdb::test::max_position_error;
using mocapdb::test::procedural_walks;

namespace {

/// The archive format (format 3), whose windows these tests are about.
const PackOptions kArchivePackOptions = [] {
    PackOptions o;
    o.format = PackFormat::Archive;
    return o;
}();

/// The group's bytes per kind of stored data (issue 36 item 5): every part present, in the format's
/// order, summing exactly to the bytes; payload and tables agreeing with the other statistics.
void check_parts(const PackedGroup& packed) {
    const ByteParts& parts = packed.stats.parts;
    CHECK(total_bytes(parts) == packed.bytes.size());
    std::vector<std::string> names;
    for (const BytePart& p : parts) names.push_back(p.name);
    CHECK(names == std::vector<std::string>{"header", "topology", "skeletons", "constant_dofs", "bases", "contexts",
                                            "clip_table", "window_table", "payload", "raw_windows"});
    auto part = [&](const std::string& name) {
        for (const BytePart& p : parts)
            if (p.name == name) return p.bytes;
        return std::uint64_t{0};
    };
    CHECK(part("payload") + part("raw_windows") == packed.stats.payload_bytes);
    CHECK(part("clip_table") + part("window_table") == packed.stats.table_bytes);
    CHECK(part("topology") > 0);
    CHECK(part("skeletons") > 0);
    // Raw windows hold float64 source rows, nothing else.
    CHECK((part("raw_windows") > 0) == (packed.stats.raw_windows > 0));
}

/// Packs `clips` (one group) at each E and checks the bound on every clip, every source frame.
void check_bound(const std::vector<Clip>& clips, std::size_t max_frames_per_clip) {
    std::vector<Clip> cut;
    for (const Clip& c : clips)
        cut.push_back(c.frame_count() > max_frames_per_clip ? slice(c, 0, max_frames_per_clip) : c);
    std::vector<const Clip*> ptrs;
    for (const Clip& c : cut) ptrs.push_back(&c);
    REQUIRE(group_clips(ptrs).size() == 1);
    for (double E : {1.0, 0.5, 0.1}) {
        PackOptions options;
        options.format = PackFormat::Archive;
        options.max_error_cm = E;
        const PackedGroup packed = pack_group(ptrs, options);
        INFO("E " << E << ": " << packed.stats.bytes << " bytes, encode-time max " << packed.stats.error.max_cm);
        CHECK(packed.stats.error.max_cm <= E);
        check_parts(packed);
        const GroupDecoder decoder(packed.bytes);
        REQUIRE(decoder.clip_count() == cut.size());
        double decoded_max = 0.0;
        for (std::size_t k = 0; k < cut.size(); ++k) {
            const double err = max_position_error(cut[k], decoder.decode_clip(k));
            INFO("clip " << cut[k].name << " max " << err);
            CHECK(err <= E);
            decoded_max = std::max(decoded_max, err);
            // The decoder's skeleton is the source's rounded to float32, to the bit: what the encoder
            // checked its bound with.
            const Skeleton& source = *cut[k].skeleton;
            const Skeleton& decoded = *decoder.skeleton(k);
            REQUIRE(decoded.size() == source.size());
            for (std::size_t j = 0; j < source.size(); ++j)
                for (int a = 0; a < 3; ++a) {
                    INFO("joint " << source.joint(j).name << " offset " << a);
                    CHECK(decoded.joint(j).offset[a] == float32_value(source.joint(j).offset[a]));
                }
        }
        // The encoder measured exactly what a reader decodes (no margin needed, no second attempt).
        CHECK(decoded_max == packed.stats.error.max_cm);
    }
}

}  // namespace

TEST_CASE("packing meets the bound on the procedural humanoid", "[packing]") {
    check_bound(procedural_walks(), 100000);
}

TEST_CASE("packing meets the bound on PFNN BVH clips", "[packing][shared]") {
    MOCAPDB_REQUIRE_SHARED(test::datasets_dir() / "cmu-walkrun-pfnn");
    check_bound(test::read_shared_clips("cmu-walkrun-pfnn", {"02_01_60fps", "07_01_60fps", "132_35_60fps"}), 400);
}

TEST_CASE("packing meets the bound on ASF/AMC clips", "[packing][shared]") {
    MOCAPDB_REQUIRE_SHARED(test::datasets_dir() / "cmu-asfamc");
    check_bound(test::read_shared_clips("cmu-asfamc", {"02_01", "05_02", "02_03"}), 400);
}

TEST_CASE("a decoded window equals the same frames of a full decode, poses by random access", "[packing]") {
    const std::vector<Clip> clips = procedural_walks();
    std::vector<const Clip*> ptrs;
    for (const Clip& c : clips) ptrs.push_back(&c);
    PackOptions options;
    options.format = PackFormat::Archive;
    options.max_error_cm = 0.5;
    options.window = 16;
    const GroupDecoder decoder(pack_group(ptrs, options).bytes);
    std::mt19937 rng(11);
    for (int trial = 0; trial < 10; ++trial) {
        const std::size_t k = rng() % decoder.clip_count();
        const Clip full = decoder.decode_clip(k);
        const std::size_t w = rng() % decoder.window_count(k);
        const FrameMatrix window = decoder.decode_window(k, w);
        const std::size_t f0 = w * decoder.window_length();
        REQUIRE(window.rows() == static_cast<Eigen::Index>(std::min(decoder.window_length(), full.frame_count() - f0)));
        CHECK(window == full.channels.middleRows(static_cast<Eigen::Index>(f0), window.rows()));
        const std::size_t begin = rng() % full.frame_count();
        const std::size_t end = begin + rng() % (full.frame_count() - begin + 1);
        CHECK(decoder.decode_frames(k, begin, end) ==
              full.channels.middleRows(static_cast<Eigen::Index>(begin), static_cast<Eigen::Index>(end - begin)));
        // One pose: the same bits as the full decode's frame.
        const std::size_t f = rng() % full.frame_count();
        std::vector<double> row(full.skeleton->channel_count());
        decoder.decode_pose(k, f, row.data());
        CHECK(std::equal(row.begin(), row.end(), full.frame(f)));
    }
}

TEST_CASE("packing refuses a bad bound, an empty group and one short clip work", "[packing]") {
    const std::vector<Clip> clips = procedural_walks();
    const std::vector<const Clip*> one{&clips[0]};
    for (double bad : {0.0, -1.0, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
        PackOptions o;
        o.format = PackFormat::Archive;
        o.max_error_cm = bad;
        CHECK_THROWS_AS(pack_group(one, o), InvalidArgument);
    }
    // The bytes do not depend on the number of encoder threads.
    {
        std::vector<const Clip*> all;
        for (const Clip& c : clips) all.push_back(&c);
        PackOptions a, b;
        a.format = b.format = PackFormat::Archive;
        a.threads = 1;
        b.threads = 3;
        CHECK(pack_group(all, a).bytes == pack_group(all, b).bytes);
    }
    const PackedGroup empty = pack_group({}, kArchivePackOptions);
    CHECK(GroupDecoder(empty.bytes).clip_count() == 0);
    CHECK(empty.bytes.size() < 16);
    REQUIRE(empty.stats.parts.size() == 1);  // an empty group is its header
    CHECK(empty.stats.parts[0].name == "header");
    CHECK(empty.stats.parts[0].bytes == empty.bytes.size());

    const Clip short_clip = slice(clips[0], 0, 5);  // shorter than one window
    PackOptions o;
    o.format = PackFormat::Archive;
    o.max_error_cm = 0.1;
    const PackedGroup packed = pack_group({&short_clip}, o);
    const GroupDecoder decoder(packed.bytes);
    REQUIRE(decoder.frame_count(0) == 5);
    CHECK(max_position_error(short_clip, decoder.decode_clip(0)) <= 0.1);
}

TEST_CASE("moving non-root position channels are coded too, a one-frame clip works", "[packing]") {
    const Clip walk = procedural_walks()[2];
    const Skeleton& s = *walk.skeleton;
    const std::size_t forearm = *s.find("LeftForeArm");
    std::vector<Joint> joints = s.joints();
    joints[forearm].channels.insert(joints[forearm].channels.begin(),
                                    {ChannelType::Xposition, ChannelType::Yposition, ChannelType::Zposition});
    auto skeleton = std::make_shared<const Skeleton>(joints, s.source_units(), s.forward());
    Clip clip;
    clip.skeleton = skeleton;
    clip.frame_rate = walk.frame_rate;
    clip.name = "stretchy";
    clip.channels.resize(walk.channels.rows(), static_cast<Eigen::Index>(skeleton->channel_count()));
    for (std::size_t j = 0; j < s.size(); ++j) {
        const auto n = static_cast<Eigen::Index>(s.joint(j).channels.size());
        const auto to = static_cast<Eigen::Index>(skeleton->first_channel(j)) + (j == forearm ? 3 : 0);
        clip.channels.middleCols(to, n) = walk.channels.middleCols(static_cast<Eigen::Index>(s.first_channel(j)), n);
    }
    const auto px = static_cast<Eigen::Index>(skeleton->first_channel(forearm));
    for (Eigen::Index f = 0; f < clip.channels.rows(); ++f)
        for (Eigen::Index a = 0; a < 3; ++a)
            clip.channels(f, px + a) = 4.0 * std::sin(0.05 * static_cast<double>(f) * static_cast<double>(a + 1));
    const Clip one_frame = slice(clip, 7, 8);
    for (double E : {1.0, 0.1}) {
        PackOptions o;
        o.format = PackFormat::Archive;
        o.max_error_cm = E;
        const GroupDecoder decoder(pack_group({&clip, &one_frame}, o).bytes);
        const Clip back = decoder.decode_clip(0);
        CHECK(max_position_error(clip, back) <= E);
        CHECK((back.channels.middleCols(px, 3) - clip.channels.middleCols(px, 3)).cwiseAbs().maxCoeff() <= E);
        CHECK(max_position_error(one_frame, decoder.decode_clip(1)) <= E);
    }
    // A group of one one-frame clip: every dof is constant.
    PackOptions o;
    o.format = PackFormat::Archive;
    o.max_error_cm = 0.1;
    const GroupDecoder single(pack_group({&one_frame}, o).bytes);
    CHECK(max_position_error(one_frame, single.decode_clip(0)) <= 0.1);
}

TEST_CASE("a truncated or foreign packed group is refused with an error", "[packing]") {
    const std::vector<Clip> clips = procedural_walks();
    const std::vector<std::uint8_t> bytes = pack_group({&clips[0], &clips[1]}, kArchivePackOptions).bytes;
    for (std::size_t cut : {std::size_t(0), std::size_t(3), bytes.size() / 3, bytes.size() - 1}) {
        INFO("cut at " << cut << " of " << bytes.size());
        CHECK_THROWS_AS(GroupDecoder(std::vector<std::uint8_t>(bytes.begin(), bytes.begin() + static_cast<long>(cut))),
                        Error);
    }
    std::vector<std::uint8_t> foreign = bytes;
    foreign[0] = 'X';
    CHECK_THROWS_AS(GroupDecoder(foreign), Error);
    std::vector<std::uint8_t> newer = bytes;
    newer[4] = 99;
    CHECK_THROWS_WITH(GroupDecoder(newer), Catch::Contains("version 99"));
    // Version 1 (frames reconstructed window-wide, Euler angles unwrapped frame to frame) decodes to
    // other bits than its encoder verified: refused, not decoded differently.
    std::vector<std::uint8_t> older = bytes;
    older[4] = 1;
    CHECK_THROWS_WITH(GroupDecoder(older), Catch::Contains("version 1, this build reads 2 to 4"));
}

TEST_CASE("packing works at 24 Hz and 120 Hz, frame rates form separate groups", "[packing]") {
    std::vector<Clip> clips;
    for (double rate : {24.0, 120.0}) {
        procedural::WalkOptions o;
        o.frame_rate = rate;
        o.cycles = 2;
        clips.push_back(procedural::generate_walk({1.2, 45.0, 0.0}, o).clip);
    }
    std::vector<const Clip*> ptrs{&clips[0], &clips[1]};
    REQUIRE(group_clips(ptrs).size() == 2);
    CHECK_THROWS_AS(pack_group(ptrs, kArchivePackOptions), InvalidArgument);
    for (const Clip& c : clips) {
        PackOptions o;
        o.format = PackFormat::Archive;
        o.max_error_cm = 0.5;
        const GroupDecoder decoder(pack_group({&c}, o).bytes);
        CHECK(decoder.frame_rate() == c.frame_rate);
        CHECK(max_position_error(c, decoder.decode_clip(0)) <= 0.5);
    }
}

TEST_CASE("automatic and fixed bases all meet the bound", "[packing]") {
    const std::vector<Clip> clips = procedural_walks();
    std::vector<const Clip*> ptrs;
    for (const Clip& c : clips) ptrs.push_back(&c);
    for (TimeBasis tb : {TimeBasis::Auto, TimeBasis::Cosine})
        for (DofBasis db : {DofBasis::Auto, DofBasis::Identity}) {
            PackOptions o;
            o.format = PackFormat::Archive;
            o.max_error_cm = 0.5;
            o.time_basis = tb;
            o.dof_basis = db;
            const PackedGroup packed = pack_group(ptrs, o);
            CHECK(packed.stats.time_basis != TimeBasis::Auto);
            CHECK(packed.stats.dof_basis != DofBasis::Auto);
            const GroupDecoder decoder(packed.bytes);
            for (std::size_t k = 0; k < clips.size(); ++k) CHECK(max_position_error(clips[k], decoder.decode_clip(k)) <= 0.5);
        }
}

TEST_CASE("a window no step brings within the bound is stored as its source rows", "[packing]") {
    // The humanoid's offsets are exact in float32, so its source rows decode exactly; no quantized
    // window can reach 1e-9 cm.
    const Clip clip = slice(procedural_walks()[1], 0, 40);
    PackOptions o;
    o.format = PackFormat::Archive;
    o.max_error_cm = 1e-9;
    const PackedGroup packed = pack_group({&clip}, o);
    CHECK(packed.stats.raw_windows == 2);
    check_parts(packed);
    const GroupDecoder decoder(packed.bytes);
    CHECK(decoder.decode_clip(0).channels == clip.channels);
    std::vector<double> row(clip.skeleton->channel_count());
    decoder.decode_pose(0, 35, row.data());
    CHECK(Eigen::Map<const VecX>(row.data(), static_cast<Eigen::Index>(row.size())) == clip.channels.row(35).transpose());
}


// The long clip spans many windows either way; under the sanitizers (10-20x slower) 20 s of it suffice.
#ifdef MOCAPDB_SANITIZED_BUILD
constexpr double kLongClipSeconds = 20.0;
#else
constexpr double kLongClipSeconds = 90.0;
#endif

TEST_CASE("packing meets the bound on a 100-joint rig at 24 Hz, clips of 1 s and 90 s", "[packing]") {
    const Clip one = hundred_joint_clip(24.0, 1.0, 1);
    const Clip longer = hundred_joint_clip(24.0, kLongClipSeconds, 2);
    REQUIRE(one.skeleton->joints().size() == 100);
    std::vector<const Clip*> ptrs{&one, &longer};
    REQUIRE(group_clips(ptrs).size() == 1);
    for (double E : {1.0, 0.1}) {
        PackOptions o;
        o.format = PackFormat::Archive;
        o.max_error_cm = E;
        const PackedGroup packed = pack_group(ptrs, o);
        INFO("E " << E << ": " << packed.stats.bytes << " bytes for " << packed.stats.frames << " frames");
        const GroupDecoder decoder(packed.bytes);
        REQUIRE(decoder.clip_count() == 2);
        CHECK(max_position_error(one, decoder.decode_clip(0)) <= E);
        CHECK(max_position_error(longer, decoder.decode_clip(1)) <= E);
        // Compact too: well below float32 channels.
        CHECK(packed.stats.bytes * 4 < packed.stats.frames * packed.stats.channels * 4);
    }
}

TEST_CASE("GroupDecoder::resident_bytes counts what the decoder holds beyond the bytes: it grows with clips and windows",
          "[packing]") {
    const std::vector<Clip> walks = procedural_walks();
    std::vector<const Clip*> one{&walks[0]}, all;
    for (const Clip& c : walks) all.push_back(&c);
    PackOptions o;
    o.format = PackFormat::Archive;
    o.max_error_cm = 1.0;
    o.time_basis = TimeBasis::Learned;
    o.dof_basis = DofBasis::Learned;
    const GroupDecoder small(pack_group(one, o).bytes);
    const GroupDecoder large(pack_group(all, o).bytes);
    CHECK(small.resident_bytes() > 0);
    // Every clip and window adds an entry; the bases and scratch are the same size for one rig.
    CHECK(large.resident_bytes() > small.resident_bytes());
    std::size_t windows = 0;
    for (std::size_t c = 0; c < large.clip_count(); ++c) windows += large.window_count(c);
    CHECK(large.resident_bytes() - small.resident_bytes() >= (windows - small.window_count(0)) * sizeof(std::uint64_t));
}
