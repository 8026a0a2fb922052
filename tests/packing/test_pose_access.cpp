// One pose by random access, through a PoseSampler and through a PoseIndex gives exactly the bits of
// its window's decode (the bits the encoder verified against the bound), on both shared rigs at each E.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cstring>
#include <filesystem>
#include <random>
#include <thread>

#include "mocapdb/io/clip_file.hpp"
#include "mocapdb/packing/group_decoder.hpp"
#include "mocapdb/packing/packed_group.hpp"
#include "mocapdb/packing/pose_index.hpp"
#include "mocapdb/packing/pose_sampler.hpp"
#include "mocapdb/procedural/walk.hpp"
#include "shared_clips.hpp"
#include "shared_data.hpp"
#include "six_channel_rig.hpp"

using namespace mocapdb;
using namespace mocapdb::packing;

namespace {

/// The archive format (format 3), whose windows these tests are about.
const PackOptions kArchiveAccessOptions = [] {
    PackOptions o;
    o.format = PackFormat::Archive;
    return o;
}();

bool same_bits(const double* a, const double* b, std::size_t n) { return std::memcmp(a, b, n * sizeof(double)) == 0; }

bool same_bits(const LocalPose& a, const LocalPose& b) {
    return a.rotations.size() == b.rotations.size() && a.translations.size() == b.translations.size() &&
           std::memcmp(a.rotations.data(), b.rotations.data(), a.rotations.size() * sizeof(Quat)) == 0 &&
           std::memcmp(a.translations.data(), b.translations.data(), a.translations.size() * sizeof(Vec3)) == 0;
}

// Largest distance of the local pose from the row's local transforms: rotations up to sign (quaternion
// components), translations (cm, relative to 1 + |t|).
struct LocalError {
    double rotation = 0.0, translation = 0.0, unit = 0.0;
    void add(const Skeleton& k, const double* row, const LocalPose& pose) {
        REQUIRE(pose.rotations.size() == k.size());
        REQUIRE(pose.translations.size() == k.size());
        for (std::size_t j = 0; j < k.size(); ++j) {
            const Quat q = k.local_rotation(j, row);
            const Quat& p = pose.rotations[j];
            rotation = std::max(rotation, std::min((q.coeffs() - p.coeffs()).norm(), (q.coeffs() + p.coeffs()).norm()));
            unit = std::max(unit, std::abs(p.norm() - 1.0));
            const Vec3 t = k.local_translation(j, row);
            translation = std::max(translation, (t - pose.translations[j]).norm() / (1.0 + t.norm()));
        }
    }
};

// Every frame of every clip: decode_pose, the index and the sampler (fed in a scrambled order, small
// capacity so that windows are evicted and decoded again) equal decode_window's row; decode_local_pose,
// the index's and the sampler's local_pose agree bit for bit, and their rotations and translations are
// the row's local transforms (Skeleton::local_rotation / local_translation) to 1e-12 (rotations to
// `rotation_tolerance`). Returns the indexes' columns of 8-, 16- and 32-bit levels, over every E.
std::array<std::size_t, 3> check_every_frame(const std::vector<Clip>& clips, const std::vector<double>& errors = {1.0, 0.5, 0.1},
                              double rotation_tolerance = 1e-12) {
    std::array<std::size_t, 3> widths{};
    std::vector<const Clip*> ptrs;
    for (const Clip& c : clips) ptrs.push_back(&c);
    for (double E : errors) {
        PackOptions options;
        options.format = PackFormat::Archive;
        options.max_error_cm = E;
        const GroupDecoder decoder(pack_group(ptrs, options).bytes);
        const PoseIndex index(decoder);
        for (std::size_t w = 0; w < 3; ++w) widths[w] += index.column_widths()[w];
        PoseSampler sampler(decoder, 2);
        const std::size_t channels = decoder.skeleton(0)->channel_count();
        REQUIRE(sampler.channel_count() == channels);
        std::vector<double> row(channels);
        std::vector<std::pair<std::size_t, std::size_t>> order;
        std::size_t mismatches = 0, sampler_mismatches = 0, frames = 0, local_mismatches = 0, index_mismatches = 0;
        LocalPose local, sampled;
        LocalError error;
        const std::size_t first_window_frames = decoder.frame_count(0);
        for (std::size_t k = 0; k < decoder.clip_count(); ++k)
            for (std::size_t w = 0; w < decoder.window_count(k); ++w) {
                const FrameMatrix window = decoder.decode_window(k, w);
                for (Eigen::Index t = 0; t < window.rows(); ++t) {
                    const std::size_t f = w * decoder.window_length() + static_cast<std::size_t>(t);
                    decoder.decode_pose(k, f, row.data());
                    if (!same_bits(row.data(), window.row(t).data(), channels)) ++mismatches;
                    decoder.decode_local_pose(k, f, local);
                    error.add(*decoder.skeleton(k), row.data(), local);
                    index.pose(k, f, row.data());
                    if (!same_bits(row.data(), window.row(t).data(), channels)) ++index_mismatches;
                    index.local_pose(k, f, sampled);
                    if (!same_bits(sampled, local)) ++index_mismatches;
                    order.emplace_back(k, f);
                    ++frames;
                }
            }
        std::shuffle(order.begin(), order.end(), std::mt19937(5));
        for (const auto& [k, f] : order) {
            const FrameMatrix rows = decoder.decode_frames(k, f, f + 1);
            if (!same_bits(sampler.pose(k, f), rows.data(), channels)) ++sampler_mismatches;
            // The sampler's local pose (frame f's dofs cached, or decoded for it now) is decode_local_pose's.
            sampler.local_pose(k, f, sampled);
            decoder.decode_local_pose(k, f, local);
            if (!same_bits(sampled, local)) ++local_mismatches;
        }
        // Local poses through a fresh sampler (dofs computed for the local pose first).
        PoseSampler fresh(decoder, 2);
        for (std::size_t f = 0; f < first_window_frames; ++f) {
            fresh.local_pose(0, f, sampled);
            decoder.decode_local_pose(0, f, local);
            if (!same_bits(sampled, local)) ++local_mismatches;
            if (!same_bits(fresh.pose(0, f), decoder.decode_frames(0, f, f + 1).data(), channels)) ++sampler_mismatches;
        }
        INFO("E " << E << ": " << frames << " frames");
        CHECK(mismatches == 0);
        CHECK(index_mismatches == 0);
        CHECK(index.coefficient_count() > 0);
        CHECK(sampler_mismatches == 0);
        CHECK(sampler.hits() + sampler.misses() == 2 * frames);
        CHECK(local_mismatches == 0);
        INFO("local pose vs the row's local transforms: rotation " << error.rotation << ", translation "
                                                                  << error.translation << ", |q| - 1 " << error.unit);
        CHECK(error.rotation < rotation_tolerance);
        CHECK(error.translation < 1e-12);
        CHECK(error.unit < 1e-12);
    }
    return widths;
}

}  // namespace

