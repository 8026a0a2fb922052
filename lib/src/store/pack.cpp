#include "mocapdb/store/pack.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "mocapdb/core/error.hpp"
#include "mocapdb/motion/forward_kinematics.hpp"
#include "mocapdb/packing/error_stats.hpp"
#include "mocapdb/packing/group_decoder.hpp"
#include "mocapdb/packing/group_split.hpp"
#include "mocapdb/packing/measured_pack.hpp"
#include "mocapdb/packing/packed_group.hpp"

namespace mocapdb {
namespace {

std::string number(double x) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", x);
    return text;
}

double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

namespace {

double ratio(std::uint64_t reference, std::uint64_t bytes) {
    return bytes > 0 ? static_cast<double>(reference) / static_cast<double>(bytes) : 0.0;
}

}  // namespace

double PackDatabaseOutcome::ratio_float32() const { return ratio(float32_bytes, tier.bytes); }

double PackDatabaseOutcome::group_ratio_float32(std::size_t group) const {
    return ratio(group_float32_bytes.at(group), tier.groups.at(group).bytes);
}

double PackDatabaseOutcome::bytes_per_second() const {
    return motion_seconds > 0 ? static_cast<double>(tier.bytes) / motion_seconds : 0.0;
}

PackDatabaseOutcome pack_database(const std::filesystem::path& db, const PackDatabaseOptions& options,
                                  const ProgressCallback& progress) {
    const auto start = std::chrono::steady_clock::now();
    const double E = options.max_error_cm;
    if (!std::isfinite(E) || !(E > 0.0))
        throw InvalidArgument("pack: --max-error-cm must be a finite number > 0 (the bound on every joint's error, cm), found " +
                              number(E));
    if (options.threads < 1) throw InvalidArgument("pack: threads must be >= 1, found " + std::to_string(options.threads));
    std::error_code ec;
    if (!std::filesystem::exists(db, ec)) throw IoError(db.string() + ": no such file");

    DatabaseWriter writer(db, DatabaseWriter::Mode::OpenOrCreate, options.wait_seconds);
    const Database& view = writer.view();
    PackDatabaseOutcome out;
    if (const auto old = view.packed()) {
        if (!options.replace)
            throw StoreError(db.string(), "/packed",
                             "the database already has a packed tier (max error " + number(old->max_error_cm) +
                                 " cm); replace it explicitly (mocapdb pack --force)");
        for (const ClipRecord& r : view.clips())
            if (!r.lossless)
                throw StoreError(db.string(), "/packed",
                                 "the packed tier is the only copy of clip '" + r.id +
                                     "' (its lossless channels were dropped); it cannot be replaced");
        out.replaced = true;
        out.replaced_max_error_cm = old->max_error_cm;
    }

    // Group by what pack_group needs (topology and frame rate) from metadata and skeletons alone:
    // channels are read one group at a time.
    const std::vector<ClipRecord> records = view.clips();
    std::vector<Clip> heads(records.size());
    std::vector<const Clip*> head_ptrs;
    std::uint64_t total_frames = 0;
    std::map<std::string, std::shared_ptr<const Skeleton>> skeletons;  // a few per collection
    for (std::size_t i = 0; i < records.size(); ++i) {
        auto& skeleton = skeletons[records[i].skeleton];
        if (!skeleton) skeleton = view.load_skeleton(records[i].skeleton);
        heads[i].skeleton = skeleton;
        heads[i].frame_rate = records[i].frame_rate;
        heads[i].name = records[i].id;
        head_ptrs.push_back(&heads[i]);
        total_frames += records[i].frames;
    }
    std::vector<std::vector<std::size_t>> groups;
    for (const std::vector<std::size_t>& g : packing::group_clips(head_ptrs)) {
        std::vector<std::size_t> frames;
        for (std::size_t i : g) frames.push_back(records[i].frames);
        for (std::vector<std::size_t>& part : packing::split_by_frames(g, frames, options.max_group_frames))
            groups.push_back(std::move(part));
    }

    packing::PackOptions po;
    po.max_error_cm = E;
    po.threads = options.threads;
    PackedTierRecord& tier = out.tier;
    tier.max_error_cm = E;
    std::vector<std::vector<std::uint8_t>> group_bytes;
    packing::ErrorAccumulator all(E);
    std::uint64_t frames_before = 0;
    for (const std::vector<std::size_t>& members : groups) {
        const auto group_start = std::chrono::steady_clock::now();
        std::vector<Clip> clips;
        clips.reserve(members.size());
        std::uint64_t group_frames = 0;
        for (std::size_t i : members) {
            clips.push_back(view.load_clip(records[i].id));
            group_frames += clips.back().frame_count();
        }
        std::vector<const Clip*> ptrs;
        for (const Clip& c : clips) ptrs.push_back(&c);
        ProgressCallback group_progress;
        if (progress)
            group_progress = [&](const Progress& p) {
                const double share = p.total > 0 ? static_cast<double>(p.done) / static_cast<double>(p.total) : 0.0;
                progress(Progress{frames_before + static_cast<std::uint64_t>(share * static_cast<double>(group_frames)),
                                  total_frames, p.item});
            };
        // The bound is checked on what is stored, decoded as a reader will, at every source frame
        // (pack_measured repacks below E should a decoded position land above it).
        packing::MeasuredGroup measured = packing::pack_measured(ptrs, po, {}, group_progress);
        const packing::GroupDecoder decoder(measured.packed.bytes);
        PackedGroupRecord r;
        r.skeleton = records[members.front()].skeleton;
        r.frame_rate = clips.front().frame_rate;
        std::uint64_t float32 = 0;
        double group_seconds = 0.0;
        for (std::size_t k = 0; k < clips.size(); ++k) {
            const packing::ErrorStats& e = measured.clip_errors[k];
            PackedClipRecord c;
            c.id = clips[k].name;
            c.frames = clips[k].frame_count();
            c.payload_bytes = decoder.clip_payload_bytes(k);
            c.max_cm = e.max_cm;
            c.p99_cm = e.p99_cm;
            c.rmse_cm = e.rmse_cm;
            r.clips.push_back(std::move(c));
            float32 += static_cast<std::uint64_t>(clips[k].channels.size()) * 4u;
            group_seconds += clips[k].duration();
        }
        const packing::ErrorAccumulator& group_errors = measured.errors;
        packing::PackedGroup& packed = measured.packed;
        out.motion_seconds += group_seconds;
        const packing::ErrorStats ge = group_errors.stats();
        r.max_cm = ge.max_cm;
        r.p99_cm = ge.p99_cm;
        r.rmse_cm = ge.rmse_cm;
        all.merge(group_errors);
        out.group_float32_bytes.push_back(float32);
        out.float32_bytes += float32;
        tier.groups.push_back(std::move(r));
        group_bytes.push_back(std::move(packed.bytes));
        frames_before += group_frames;
        out.group_seconds.push_back(seconds_since(group_start));
        if (progress) progress(Progress{frames_before, total_frames, {}});
    }
    const packing::ErrorStats te = all.stats();
    tier.max_cm = te.max_cm;
    tier.p99_cm = te.p99_cm;
    tier.rmse_cm = te.rmse_cm;
    writer.put_packed(tier, group_bytes);
    out.tier = writer.view().packed().value();  // names, bytes and counts as stored
    if (options.drop_lossless) out.dropped_lossless = writer.drop_lossless();
    writer.commit();
    out.file_bytes = Database(db).file_size();
    out.seconds = seconds_since(start);
    return out;
}

std::size_t drop_lossless_tier(const std::filesystem::path& db, double wait_seconds) {
    std::error_code ec;
    if (!std::filesystem::exists(db, ec)) throw IoError(db.string() + ": no such file");
    DatabaseWriter writer(db, DatabaseWriter::Mode::OpenOrCreate, wait_seconds);
    const std::size_t dropped = writer.drop_lossless();
    writer.commit();
    return dropped;
}

}  // namespace mocapdb
