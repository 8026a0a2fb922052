// mocapdb report: the rate–distortion table of a set (Tucker against the baselines, one run), or
// with --collection the whole-collection benchmark of the packed tier beside ACL
// (collection_report_cli.hpp).
#include <cstdio>
#include <ostream>

#include "collection_report_cli.hpp"
#include "commands.hpp"
#include "output_files.hpp"
#include "json_writer.hpp"
#include "mocapdb_json/report_json.hpp"
#include "mocapdb/io/text_file.hpp"
#include "mocapdb/store/database.hpp"
#include "mocapdb/workflow/aligned_set_data.hpp"
#include "mocapdb/workflow/set_rate_report.hpp"
#include "pipeline.hpp"
#include "progress_bar.hpp"

namespace mocapdb::cli {
namespace {

struct ReportArgs {
    std::string db;
    std::string set;
    std::vector<double> targets;
    bool sweep = false;
    bool json = false;
    bool no_hooi = false;
    int bits = 12;
    std::string csv;
    std::string svg;
    bool force = false;
};

void run_report(const ReportArgs& a) {
    refuse_existing({a.csv, a.svg}, a.force);
    const workflow::AlignedSetData c = workflow::load_aligned_set(Database(a.db), a.set);
    compression::RateOptions options;
    if (!a.targets.empty()) options.max_cm = a.targets;
    else if (a.sweep) options.max_cm = {10, 5, 2, 1, 0.5, 0.2, 0.1, 0.05};
    options.quantization_bits = a.bits;
    options.hooi = !a.no_hooi;
    ProgressBar bar("report");
    options.progress = bar.callback();
    const RateOutcome r = workflow::rate_report(c, options);
    bar.clear();

    if (!a.csv.empty()) {
        const std::string text = rate_csv(r);
        write_file_atomically(a.csv, [&](std::ostream& out) { out << text; });
    }
    if (!a.svg.empty()) {
        const std::string text = rate_svg(a.set, r);
        write_file_atomically(a.svg, [&](std::ostream& out) { out << text; });
    }
    if (a.json) {
        JsonWriter j;
        json::write_rate_report(j, a.set, r);
        std::fputs(j.str().c_str(), stdout);
        return;
    }
    std::fputs(rate_table_text(a.set, r).c_str(), stdout);
}

}  // namespace

void setup_report(CLI::App& app) {
    auto a = std::make_shared<ReportArgs>();
    auto c = std::make_shared<CollectionReportArgs>();
    auto collection = std::make_shared<bool>(false);
    CLI::App* cmd = app.add_subcommand(
        "report",
        "Rate-distortion table of a set (Tucker against PCA, zfp, deflate), or of the whole collection's packed tier beside ACL");
    cmd->footer(
        "Examples:\n"
        "  mocapdb report db.h5 --set walks\n"
        "  mocapdb report db.h5 --set walks --sweep --csv rd.csv --svg rd.svg --json\n"
        "  mocapdb report cmu.h5 --collection --reference ../shared/reference/acl/cmu-asfamc.csv\n"
        "  mocapdb report cmu.h5 --collection --max-error-cm 1,0.1 --source-dir ../shared/datasets/cmu-asfamc --json\n"
        "With --set:\n"
        "Each row is the cheapest setting of a method whose measured max joint-position error (forward\n"
        "kinematics, every joint, frame and sample of the aligned set) meets the target (default 1 and\n"
        "0.1 cm; --sweep: 10 to 0.05 cm). Bytes count everything needed to rebuild the samples with their\n"
        "timing and parameters (lib/include/mocapdb/compression/rate_distortion.hpp).\n"
        "With --collection: every clip packed in memory per E (default 1, 0.5, 0.1, 0.03, 0.01 cm) as `mocapdb pack`\n"
        "would store it (nothing is written): bytes (everything the decoder needs), ratio to float32\n"
        "channels, bytes per second of motion, bits per joint per frame, max / p99 / RMSE cm measured on\n"
        "the decoded bytes, encode s, decode us per pose (random access) and MB/s (streaming); with\n"
        "--reference (a per-clip ACL table, ../shared/reference/acl/) ACL's bytes at the same max error\n"
        "and RMSE over the same clips (as compare.py) and how many times smaller ours are (below ACL's most\n"
        "precise setting: its bytes there as a lower bound, '>='); the lossless tier (everything the file\n"
        "spends on the clips, HDF5 objects included) beside gzip -9 of the source files (found by name in\n"
        "--source-dir or its subfolders, checked by SHA-256).\n"
        "JSON keys: file, clips, frames, groups, motion_seconds, float32_bytes, threads, random_poses,\n"
        "targets[] (max_error_cm, bytes, parts (bytes per kind of stored data, summing to bytes),\n"
        "float32_bytes, ratio_float32, bytes_per_second, bits_per_joint_frame, max_cm, p99_cm, rmse_cm,\n"
        "encode_seconds, stream_mb_per_second, decode_pose_us, resident_bytes (decoder memory beyond the\n"
        "bytes), indexed_local_pose_us, index_bytes,\n"
        "acl {bytes_at_max, smaller_at_max, bytes_at_rmse, smaller_at_rmse, max_lower_bound,\n"
        "rmse_lower_bound} or null, group_figures[] with parts), lossless {bytes, channel_bytes,\n"
        "ratio_float32, gzip9_bytes, gzip9_ratio_float32, ...},\n"
        "reference {files, comparable, reason, clips_missing, settings[]} or null.");
    cmd->add_option("db", a->db, "database file")->required()->check(CLI::ExistingFile);
    auto* set = cmd->add_option("--set", a->set, "motion set (aligned)");
    auto* whole =
        cmd->add_flag("--collection", *collection, "the whole collection's packed tier (every clip)")->excludes(set);
    auto* targets = cmd->add_option("--targets", a->targets, "max-error targets in cm, comma separated")
                        ->delimiter(',')
                        ->check(CLI::PositiveNumber);
    cmd->add_flag("--sweep", a->sweep, "targets 10, 5, 2, 1, 0.5, 0.2, 0.1, 0.05 cm")->excludes(targets);
    cmd->add_option("--bits", a->bits, "quantization bits of tucker+residual")->check(CLI::Range(4, 16));
    cmd->add_flag("--no-hooi", a->no_hooi, "skip the HOOI rows");
    auto collection_only = [&](CLI::Option* o) { o->needs(whole); };
    collection_only(cmd->add_option("--max-error-cm", c->max_error_cm,
                                    "--collection: bounds E in cm, comma separated (default 1,0.5,0.1,0.03,0.01)")
                        ->delimiter(',')
                        ->check(CLI::PositiveNumber));
    collection_only(cmd->add_option("--reference", c->references, "--collection: per-clip ACL table (CSV); repeatable")
                        ->check(CLI::ExistingFile));
    collection_only(
        cmd->add_option(
               "--source-dir", c->source_dirs,
               "--collection: folder of the clips' source files (subfolders searched), for gzip -9; repeatable")
            ->check(CLI::ExistingDirectory));
    collection_only(
        cmd->add_option("--threads", c->threads, "--collection: encoder threads")->check(CLI::Range(1, 64)));
    collection_only(cmd->add_option("--poses", c->poses, "--collection: random poses timed per E (default 20000)"));
    cmd->add_option("--csv", a->csv, "also write the table as CSV");
    cmd->add_option("--svg", a->svg,
                    "also write an SVG chart (--set: ratio against max error; --collection: bytes against max error)");
    cmd->add_flag("--json", a->json, "print the table as JSON");
    cmd->add_flag("--force", a->force, "overwrite existing --csv/--svg files");
    cmd->callback([a, c, collection, cmd] {
        if (*collection) {
            for (const char* set_only : {"--targets", "--sweep", "--bits", "--no-hooi"})
                if (cmd->count(set_only) > 0)
                    throw CLI::ValidationError(std::string(set_only) + " belongs to --set, not --collection");
            c->db = a->db;
            c->json = a->json;
            c->csv = a->csv;
            c->svg = a->svg;
            c->force = a->force;
            run_collection_report(*c);
        } else if (a->set.empty()) {
            throw CLI::RequiredError("--set NAME or --collection");
        } else {
            run_report(*a);
        }
    });
}

}  // namespace mocapdb::cli
