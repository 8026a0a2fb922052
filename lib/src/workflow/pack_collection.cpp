#include "mocapdb/core/stopwatch.hpp"
#include "mocapdb/workflow/pack_collection.hpp"

#include <chrono>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <cstdio>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "mocapdb/core/error.hpp"
#include "mocapdb/core/remedy.hpp"
#include "mocapdb/motion/forward_kinematics.hpp"
#include "mocapdb/packing/error_stats.hpp"
#include "mocapdb/packing/group_decoder.hpp"
#include "mocapdb/packing/group_split.hpp"
#include "mocapdb/packing/measured_pack.hpp"
#include "mocapdb/packing/packed_group.hpp"

namespace mocapdb::workflow {
namespace {

std::string number(double x) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", x);
    return text;
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

namespace {

// The collection as pack_database groups it: records, and groups of indices into them.
struct Grouping {
    std::vector<ClipRecord> records;
    std::vector<std::vector<std::size_t>> groups;
    std::uint64_t total_frames = 0;
};

Grouping group_collection(const Database& view, std::size_t max_group_frames) {
    // By what pack_group needs (topology and frame rate), from metadata and skeletons alone:
    // channels are read one group at a time.
    Grouping out;
    out.records = view.clips();
    const std::vector<ClipRecord>& records = out.records;
    std::vector<Clip> heads(records.size());
    std::vector<const Clip*> head_ptrs;
    std::map<std::string, std::shared_ptr<const Skeleton>> skeletons;  // a few per collection
    for (std::size_t i = 0; i < records.size(); ++i) {
        auto& skeleton = skeletons[records[i].skeleton];
        if (!skeleton) skeleton = view.load_skeleton(records[i].skeleton);
        heads[i].skeleton = skeleton;
        heads[i].frame_rate = records[i].frame_rate;
        heads[i].name = records[i].id;
        head_ptrs.push_back(&heads[i]);
        out.total_frames += records[i].frames;
    }
    for (const std::vector<std::size_t>& g : packing::group_clips(head_ptrs)) {
        std::vector<std::size_t> frames;
        for (std::size_t i : g) frames.push_back(records[i].frames);
        for (std::vector<std::size_t>& part : packing::split_by_frames(g, frames, max_group_frames))
            out.groups.push_back(std::move(part));
    }
    return out;
}

// The whole collection packed at E in memory (nothing written): the tier's records, its groups'
// bytes and the outcome's figures.
struct PackedCollection {
    PackDatabaseOutcome outcome;
    std::vector<std::vector<std::uint8_t>> group_bytes;
};

PackedCollection pack_collection(const Database& view, const Grouping& grouping, double E,
                                 const PackDatabaseOptions& options, const ProgressCallback& progress) {
    packing::PackOptions po;
    po.max_error_cm = E;
    po.threads = options.threads;
    po.format = options.format;
    PackedCollection pc;
    PackDatabaseOutcome& out = pc.outcome;
    PackedTierRecord& tier = out.tier;
    tier.max_error_cm = E;
    packing::ErrorAccumulator all(E);
    std::uint64_t frames_before = 0;
    const std::vector<ClipRecord>& records = grouping.records;
    for (const std::vector<std::size_t>& members : grouping.groups) {
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
                                  grouping.total_frames, p.item});
            };
        // The bound is checked on what is stored, decoded as a reader will, at every source frame
        // (pack_measured repacks below E should a decoded position land above it).
        packing::MeasuredGroup measured = packing::pack_measured(ptrs, po, {}, group_progress);
        const packing::GroupDecoder decoder(measured.packed.bytes);
        PackedGroupRecord r;
        r.skeleton = records[members.front()].skeleton;
        r.frame_rate = clips.front().frame_rate;
        r.bytes = measured.packed.bytes.size();
        r.frames = group_frames;
        std::uint64_t float32 = 0;
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
            out.motion_seconds += clips[k].duration();
        }
        const packing::ErrorStats ge = measured.errors.stats();
        r.max_cm = ge.max_cm;
        r.p99_cm = ge.p99_cm;
        r.rmse_cm = ge.rmse_cm;
        all.merge(measured.errors);
        out.group_float32_bytes.push_back(float32);
        out.float32_bytes += float32;
        tier.bytes += r.bytes;
        tier.clips += r.clips.size();
        tier.frames += group_frames;
        tier.groups.push_back(std::move(r));
        packing::add_parts(out.parts, measured.packed.stats.parts);
        out.group_parts.push_back(std::move(measured.packed.stats.parts));
        pc.group_bytes.push_back(std::move(measured.packed.bytes));
        frames_before += group_frames;
        out.group_seconds.push_back(seconds_since(group_start));
        out.group_formats.push_back(decoder.format());
        out.group_windows.push_back(static_cast<int>(decoder.window_length()));
        if (progress) progress(Progress{frames_before, grouping.total_frames, {}});
    }
    const packing::ErrorStats te = all.stats();
    tier.max_cm = te.max_cm;
    tier.p99_cm = te.p99_cm;
    tier.rmse_cm = te.rmse_cm;
    return pc;
}

// E to three significant digits (the bounds a budget search tries read as the user would type them).
double three_digits(double E) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3g", E);
    return std::strtod(text, nullptr);
}

