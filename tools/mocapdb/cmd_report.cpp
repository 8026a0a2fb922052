// mocapdb report: the rate–distortion table of a set (Tucker against the baselines, one run).
#include <algorithm>
#include <cstdio>
#include <sstream>

#include "commands.hpp"
#include "json_writer.hpp"
#include "mocapdb/compression/rate_distortion.hpp"
#include "mocapdb/io/text_file.hpp"
#include "mocapdb/motion/pose_vector.hpp"
#include "set_context.hpp"
#include "svg_plot.hpp"

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
};

std::string ranks_text(const std::vector<long long>& r) {
    std::string s;
    for (std::size_t i = 0; i < r.size(); ++i) s += (i ? "x" : "") + std::to_string(r[i]);
    return s.empty() ? "-" : s;
}

std::string target_text(double t) {
    if (t == 0.0) return "lossless";
    std::ostringstream s;
    s << "<=" << t << "cm";
    return s.str();
}

struct Totals {
    std::uint64_t clip_bytes = 0;  // the samples' source channels as float32
    double seconds = 0.0;
    std::size_t joints = 0;        // joints with rotations (pose-vector joints)
};

void write_json(const ReportArgs& a, const compression::RateReport& r, const Totals& t) {
    JsonWriter j;
    j.begin_object();
    j.key("set").value(a.set);
    j.key("dims").begin_array();
    for (auto d : r.dims) j.value(static_cast<long long>(d));
    j.end_array();
    j.key("raw_bytes").value(static_cast<long long>(r.raw_bytes));
    j.key("raw_clip_bytes").value(static_cast<long long>(t.clip_bytes));
    j.key("side_bytes").value(static_cast<long long>(r.side_bytes));
    j.key("seconds_of_motion").value(t.seconds);
    j.key("rows").begin_array();
    for (const compression::RateRow& row : r.rows) {
        j.begin_object();
        j.key("method").value(row.method);
        j.key("target_cm").value(row.target_cm);
        j.key("target_met").value(row.target_met);
        j.key("ranks").begin_array();
        for (long long k : row.ranks) j.value(k);
        j.end_array();
        j.key("setting").value(row.setting);
        j.key("bytes").value(static_cast<long long>(row.bytes));
        j.key("ratio").value(row.ratio);
        j.key("ratio_clips").value(static_cast<double>(t.clip_bytes) / static_cast<double>(row.bytes));
        j.key("bytes_per_second").value(static_cast<double>(row.bytes) / t.seconds);
        j.key("bits_per_joint_frame")
            .value(8.0 * static_cast<double>(row.bytes) /
                   (static_cast<double>(t.joints) * static_cast<double>(r.dims[1] * r.dims[2])));
        j.key("dof_rmse").value(row.stats.dof_rmse);
        j.key("rmse_cm").value(row.stats.rmse_cm);
        j.key("mean_cm").value(row.stats.mean_cm);
        j.key("max_cm").value(row.stats.max_cm);
        j.key("p99_cm").value(row.stats.p99_cm);
        j.key("worst").begin_object();
        j.key("sample").value(static_cast<long long>(row.stats.worst.sample));
        j.key("frame").value(static_cast<long long>(row.stats.worst.frame));
        j.key("joint").value(row.stats.worst.joint);
        j.end_object();
        j.key("precompute_s").value(row.precompute_s);
        j.key("us_per_pose").value(row.us_per_pose);
        j.key("access").value(row.access);
        j.end_object();
    }
    j.end_array();
    j.end_object();
    std::fputs(j.str().c_str(), stdout);
}

std::string csv_of(const compression::RateReport& r, const Totals& t) {
    std::ostringstream s;
    s.precision(9);
    s << "method,target_cm,target_met,ranks,setting,bytes,ratio,ratio_clips,rmse_cm,mean_cm,max_cm,p99_cm,"
         "precompute_s,us_per_pose,access\n";
    for (const compression::RateRow& row : r.rows)
        s << row.method << ',' << row.target_cm << ',' << (row.target_met ? 1 : 0) << ',' << ranks_text(row.ranks)
          << ',' << row.setting << ',' << row.bytes << ',' << row.ratio << ','
          << static_cast<double>(t.clip_bytes) / static_cast<double>(row.bytes) << ',' << row.stats.rmse_cm << ','
          << row.stats.mean_cm << ',' << row.stats.max_cm << ',' << row.stats.p99_cm << ',' << row.precompute_s << ','
          << row.us_per_pose << ',' << row.access << '\n';
    return s.str();
}