TEST_CASE("decode_pose, PoseIndex and PoseSampler equal decode_window bit for bit: PFNN rig", "[packing][shared]") {
    MOCAPDB_REQUIRE_SHARED(test::datasets_dir() / "cmu-walkrun-pfnn");
    check_every_frame(test::read_shared_clips("cmu-walkrun-pfnn", {"02_01_60fps", "07_01_60fps", "132_35_60fps"}, 300));
}

TEST_CASE("decode_pose, PoseIndex and PoseSampler equal decode_window bit for bit: static ROOT, 6 channels on every joint",
          "[packing][shared]") {
    MOCAPDB_REQUIRE_SHARED(test::datasets_dir() / "cmu-walkrun-pfnn");
    const std::vector<Clip> sources = test::read_shared_clips("cmu-walkrun-pfnn", {"02_01_60fps", "132_35_60fps"}, 200);
    for (PositionChannels positions : {PositionChannels::replace_offset, PositionChannels::add_to_offset}) {
        std::vector<Clip> clips;
        for (const Clip& c : sources)
            clips.push_back(test::through_bvh_text(test::six_channel_layout(c, Vec3(0.0, 92.5, 1.5)), positions));
        check_every_frame(clips, {1.0, 0.1});
    }
}

TEST_CASE("decode_pose, PoseIndex and PoseSampler equal decode_window bit for bit: 31-joint ASF rig", "[packing][shared]") {
    MOCAPDB_REQUIRE_SHARED(test::datasets_dir() / "cmu-asfamc");
    const auto widths = check_every_frame(test::read_shared_clips("cmu-asfamc", {"02_01", "05_02", "02_03"}, 300));
    CHECK(widths[0] > 0);  // the index's columns of 8- and 16-bit levels both decoded
    CHECK(widths[1] > 0);
}

