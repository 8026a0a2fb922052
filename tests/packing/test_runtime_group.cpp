// The runtime group (format 4, what pack_group writes by default): header and runtime body in one
// buffer, read through GroupDecoder, PoseSampler, PoseIndex and RuntimeDecoder with the same bits by
// every path; within E of the source at every frame; the parts add up; the bytes do not depend on the
// thread count; a damaged body fails its checksum.
#include <catch2/catch.hpp>

#include <cstring>
#include <mutex>
#include <random>
#include <vector>

#include "mocapdb/packing/group_decoder.hpp"
#include "mocapdb/packing/measured_pack.hpp"
#include "mocapdb/packing/packed_group.hpp"
#include "mocapdb/packing/pose_index.hpp"
#include "mocapdb/packing/pose_sampler.hpp"
#include "mocapdb/packing/runtime_decoder.hpp"
#include "mocapdb/packing/runtime_encoder.hpp"
#include "fk_error.hpp"
#include "shared_clips.hpp"
#include "shared_data.hpp"

using namespace mocapdb;
using namespace mocapdb::packing;
using namespace mocapdb::test;

namespace {

bool rg_same_bits(const LocalPose& a, const LocalPose& b) {
    return a.rotations.size() == b.rotations.size() && a.translations.size() == b.translations.size() &&
           std::memcmp(a.rotations.data(), b.rotations.data(), a.rotations.size() * sizeof(Quat)) == 0 &&
           std::memcmp(a.translations.data(), b.translations.data(), a.translations.size() * sizeof(Vec3)) == 0;
}

std::vector<const Clip*> rg_pointers(const std::vector<Clip>& clips) {
    std::vector<const Clip*> out;
    for (const Clip& c : clips) out.push_back(&c);
    return out;
}

std::uint64_t rg_part(const PackStats& s, const std::string& name) {
    for (const BytePart& p : s.parts)
        if (p.name == name) return p.bytes;
    return 0;
}

}  // namespace

TEST_CASE("runtime group: the default format, within E by every reader, the same bits by every path",
          "[packing][shared]") {
    MOCAPDB_REQUIRE_SHARED(datasets_dir() / "cmu-asfamc");
    const std::vector<Clip> clips = read_shared_clips("cmu-asfamc", {"02_01", "05_02", "16_13"}, 200);
    const std::vector<const Clip*> ptrs = rg_pointers(clips);
    for (double E : {1.0, 0.1}) {
        PackOptions o;
        o.max_error_cm = E;
        const PackedGroup packed = pack_group(ptrs, o);
        const PackStats& s = packed.stats;
        INFO("E " << E << ": " << s.bytes << " bytes, W " << s.runtime_window << ", encoder max " << s.error.max_cm);
        REQUIRE(s.format == PackFormat::Runtime);
        CHECK((s.runtime_window == 8 || s.runtime_window == 16));
        CHECK(s.error.max_cm <= E);
        std::uint64_t sum = 0;
        for (const BytePart& p : s.parts) sum += p.bytes;
        CHECK(sum == packed.bytes.size());
        CHECK(s.payload_bytes == rg_part(s, "body_header") + rg_part(s, "code_tables") + rg_part(s, "offsets") +
                                     rg_part(s, "payload") + rg_part(s, "slack"));
        CHECK(rg_part(s, "contexts") == 0);
        CHECK(rg_part(s, "checksum") == 4);

        const GroupDecoder decoder(packed.bytes);
        CHECK(decoder.format() == PackFormat::Runtime);
        REQUIRE(decoder.clip_count() == clips.size());
        CHECK(decoder.window_length() == static_cast<std::size_t>(s.runtime_window));
        const RuntimeDecoder runtime(packed.bytes.data(), packed.bytes.size());
        CHECK(decoder.resident_bytes() >= runtime.resident_bytes());
        std::size_t clip_bytes = 0;
        double decoded_max = 0.0;
        for (std::size_t k = 0; k < clips.size(); ++k) {
            clip_bytes += decoder.clip_payload_bytes(k);
            const double err = max_position_error(clips[k], decoder.decode_clip(k));
            CHECK(err <= E);
            decoded_max = std::max(decoded_max, err);
        }
        CHECK(decoded_max <= s.error.max_cm);
        CHECK(clip_bytes == rg_part(s, "payload"));

        // Every path gives the cold local pose's and the cold row's bits: GroupDecoder, RuntimeDecoder on
        // the same bytes, a PoseIndex, and a PoseSampler asked in random and in sequential order.
        const PoseIndex index(decoder);
        CHECK(index.memory_bytes() == 0);
        PoseSampler sampler(decoder, 4);
        std::mt19937_64 rng(5);
        std::size_t differ = 0, asked = 0;
        LocalPose a, b;
        std::vector<double> row_a, row_b;
        auto compare = [&](std::size_t k, std::size_t f) {
            ++asked;
            decoder.decode_local_pose(k, f, a);
            runtime.decode_local_pose(k, f, b);
            differ += !rg_same_bits(a, b);
            index.local_pose(k, f, b);
            differ += !rg_same_bits(a, b);
            sampler.local_pose(k, f, b);
            differ += !rg_same_bits(a, b);
            const std::size_t channels = decoder.skeleton(k)->channel_count();
            row_a.resize(channels);
            row_b.resize(channels);
            decoder.decode_pose(k, f, row_a.data());
            sampler.pose(k, f, row_b.data());
            differ += std::memcmp(row_a.data(), row_b.data(), channels * sizeof(double)) != 0;
            index.pose(k, f, row_b.data());
            differ += std::memcmp(row_a.data(), row_b.data(), channels * sizeof(double)) != 0;
        };
        for (int i = 0; i < 400; ++i) {
            const std::size_t k = std::uniform_int_distribution<std::size_t>(0, clips.size() - 1)(rng);
            compare(k, std::uniform_int_distribution<std::size_t>(0, decoder.frame_count(k) - 1)(rng));
        }
        for (std::size_t f = 0; f < decoder.frame_count(1); ++f) compare(1, f);
        INFO(asked << " frames asked");
        CHECK(differ == 0);
        CHECK(sampler.hits() > 0);
        CHECK(sampler.misses() > 0);
    }
}