std::string svg_of(const ReportArgs& a, const compression::RateReport& r) {
    PlotSpec spec;
    spec.title = "Set '" + a.set + "': compression ratio against max joint error";
    spec.x_label = "max joint-position error (cm, after forward kinematics), log";
    spec.y_label = "compression ratio (raw aligned float32 / stored bytes), log";
    for (const compression::RateRow& row : r.rows) {
        if (row.target_cm == 0.0 || !row.target_met) continue;
        auto it = std::find_if(spec.series.begin(), spec.series.end(), [&](const PlotSeries& p) { return p.name == row.method; });
        if (it == spec.series.end()) {
            spec.series.push_back({row.method, {}, {}});
            it = spec.series.end() - 1;
        }
        it->x.push_back(row.stats.max_cm);
        it->y.push_back(row.ratio);
    }
    spec.note = "tensor " + std::to_string(r.dims[0]) + " dofs x " + std::to_string(r.dims[1]) + " frames x " +
                std::to_string(r.dims[2]) + " samples; every method charged the same side information; higher is better";
    return render_line_plot(spec);
}

void run_report(const ReportArgs& a) {
    const SetContext c = load_set_context(Database(a.db), a.set);
    compression::RateOptions options;
    if (!a.targets.empty()) options.max_cm = a.targets;
    else if (a.sweep) options.max_cm = {10, 5, 2, 1, 0.5, 0.2, 0.1, 0.05};
    options.parameters = c.set.parameters.cols();
    options.quantization_bits = a.bits;
    options.hooi = !a.no_hooi;
    const compression::RateReport r = compression::rate_distortion(c.aligned.tensor, c.skeleton, options);
    Totals t;
    t.clip_bytes = 4 * c.clip_channel_values;
    t.seconds = c.seconds_of_motion;
    t.joints = PoseLayout(*c.skeleton).rotation_joints().size();

    if (!a.csv.empty()) {
        const std::string text = csv_of(r, t);
        write_file_atomically(a.csv, [&](std::ostream& out) { out << text; });
    }
    if (!a.svg.empty()) {
        const std::string text = svg_of(a, r);
        write_file_atomically(a.svg, [&](std::ostream& out) { out << text; });
    }
    if (a.json) {
        write_json(a, r, t);
        return;
    }
    std::printf("set '%s': %lld dofs x %lld frames x %lld samples (%.1f s of motion); raw aligned float32 %llu bytes, "
                "source channels float32 %llu bytes; every row includes %llu bytes of timing/parameters\n",
                a.set.c_str(), static_cast<long long>(r.dims[0]), static_cast<long long>(r.dims[1]),
                static_cast<long long>(r.dims[2]), t.seconds, static_cast<unsigned long long>(r.raw_bytes),
                static_cast<unsigned long long>(t.clip_bytes), static_cast<unsigned long long>(r.side_bytes));
    std::printf("%-16s %-9s %-10s %10s %8s %9s %9s %9s %11s %11s %s\n", "method", "target", "ranks", "bytes", "ratio",
                "rmse_cm", "p99_cm", "max_cm", "precomp_s", "us/pose", "");
    for (const compression::RateRow& row : r.rows)
        std::printf("%-16s %-9s %-10s %10llu %8.2f %9.4f %9.4f %9.4f %11.4f %11.3f %s%s\n", row.method.c_str(),
                    target_text(row.target_cm).c_str(), ranks_text(row.ranks).c_str(),
                    static_cast<unsigned long long>(row.bytes), row.ratio, row.stats.rmse_cm, row.stats.p99_cm,
                    row.stats.max_cm, row.precompute_s, row.us_per_pose, row.access.c_str(),
                    row.target_met ? "" : "  (target not met)");
    std::printf("us/pose: 'pose' = one pose synthesized from the model; 'stream' = decoding the whole set / poses.\n");
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
    cmd->callback([a] { run_report(*a); });
}

}  // namespace mocapdb::cli