TEST_CASE("Local poses of one- and two-channel joints: every rotation order, absent axis and bone axis", "[packing]") {
    // 18 joints with two rotation channels (6 orders x 3 absent axes), 3 with one (x, y, z) and one
    // with three, each under its own bone axis C, the middle angle swept past ±90° (the other Euler
    // family) and the others over ±150°: the local poses (four joints of a kind at a time, partial
    // groups included) equal the row's transforms. Frames land
    // within 1e-4 of ±90° (gimbal lock), where splitting a rotation into two angles amplifies rounding
    // by about 1 / cos b (both here and in the row's atan2): measured up to 2e-12 there, hence 1e-10;
    // a wrong family, axis or sign is off by O(1).
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    std::vector<Joint> joints(1);
    joints[0].name = "root";
    joints[0].channels = {ChannelType::Xposition, ChannelType::Yposition, ChannelType::Zposition,
                          ChannelType::Zrotation, ChannelType::Xrotation, ChannelType::Yrotation};
    for (int order = 0; order < 6; ++order)
        for (int missing = 0; missing < 3; ++missing) {
            Joint j;
            j.name = "j" + std::to_string(joints.size());
            j.parent = static_cast<int>(joints.size()) - 1;
            j.offset = Vec3(0.0, 10.0, 0.0);
            j.rotation_order = static_cast<EulerOrder>(order);
            const auto axes = axes_of(j.rotation_order);
            for (int n = 0; n < 3; ++n)
                if (n != missing) j.channels.push_back(static_cast<ChannelType>(3 + static_cast<int>(axes[static_cast<std::size_t>(n)])));
            j.axis = Quat(unit(rng), unit(rng), unit(rng), unit(rng)).normalized();
            joints.push_back(j);
        }
    for (int axis = 0; axis < 4; ++axis) {  // 3: three channels
        Joint j;
        j.name = "j" + std::to_string(joints.size());
        j.parent = static_cast<int>(joints.size()) - 1;
        j.offset = Vec3(0.0, 10.0, 0.0);
        j.rotation_order = EulerOrder::YZX;
        for (int a = 0; a < 3; ++a)
            if (a == axis || axis == 3) j.channels.push_back(static_cast<ChannelType>(3 + a));
        j.axis = Quat(unit(rng), unit(rng), unit(rng), unit(rng)).normalized();
        joints.push_back(j);
    }
    Joint end;
    end.name = "end";
    end.parent = static_cast<int>(joints.size()) - 1;
    end.offset = Vec3(0.0, 10.0, 0.0);
    end.end_site = true;
    joints.push_back(end);
    Clip clip;
    clip.skeleton = std::make_shared<const Skeleton>(joints);
    clip.frame_rate = 60.0;
    clip.name = "two_channel_orders";
    const int frames = 240;
    clip.channels = FrameMatrix::Zero(frames, static_cast<Eigen::Index>(clip.skeleton->channel_count()));
    for (int f = 0; f < frames; ++f) {
        const double t = f / 60.0;
        clip.channels(f, 0) = 20.0 * t;
        clip.channels(f, 1) = 90.0;
        for (Eigen::Index c = 3; c < 6; ++c) clip.channels(f, c) = 0.3 * std::sin(t + static_cast<double>(c));
        for (std::size_t j = 1; j + 1 < joints.size(); ++j) {
            const auto axes = axes_of(joints[j].rotation_order);
            for (std::size_t n = 0; n < 3; ++n) {
                const int column = clip.skeleton->channel_column(j, static_cast<ChannelType>(3 + static_cast<int>(axes[n])));
                if (column < 0) continue;
                const double amplitude = n == 1 ? 2.0 : 2.6;  // the middle angle past ±π/2
                clip.channels(f, column) = amplitude * std::sin((0.9 + 0.2 * static_cast<double>(n)) * t + static_cast<double>(j + n));
            }
        }
    }
    check_every_frame({clip}, {1.0, 0.1}, 1e-10);
}

