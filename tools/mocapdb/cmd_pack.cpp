// mocapdb pack DB.h5 --max-error-cm E | --max-bytes N: store every clip in the database's error-bounded
// packed tier (at E, or at the smallest E whose bytes fit N).
#include <cstdint>
#include <cstdio>
#include <limits>

#include "byte_parts_output.hpp"
#include "commands.hpp"
#include "json_writer.hpp"
#include "mocapdb_json/step_json.hpp"
#include "mocapdb/workflow/pack_collection.hpp"
#include "progress_bar.hpp"

namespace mocapdb::cli {
namespace {

struct PackArgs {
    std::string db;
    double max_error_cm = 0.0;
    std::uint64_t max_bytes = 0;  ///< --max-bytes (0: not given)
    int threads = 2;
    std::string format = "runtime";
    bool json = false;
    bool force = false;
    bool drop_lossless = false;
    bool has_bound = false;  ///< --max-error-cm or --max-bytes was given
};

void print_json(const std::string& db, const workflow::PackDatabaseOutcome& o) {
    JsonWriter j;
    json::write_pack(j, db, o);
    std::fputs(j.str().c_str(), stdout);
}

void print_text(const std::string& db, const workflow::PackDatabaseOutcome& o) {
    const PackedTierRecord& t = o.tier;
    std::printf(
        "packed %zu clips (%zu frames, %.1f s of motion) of %s at max error %g cm%s: %zu bytes, %.1f:1 against "
        "float32 channels; max %.4f cm, p99 %.4f cm, RMSE %.4f cm; %.2f s; file now %.2f MB\n",
        t.clips, t.frames, o.motion_seconds, db.c_str(), t.max_error_cm,
        o.replaced ? " (replacing the earlier packed tier)" : "", static_cast<std::size_t>(t.bytes), o.ratio_float32(),
        t.max_cm, t.p99_cm, t.rmse_cm, o.seconds, static_cast<double>(o.file_bytes) / 1e6);
    if (o.budget)
        std::printf("budget %zu bytes: the smallest max error that fits is %g cm (%zu bytes, %zu E tried)\n",
                    static_cast<std::size_t>(o.budget->max_bytes), t.max_error_cm, static_cast<std::size_t>(t.bytes),
                    o.budget->tried.size());
    std::printf("bytes by part: %s\n", parts_text(o.parts).c_str());
    if (o.dropped_lossless > 0)
        std::printf("dropped the lossless channels of %zu clips: they are now stored within %g cm only\n",
                    o.dropped_lossless, t.max_error_cm);
    if (t.groups.empty()) return;
    std::printf("\n%-6s %-16s %8s %6s %9s %-11s %11s %8s %9s %9s %9s\n", "group", "skeleton", "rate Hz", "clips",
                "frames", "format", "bytes", "ratio", "max cm", "p99 cm", "rmse cm");
    for (std::size_t g = 0; g < t.groups.size(); ++g) {
        const PackedGroupRecord& r = t.groups[g];
        const std::string format = (o.group_formats.at(g) == packing::PackFormat::Runtime ? "runtime W" : "archive W") +
                                   std::to_string(o.group_windows.at(g));
        std::printf("%-6s %-16s %8.6g %6zu %9zu %-11s %11zu %7.1f:1 %9.4f %9.4f %9.4f\n", r.name.c_str(),
                    r.skeleton.c_str(), r.frame_rate, r.clips.size(), r.frames, format.c_str(),
                    static_cast<std::size_t>(r.bytes), o.group_ratio_float32(g), r.max_cm, r.p99_cm, r.rmse_cm);
    }
}

void run_pack(const PackArgs& a) {
    if (!a.has_bound && a.drop_lossless) {  // no --max-error-cm: drop against the stored tier
        const std::size_t dropped = workflow::drop_lossless_tier(a.db);
        if (a.json) {
            JsonWriter j;
            json::write_dropped_lossless(j, a.db, dropped);
            std::fputs(j.str().c_str(), stdout);
        } else {
            std::printf(
                "dropped the lossless channels of %zu clips of %s: they are now stored in the packed tier only\n",
                dropped, a.db.c_str());
        }
        return;
    }
    workflow::PackDatabaseOptions options;
    options.drop_lossless = a.drop_lossless;
    options.max_error_cm = a.max_error_cm;
    options.max_bytes = a.max_bytes;
    options.threads = a.threads;
    options.format = a.format == "archive" ? packing::PackFormat::Archive : packing::PackFormat::Runtime;
    options.replace = a.force;
    workflow::PackDatabaseOutcome o;
    {
        ProgressBar bar("pack");
        o = workflow::pack_database(a.db, options, bar.callback());
    }
    if (a.json) {
        print_json(a.db, o);
    } else {
        print_text(a.db, o);
    }
}

}  // namespace

void setup_pack(CLI::App& app) {
    auto a = std::make_shared<PackArgs>();
    CLI::App* cmd =
        app.add_subcommand("pack", "Store every clip in the database's error-bounded packed tier (/packed)");
    cmd->footer(
        "Groups the clips by skeleton topology and frame rate, packs each group so that every joint and\n"
        "end site of every source frame is within --max-error-cm of the source clip (forward kinematics,\n"
        "world frame), and stores the groups under /packed (schemas/format-v4.md §9) in one atomic\n"
        "session. The lossless clips stay; the figures are measured by decoding the stored bytes.\n"
        "--format runtime (default) stores groups from which one pose decodes in about a microsecond\n"
        "(keys and detail levels, static codes; a group it cannot hold within E is stored as archive);\n"
        "--format archive stores whole windows range-coded: smaller at fine E, a pose costs 15-100 us.\n"
        "An existing packed tier is replaced only with --force.\n"
        "--max-bytes N instead packs to a byte budget: the smallest E (3 significant digits, to about 2 %,\n"
        "between 0.001 and 100 cm) whose bytes fit N, found by packing the collection in memory at several E\n"
        "(only the E chosen is written); it prints the E reached and fails, naming the smallest size\n"
        "reachable, when even 100 cm does not fit.\n"
        "--drop-lossless then removes the lossless channels of every packed clip, so the file is small;\n"
        "those clips are afterwards decoded from the packed tier (within E), the tier can no longer be\n"
        "replaced or removed, and export needs --from-packed for them. Without --max-error-cm it drops\n"
        "against the tier already stored.\n"
        "JSON keys: file, max_error_cm, bytes (everything the decoder needs), float32_bytes,\n"
        "ratio_float32, clips, frames, max_cm, p99_cm, rmse_cm, motion_seconds, bytes_per_second,\n"
        "replaced, dropped_lossless_clips, file_bytes, seconds, parts (bytes per kind of stored data:\n"
        "header, topology, skeletons, constant_dofs, bases, clip_table; runtime: checksum, body_header,\n"
        "code_tables, offsets, payload, slack; archive: contexts, window_table, payload, raw_windows;\n"
        "they sum to bytes), budget ({max_bytes, max_error_cm, tried[] {max_error_cm, bytes, fits}} or\n"
        "null), groups[] (name, path, skeleton, frame_rate, the same figures, format \"runtime\" or\n"
        "\"archive\", window: frames from key to key or per window, and parts).\n"
        "Examples:\n"
        "  mocapdb pack cmu.h5 --max-error-cm 1\n"
        "  mocapdb pack cmu.h5 --max-error-cm 0.5 --force --json\n"
        "  mocapdb pack cmu.h5 --max-error-cm 0.5 --drop-lossless\n"
        "  mocapdb pack cmu.h5 --max-bytes 5000000 --force\n"
        "  mocapdb export cmu.h5 --clip 16_15 --from-packed -o 16_15.bvh");
    cmd->add_option("db", a->db, "database file")->required()->check(CLI::ExistingFile);
    auto* bound =
        cmd->add_option("--max-error-cm", a->max_error_cm, "E: bound on every joint's position error (cm, > 0)");
    auto* budget = cmd->add_option("--max-bytes", a->max_bytes,
                                   "N: pack at the smallest max error whose bytes fit N (instead of --max-error-cm)")
                       ->check(CLI::Range(std::uint64_t{1}, std::numeric_limits<std::uint64_t>::max()))
                       ->excludes(bound);
    auto* drop = cmd->add_flag("--drop-lossless", a->drop_lossless,
                               "remove the lossless channels of the packed clips (irreversible)");
    cmd->callback([a, bound, budget, drop] {
        if (bound->count() == 0 && budget->count() == 0 && drop->count() == 0)
            throw CLI::RequiredError(
                "--max-error-cm or --max-bytes (or --drop-lossless alone, to drop against the stored tier)");
        a->has_bound = bound->count() > 0 || budget->count() > 0;
        run_pack(*a);
    });
    cmd->add_option("--threads", a->threads, "encoder threads")->check(CLI::Range(1, 64));
    cmd->add_option("--format", a->format, "runtime (a pose in about a microsecond) or archive (smallest)")
        ->check(CLI::IsMember({"runtime", "archive"}));
    cmd->add_flag("--json", a->json, "print one JSON object");
    cmd->add_flag("--force", a->force, "replace an existing packed tier");
}

}  // namespace mocapdb::cli
