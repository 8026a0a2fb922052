// The runtime tier (encode_runtime, RuntimeDecoder) on real clips: every frame decoded from the runtime
// body is within E of its source by forward kinematics of every joint and end site; the cold path
// (one frame, nothing kept) gives the sequential path's bits (window by window), the portable pose
// kernels the automatic ones' (AVX2 where the CPU has it), and local poses the decoded rows' local
// transforms; the six-channel rig in both position-channel conventions; damaged bodies throw.
#include <catch2/catch.hpp>

#include <cstring>
#include <iterator>
#include <random>
#include <string>
#include <vector>

#include "mocapdb/motion/forward_kinematics.hpp"
#include "mocapdb/packing/packed_group.hpp"
#include "mocapdb/packing/runtime_decoder.hpp"
#include "mocapdb/packing/runtime_encoder.hpp"
#include "fk_error.hpp"
#include "rig_clips.hpp"
#include "shared_clips.hpp"
#include "shared_data.hpp"
#include "six_channel_rig.hpp"

using namespace mocapdb;
using namespace mocapdb::packing;
using namespace mocapdb::test;

namespace {

bool same_pose_bits(const LocalPose& a, const LocalPose& b) {
    return a.rotations.size() == b.rotations.size() && a.translations.size() == b.translations.size() &&
           std::memcmp(a.rotations.data(), b.rotations.data(), a.rotations.size() * sizeof(Quat)) == 0 &&
           std::memcmp(a.translations.data(), b.translations.data(), a.translations.size() * sizeof(Vec3)) == 0;
}

struct Packed {
    std::vector<std::uint8_t> group;
    RuntimeBody body;
};

Packed pack_runtime(const std::vector<Clip>& clips, double E, int window) {
    std::vector<const Clip*> ptrs;
    for (const Clip& c : clips) ptrs.push_back(&c);
    REQUIRE(group_clips(ptrs).size() == 1);
    PackOptions po;
    po.format = PackFormat::Archive;  // the header encode_runtime reads
    po.max_error_cm = E;
    po.time_basis = TimeBasis::Learned;
    po.dof_basis = DofBasis::Learned;
    Packed p;
    p.group = pack_group(ptrs, po).bytes;
    RuntimeOptions ro;
    ro.max_error_cm = E;
    ro.window = window;
    p.body = encode_runtime(p.group, ptrs, ro);
    return p;
}

/// Every frame of every clip: FK of the decoded rows within E (and within the encoder's max); the cold
/// local pose and row equal the sequential ones bit for bit and the portable kernels' bit for bit; the
/// local pose is the row's local transforms (1e-12) and its FK is within E.
void check_runtime(const std::vector<Clip>& clips, double E, int window) {
    const Packed p = pack_runtime(clips, E, window);
    const RuntimeStats& s = p.body.stats;
    INFO("E " << E << " cm, W " << s.window << ": " << s.bytes << " bytes (entries " << s.entry_bytes << ", side " << s.side_bytes
              << ", offsets " << s.offset_bytes << "), encoder max " << s.max_error_cm << " cm, " << s.encode_seconds << " s");
    CHECK(s.max_error_cm <= E);
    if (window != 0) CHECK(s.window == window);
    const RuntimeDecoder decoder(p.group.data(), p.group.size(), p.body.bytes.data(), p.body.bytes.size());
    const RuntimeDecoder portable(p.group.data(), p.group.size(), p.body.bytes.data(), p.body.bytes.size(), RuntimeKernels::Portable);
    CHECK_FALSE(portable.uses_avx2());
    REQUIRE(decoder.clip_count() == clips.size());
    CHECK(decoder.window_length() == static_cast<std::size_t>(s.window));
    CHECK(decoder.resident_bytes() > 0);
    double decoded_max = 0.0, local_rotation = 0.0, local_translation = 0.0, local_fk = 0.0;
    std::size_t cold_rows_differ = 0, cold_poses_differ = 0, portable_differ = 0, frames = 0;
    std::vector<LocalPose> sequential;
    LocalPose cold, other;
    GlobalPose pose;
    for (std::size_t k = 0; k < clips.size(); ++k) {
        const Clip decoded = decoder.decode_clip(k);
        const double err = max_position_error(clips[k], decoded);
        INFO("clip " << clips[k].name << " max " << err << " cm");
        CHECK(err <= E);
        decoded_max = std::max(decoded_max, err);
        const Skeleton& sk = *decoder.skeleton(k);
        const MatX source = joint_positions(clips[k]);
        decoder.decode_local_poses(k, 0, decoder.frame_count(k), sequential);
        std::vector<double> row(sk.channel_count());
        for (std::size_t f = 0; f < decoder.frame_count(k); ++f, ++frames) {
            decoder.decode_pose(k, f, row.data());
            if (std::memcmp(row.data(), decoded.channels.row(static_cast<Eigen::Index>(f)).data(), row.size() * sizeof(double)) != 0)
                ++cold_rows_differ;
            decoder.decode_local_pose(k, f, cold);
            if (!same_pose_bits(cold, sequential[f])) ++cold_poses_differ;
            portable.decode_local_pose(k, f, other);
            if (!same_pose_bits(cold, other)) ++portable_differ;
            for (std::size_t j = 0; j < sk.size(); ++j) {
                const Quat q = sk.local_rotation(j, row.data());
                const Quat& c = cold.rotations[j];
                local_rotation = std::max(local_rotation, std::min((q.coeffs() - c.coeffs()).norm(), (q.coeffs() + c.coeffs()).norm()));
                const Vec3 t = sk.local_translation(j, row.data());
                local_translation = std::max(local_translation, (t - cold.translations[j]).norm() / (1.0 + t.norm()));
            }
            forward_kinematics(sk, cold.rotations, cold.translations, pose);
            for (std::size_t j = 0; j < sk.size(); ++j)
                local_fk = std::max(local_fk, (pose.positions[j] - source.block<3, 1>(3 * static_cast<Eigen::Index>(j),
                                                                                        static_cast<Eigen::Index>(f))).norm());
        }
    }
    INFO(frames << " frames: decoded max " << decoded_max << " cm, local pose FK max " << local_fk << " cm, local rotation "
                << local_rotation << ", translation " << local_translation);
    CHECK(decoded_max <= s.max_error_cm);
    CHECK(cold_rows_differ == 0);
    CHECK(cold_poses_differ == 0);
    CHECK(portable_differ == 0);
    CHECK(local_rotation <= 1e-12);
    CHECK(local_translation <= 1e-12);
    CHECK(local_fk <= E + 1e-9);
}

const char* convention_name(PositionChannels p) { return p == PositionChannels::replace_offset ? "replace" : "add"; }

}  // namespace