TEST_CASE("runtime group: the bytes do not depend on the thread count; pack_measured reads them", "[packing][shared]") {
    MOCAPDB_REQUIRE_SHARED(datasets_dir() / "cmu-walkrun-pfnn");
    const std::vector<Clip> clips =
        read_shared_clips("cmu-walkrun-pfnn", {"16_13_60fps", "02_01_60fps", "132_35_60fps"}, 240);
    const std::vector<const Clip*> ptrs = rg_pointers(clips);
    PackOptions o;
    o.max_error_cm = 0.5;
    o.threads = 1;
    const PackedGroup one = pack_group(ptrs, o);
    o.threads = 3;
    // Progress from the workers: done never falls, never passes the total, and ends there.
    std::mutex mutex;
    std::vector<Progress> seen;
    const PackedGroup three = pack_group(ptrs, o, [&](const Progress& p) {
        const std::lock_guard<std::mutex> lock(mutex);
        seen.push_back(p);
    });
    CHECK(one.bytes == three.bytes);
    REQUIRE(seen.size() > 3);
    for (std::size_t i = 0; i < seen.size(); ++i) {
        CHECK(seen[i].done <= seen[i].total);
        if (i > 0) CHECK(seen[i].done >= seen[i - 1].done);
    }
    CHECK(seen.back().done == seen.back().total);
    const MeasuredGroup measured = pack_measured(ptrs, o);
    CHECK(measured.packed.bytes == one.bytes);
    CHECK(measured.errors.stats().max_cm <= 0.5);
    CHECK(measured.errors.stats().max_cm == one.stats.error.max_cm);
    // The archive format stays available, and is its own format.
    o.format = PackFormat::Archive;
    const PackedGroup archive = pack_group(ptrs, o);
    CHECK(archive.stats.format == PackFormat::Archive);
    CHECK(GroupDecoder(archive.bytes).format() == PackFormat::Archive);
    CHECK_THROWS_AS(RuntimeDecoder(archive.bytes.data(), archive.bytes.size()), Error);
    RuntimeOptions ro;
    ro.max_error_cm = 0.5;
    CHECK_THROWS_AS(encode_runtime(one.bytes, ptrs, ro), InvalidArgument);
}

TEST_CASE("runtime group: a damaged or truncated group throws at construction (the body's checksum)",
          "[packing][shared]") {
    MOCAPDB_REQUIRE_SHARED(datasets_dir() / "cmu-walkrun-pfnn");
    const std::vector<Clip> clips = read_shared_clips("cmu-walkrun-pfnn", {"16_13_60fps", "02_01_60fps"}, 120);
    PackOptions o;
    o.max_error_cm = 1.0;
    const PackedGroup packed = pack_group(rg_pointers(clips), o);
    const std::size_t body_start = packed.bytes.size() - packed.stats.payload_bytes;
    std::mt19937_64 rng(3);
    std::size_t thrown = 0, trials = 0;
    // One flipped bit anywhere in the body (keys included, which its structure checks cannot see).
    for (; trials < 200; ++trials) {
        std::vector<std::uint8_t> bad = packed.bytes;
        bad[std::uniform_int_distribution<std::size_t>(body_start, bad.size() - 1)(rng)] ^=
            static_cast<std::uint8_t>(1u << std::uniform_int_distribution<int>(0, 7)(rng));
        try {
            const GroupDecoder d(bad);
        } catch (const Error&) {
            ++thrown;
        }
    }
    CHECK(thrown == trials);
    for (std::size_t n : {std::size_t{0}, std::size_t{5}, body_start - 1, body_start, packed.bytes.size() - 1}) {
        INFO("first " << n << " bytes");
        const std::vector<std::uint8_t> cut(packed.bytes.begin(), packed.bytes.begin() + static_cast<std::ptrdiff_t>(n));
        CHECK_THROWS_AS(GroupDecoder(cut), Error);
    }
}
