// mocapdb report: the rate–distortion table of a set (Tucker against the baselines, one run).
#include <cstdio>
#include <ostream>

#include "commands.hpp"
#include "output_files.hpp"
#include "json_writer.hpp"
#include "mocapdb/io/text_file.hpp"
#include "pipeline.hpp"

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
    const SetContext c = load_set_context(Database(a.db), a.set);
    compression::RateOptions options;
    if (!a.targets.empty()) options.max_cm = a.targets;
    else if (a.sweep) options.max_cm = {10, 5, 2, 1, 0.5, 0.2, 0.1, 0.05};
    options.quantization_bits = a.bits;
    options.hooi = !a.no_hooi;
    const RateOutcome r = rate_report(c, options);

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
        j.begin_object();
        j.key("set").value(a.set);
        j.key("dims").begin_array();
        for (auto d : r.report.dims) j.value(static_cast<long long>(d));
        j.end_array();
        j.key("raw_bytes").value(static_cast<long long>(r.report.raw_bytes));
        j.key("raw_clip_bytes").value(static_cast<long long>(r.clip_bytes));
        j.key("side_bytes").value(static_cast<long long>(r.report.side_bytes));
        j.key("seconds_of_motion").value(r.seconds);
        write_rate_rows_json(j, r);
        j.end_object();
        std::fputs(j.str().c_str(), stdout);
        return;
    }
    std::fputs(rate_table_text(a.set, r).c_str(), stdout);
}

}  // namespace

void setup_report(CLI::App& app) {
    auto a = std::make_shared<ReportArgs>();
    CLI::App* cmd = app.add_subcommand("report", "Rate-distortion table of a set: Tucker against PCA, zfp, deflate");
    cmd->footer(
        "Examples:\n"
        "  mocapdb report db.h5 --set walks\n"
        "  mocapdb report db.h5 --set walks --sweep --csv rd.csv --svg rd.svg --json\n"
        "Each row is the cheapest setting of a method whose measured max joint-position error (forward\n"
        "kinematics, every joint, frame and sample of the aligned set) meets the target (default 1 and\n"
        "0.1 cm; --sweep: 10 to 0.05 cm). Bytes count everything needed to rebuild the samples with their\n"
        "timing and parameters (lib/include/mocapdb/compression/rate_distortion.hpp).");
    cmd->add_option("db", a->db, "database file")->required()->check(CLI::ExistingFile);
    cmd->add_option("--set", a->set, "motion set (aligned)")->required();
    auto* targets = cmd->add_option("--targets", a->targets, "max-error targets in cm, comma separated")
                        ->delimiter(',')
                        ->check(CLI::PositiveNumber);
    cmd->add_flag("--sweep", a->sweep, "targets 10, 5, 2, 1, 0.5, 0.2, 0.1, 0.05 cm")->excludes(targets);
    cmd->add_option("--bits", a->bits, "quantization bits of tucker+residual")->check(CLI::Range(4, 16));
    cmd->add_flag("--no-hooi", a->no_hooi, "skip the HOOI rows");
    cmd->add_option("--csv", a->csv, "also write the table as CSV");
    cmd->add_option("--svg", a->svg, "also write ratio against max error as an SVG chart");
    cmd->add_flag("--json", a->json, "print the table as JSON");
    cmd->add_flag("--force", a->force, "overwrite existing --csv/--svg files");
    cmd->callback([a] { run_report(*a); });
}

}  // namespace mocapdb::cli