TEST_CASE("runtime tier: clips of 1, 2, 8, 9, 16, 17 and 40 frames (a key alone, windows cut short, whole windows) "
          "at W 8 and 16",
          "[packing]") {
    const std::vector<Clip> walks = procedural_walks();
    std::vector<Clip> clips;
    const std::size_t lengths[] = {1, 2, 8, 9, 16, 17, 40};
    for (std::size_t i = 0; i < std::size(lengths); ++i) {
        clips.push_back(slice(walks[i % walks.size()], 3 * i, 3 * i + lengths[i]));
        clips.back().name = "cut" + std::to_string(lengths[i]);
    }
    check_runtime(clips, 0.5, 8);
    check_runtime(clips, 0.5, 16);
}

TEST_CASE("runtime tier: PFNN clips within E at 1 and 0.1 cm, cold = sequential = portable, bit for bit", "[packing][shared]") {
    MOCAPDB_REQUIRE_SHARED(datasets_dir() / "cmu-walkrun-pfnn");
    const std::vector<Clip> clips = read_shared_clips("cmu-walkrun-pfnn", {"16_13_60fps", "02_01_60fps", "132_35_60fps"}, 300);
    check_runtime(clips, 1.0, 8);
    check_runtime(clips, 0.1, 16);
}

TEST_CASE("runtime tier: ASF/AMC clips of three subjects (three skeletons) within E at 1 and 0.1 cm", "[packing][shared]") {
    MOCAPDB_REQUIRE_SHARED(datasets_dir() / "cmu-asfamc");
    const std::vector<Clip> clips = read_shared_clips("cmu-asfamc", {"02_01", "05_02", "16_13"}, 300);
    check_runtime(clips, 1.0, 16);
    check_runtime(clips, 0.1, 8);
}

TEST_CASE("runtime tier: the window chosen by bytes (W 8 or 16) is within E", "[packing][shared]") {
    MOCAPDB_REQUIRE_SHARED(datasets_dir() / "cmu-walkrun-pfnn");
    const std::vector<Clip> clips = read_shared_clips("cmu-walkrun-pfnn", {"07_01_60fps"}, 200);
    check_runtime(clips, 0.5, 0);
}

TEST_CASE("runtime tier: the six-channel rig (static ROOT, travel in Hips) in both position-channel conventions",
          "[packing][shared]") {
    MOCAPDB_REQUIRE_SHARED(datasets_dir() / "cmu-walkrun-pfnn");
    const std::vector<Clip> sources = read_shared_clips("cmu-walkrun-pfnn", {"16_13_60fps", "02_01_60fps"}, 160);
    for (PositionChannels positions : {PositionChannels::replace_offset, PositionChannels::add_to_offset}) {
        INFO("position channels " << convention_name(positions));
        std::vector<Clip> clips;
        for (std::size_t i = 0; i < sources.size(); ++i) {
            const Vec3 hips = i % 2 == 0 ? Vec3(0.0, 92.5, 1.5) : Vec3(0.0, 101.0, -2.0);
            clips.push_back(through_bvh_text(six_channel_layout(sources[i], hips, true), positions));
            REQUIRE(clips.back().skeleton->motion_root() == 1u);
        }
        check_runtime(clips, 1.0, 8);
        check_runtime(clips, 0.1, 16);
    }
}