// The smallest E (to about 2 %) whose packed bytes fit options.max_bytes: bracketed by factors of 10
// from 1 cm, then narrowed by interpolating log bytes against log E (kept inside the bracket's middle
// so that it always shrinks). Only E that were packed are returned: the bytes are those measured.
PackedCollection pack_to_budget(const Database& view, const Grouping& grouping, const PackDatabaseOptions& options,
                                const ProgressCallback& progress, PackDatabaseOutcome::Budget& budget) {
    const std::uint64_t N = options.max_bytes;
    budget.max_bytes = N;
    std::optional<PackedCollection> fit;    // the smallest E that fits so far
    double fail_E = 0.0, fail_bytes = 0.0;  // the largest E that does not fit so far (0: none)
    auto attempt = [&](double E) {
        std::optional<PackedCollection> pc;
        try {
            pc = pack_collection(view, grouping, E, options, progress);
        } catch (const packing::PackingFailed&) {
            // So fine a bound that even source rows miss it with the stored skeleton: too fine.
            budget.tried.push_back({E, 0, false});
            if (E > fail_E) fail_E = E, fail_bytes = std::numeric_limits<double>::infinity();
            return;
        }
        const std::uint64_t bytes = pc->outcome.tier.bytes;
        const bool fits = bytes <= N;
        budget.tried.push_back({E, bytes, fits});
        if (fits && (!fit || E < fit->outcome.tier.max_error_cm)) fit = std::move(pc);
        else if (!fits && E > fail_E) fail_E = E, fail_bytes = static_cast<double>(bytes);
    };
    attempt(1.0);
    if (fit) {
        while (fail_E == 0.0 && fit->outcome.tier.max_error_cm > kFinestBudgetErrorCm)
            attempt(std::max(kFinestBudgetErrorCm, fit->outcome.tier.max_error_cm / 10.0));
    } else {
        for (double E = 10.0; !fit; E = std::min(kCoarsestBudgetErrorCm, E * 10.0)) {
            attempt(E);
            if (!fit && E >= kCoarsestBudgetErrorCm)
                throw BudgetUnreachable("pack: even at a max error of " + number(E) + " cm the packed tier takes " +
                                        number(fail_bytes) + " bytes, over the budget of " + std::to_string(N) +
                                        " bytes (" + number(fail_bytes) +
                                        " bytes is the smallest this collection packs to)");
        }
    }
    while (fail_E > 0.0 && fit->outcome.tier.max_error_cm / fail_E > 1.02) {
        const double hi = fit->outcome.tier.max_error_cm, hi_bytes = static_cast<double>(fit->outcome.tier.bytes);
        double t = 0.5;  // where log N lies between the bracket's log bytes, in log E
        if (std::isfinite(fail_bytes) && fail_bytes > hi_bytes && hi_bytes > 0.0)
            t = (std::log(static_cast<double>(N)) - std::log(hi_bytes)) / (std::log(fail_bytes) - std::log(hi_bytes));
        t = std::clamp(t, 0.2, 0.8);
        const double E = three_digits(std::exp(std::log(hi) + t * (std::log(fail_E) - std::log(hi))));
        if (!(E < hi && E > fail_E)) break;  // three digits cannot split the bracket further
        attempt(E);
    }
    return std::move(*fit);
}

}  // namespace

PackDatabaseOutcome pack_database(const std::filesystem::path& db, const PackDatabaseOptions& options,
                                  const ProgressCallback& progress) {
    const auto start = std::chrono::steady_clock::now();
    const double E = options.max_error_cm;
    const bool to_budget = options.max_bytes > 0;
    if (!to_budget && (!std::isfinite(E) || !(E > 0.0)))
        throw InvalidArgument(
            "pack: the max error must be a finite number > 0 (the bound on every joint's error, cm), found " +
            number(E));
    if (options.threads < 1)
        throw InvalidArgument("pack: threads must be >= 1, found " + std::to_string(options.threads));
    std::error_code ec;
    if (!std::filesystem::exists(db, ec)) throw IoError(db.string() + ": no such file");

    DatabaseWriter writer(db, DatabaseWriter::Mode::OpenOrCreate, options.wait_seconds);
    const Database& view = writer.view();
    bool replaced = false;
    double replaced_max_error_cm = 0.0;
    if (const auto old = view.packed()) {
        if (!options.replace)
            throw Refused<StoreError>(Remedy::Overwrite, db.string(), "/packed",
                                      "the database already has a packed tier (max error " + number(old->max_error_cm) +
                                          " cm), replaced only on request");
        for (const ClipRecord& r : view.clips())
            if (!r.lossless)
                throw StoreError(db.string(), "/packed",
                                 "the packed tier is the only copy of clip '" + r.id +
                                     "' (its lossless channels were dropped); it cannot be replaced");
        replaced = true;
        replaced_max_error_cm = old->max_error_cm;
    }

    const Grouping grouping = group_collection(view, options.max_group_frames);
    PackDatabaseOutcome::Budget budget;
    PackedCollection pc = to_budget ? pack_to_budget(view, grouping, options, progress, budget)
                                    : pack_collection(view, grouping, E, options, progress);
    PackDatabaseOutcome out = std::move(pc.outcome);
    if (to_budget) out.budget = std::move(budget);
    out.replaced = replaced;
    out.replaced_max_error_cm = replaced_max_error_cm;
    writer.put_packed(out.tier, pc.group_bytes);
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

}  // namespace mocapdb::workflow