TEST_CASE("PoseIndex: columns with levels beyond 16 bits keep 32-bit cells, same bits", "[packing][shared]") {
    MOCAPDB_REQUIRE_SHARED(test::datasets_dir() / "cmu-asfamc");
    // A bound far below any codec's use makes quantizer steps tiny and the largest levels exceed ±32767.
    const auto widths = check_every_frame(test::read_shared_clips("cmu-asfamc", {"02_01"}, 64), {0.0005});
    CHECK(widths[2] > 0);  // and narrower columns after them in the same blocks
    CHECK(widths[0] > 0);
}

TEST_CASE("PoseSampler: playback hits its cache, bad indices and capacity are refused", "[packing]") {
    std::vector<Clip> clips;
    for (double turn : {0.0, 90.0}) {
        procedural::WalkOptions o;
        o.frame_rate = 60.0;
        o.cycles = 2;
        clips.push_back(procedural::generate_walk({1.2, turn, 0.0}, o).clip);
    }
    const GroupDecoder decoder(pack_group({&clips[0], &clips[1]}, kArchiveAccessOptions).bytes);
    CHECK_THROWS_AS(PoseSampler(decoder, 0), InvalidArgument);
    PoseSampler sampler(decoder, 1);
    CHECK(sampler.capacity() == 1);
    const std::size_t frames = decoder.frame_count(0);
    std::vector<double> row(sampler.channel_count()), expected(sampler.channel_count());
    for (std::size_t f = 0; f < frames; ++f) {
        sampler.pose(0, f, row.data());
        decoder.decode_pose(0, f, expected.data());
        CHECK(same_bits(row.data(), expected.data(), row.size()));
    }
    // One window decoded per W frames, every other pose a hit.
    CHECK(sampler.misses() == decoder.window_count(0));
    CHECK(sampler.hits() == frames - decoder.window_count(0));
    CHECK_THROWS_AS(sampler.pose(0, frames), InvalidArgument);
    CHECK_THROWS_AS(sampler.pose(2, 0), InvalidArgument);
    sampler.clear();
    CHECK(sampler.hits() + sampler.misses() == 0);
    sampler.pose(1, 0, row.data());
    decoder.decode_pose(1, 0, expected.data());
    CHECK(same_bits(row.data(), expected.data(), row.size()));
}

TEST_CASE("PoseIndex: bad indices are refused, threads sharing one index decode the decoder's bits", "[packing]") {
    std::vector<Clip> clips;
    for (double turn : {0.0, 90.0, -45.0}) {
        procedural::WalkOptions o;
        o.frame_rate = 60.0;
        o.cycles = 3;
        clips.push_back(procedural::generate_walk({1.2, turn, 0.0}, o).clip);
    }
    const GroupDecoder decoder(pack_group({&clips[0], &clips[1], &clips[2]}, kArchiveAccessOptions).bytes);
    const PoseIndex index(decoder);
    CHECK(index.memory_bytes() >= index.coefficient_count() * 2);
    std::vector<double> row(decoder.skeleton(0)->channel_count());
    CHECK_THROWS_AS(index.pose(0, decoder.frame_count(0), row.data()), InvalidArgument);
    CHECK_THROWS_AS(index.pose(3, 0, row.data()), InvalidArgument);
    LocalPose local;
    CHECK_THROWS_AS(index.local_pose(3, 0, local), InvalidArgument);
    // Every frame, from two threads at once in opposite orders, against decode_pose.
    std::vector<std::pair<std::size_t, std::size_t>> frames;
    for (std::size_t k = 0; k < decoder.clip_count(); ++k)
        for (std::size_t f = 0; f < decoder.frame_count(k); ++f) frames.emplace_back(k, f);
    std::size_t mismatches[2] = {0, 0};
    auto run = [&](int id) {
        std::vector<double> mine(row.size()), expected(row.size());
        for (std::size_t i = 0; i < frames.size(); ++i) {
            const auto& [k, f] = frames[id == 0 ? i : frames.size() - 1 - i];
            index.pose(k, f, mine.data());
            decoder.decode_pose(k, f, expected.data());
            if (!same_bits(mine.data(), expected.data(), mine.size())) ++mismatches[id];
        }
    };
    std::thread other(run, 1);
    run(0);
    other.join();
    CHECK(mismatches[0] == 0);
    CHECK(mismatches[1] == 0);
}