TEST_CASE("runtime tier: truncated, garbled or mismatched bodies throw; decoding a damaged body that still parses stays "
          "in bounds",
          "[packing][shared]") {
    MOCAPDB_REQUIRE_SHARED(datasets_dir() / "cmu-walkrun-pfnn");
    const std::vector<Clip> clips = read_shared_clips("cmu-walkrun-pfnn", {"16_13_60fps", "02_01_60fps"}, 120);
    const Packed p = pack_runtime(clips, 1.0, 16);
    const std::vector<std::uint8_t>& body = p.body.bytes;
    auto decode_all = [&](const std::vector<std::uint8_t>& bytes) {
        const RuntimeDecoder d(p.group.data(), p.group.size(), bytes.data(), bytes.size());
        LocalPose out;
        for (std::size_t k = 0; k < d.clip_count(); ++k)
            for (std::size_t f = 0; f < d.frame_count(k); ++f) d.decode_local_pose(k, f, out);
        (void)d.decode_clip(0);
    };
    decode_all(body);
    // Truncated: every length short of the whole throws (each copy is exactly that long: the sanitizer
    // build sees any read past it).
    for (std::size_t n = 0; n < body.size(); n += n < 64 ? 1 : 97) {
        const std::vector<std::uint8_t> cut(body.begin(), body.begin() + static_cast<std::ptrdiff_t>(n));
        INFO("first " << n << " of " << body.size() << " bytes");
        CHECK_THROWS_AS(RuntimeDecoder(p.group.data(), p.group.size(), cut.data(), cut.size()), Error);
    }
    // The header's fields.
    for (std::size_t at : {0, 1, 2, 4, 8, 12, 16, 20}) {
        std::vector<std::uint8_t> bad = body;
        bad[at] ^= 0x5a;
        INFO("header byte " << at);
        CHECK_THROWS_AS(RuntimeDecoder(p.group.data(), p.group.size(), bad.data(), bad.size()), Error);
    }
    // Another group's header: its clip count and dofs differ.
    {
        const std::vector<Clip> one(clips.begin(), clips.begin() + 1);
        const Packed q = pack_runtime(one, 1.0, 16);
        CHECK_THROWS_AS(RuntimeDecoder(q.group.data(), q.group.size(), body.data(), body.size()), Error);
    }
    // Garbled bytes anywhere: construction throws Error, or the body still parses and every frame decodes
    // (no crash, no read outside the body: the sanitizer build checks it).
    std::mt19937_64 rng(11);
    std::size_t thrown = 0, parsed = 0;
    for (int trial = 0; trial < 300; ++trial) {
        std::vector<std::uint8_t> bad = body;
        const int flips = 1 + trial % 4;
        for (int k = 0; k < flips; ++k)
            bad[std::uniform_int_distribution<std::size_t>(0, bad.size() - 1)(rng)] ^=
                static_cast<std::uint8_t>(1u << std::uniform_int_distribution<int>(0, 7)(rng));
        try {
            decode_all(bad);
            ++parsed;
        } catch (const Error&) {
            ++thrown;
        }
    }
    INFO(thrown << " garbled bodies threw, " << parsed << " parsed and decoded");
    CHECK(thrown >= 150);
    // Options and clips that are not the group's.
    std::vector<const Clip*> ptrs{&clips[0], &clips[1]};
    RuntimeOptions o;
    o.window = 12;
    CHECK_THROWS_AS(encode_runtime(p.group, ptrs, o), InvalidArgument);
    o.window = 16;
    o.max_error_cm = 0.0;
    CHECK_THROWS_AS(encode_runtime(p.group, ptrs, o), InvalidArgument);
    o.max_error_cm = 1.0;
    const Clip shorter = slice(clips[1], 0, 60);
    const std::vector<const Clip*> other{&clips[0], &shorter};
    CHECK_THROWS_AS(encode_runtime(p.group, other, o), InvalidArgument);
    const RuntimeDecoder d(p.group.data(), p.group.size(), body.data(), body.size());
    LocalPose out;
    CHECK_THROWS_AS(d.decode_local_pose(2, 0, out), InvalidArgument);
    CHECK_THROWS_AS(d.decode_local_pose(0, clips[0].frame_count(), out), InvalidArgument);
}
