#include "collection_report_cli.hpp"

#include <algorithm>
#include <cstdio>
#include <limits>
#include <optional>
#include <ostream>
#include <sstream>

#include "byte_parts_output.hpp"
#include "json_writer.hpp"
#include "mocapdb_json/report_json.hpp"
#include "mocapdb/eval/collection_acl.hpp"
#include "mocapdb/io/text_file.hpp"
#include "mocapdb/eval/collection_report.hpp"
#include "output_files.hpp"
#include "progress_bar.hpp"
#include "svg_plot.hpp"

namespace mocapdb::cli {
namespace {

// The ACL side of the report: the aggregated reference and, per E, the comparison.
using Reference = eval::CollectionAcl;

std::string fixed(double v, int decimals) {
    char b[48];
    std::snprintf(b, sizeof b, "%.*f", decimals, v);
    return b;
}

std::string general(double v, int digits = 6) {
    char b[48];
    std::snprintf(b, sizeof b, "%.*g", digits, v);
    return b;
}

// ">=" marks a lower bound (our error below ACL's most precise setting, AclComparison).
std::string opt_bytes(const std::optional<double>& v, bool usable, bool lower_bound) {
    if (!usable) return "n/a";
    return v ? (lower_bound ? ">=" : "") + fixed(*v, 0) : "outside";
}

std::string opt_ratio(const std::optional<double>& v, bool usable, bool lower_bound) {
    if (!usable) return "n/a";
    return v ? (lower_bound ? ">=" : "") + fixed(*v, 2) + "x" : "outside";
}

std::string render_json(const CollectionReportArgs& a, const eval::CollectionReport& r, const Reference& ref) {
    JsonWriter j;
    json::write_collection_report(j, a.db, r, ref);
    return j.str();
}

std::string render_csv(const eval::CollectionReport& r, const Reference& ref) {
    std::ostringstream s;
    s.precision(9);
    s << "tier,max_error_cm,bytes,float32_bytes,ratio_float32,bytes_per_second,bits_per_joint_frame,max_cm,p99_cm,"
         "rmse_cm,encode_s,decode_pose_us,stream_mb_s,acl_bytes_at_max,x_smaller_at_max,acl_bytes_at_rmse,"
         "x_smaller_at_rmse,gzip9_bytes,gzip9_ratio_float32,indexed_local_pose_us,index_bytes,acl_at_max_lower_bound,"
         "acl_at_rmse_lower_bound\n";
    auto cell = [](const std::optional<double>& v) { return v ? general(*v, 9) : std::string(); };
    for (std::size_t t = 0; t < r.targets.size(); ++t) {
        const eval::TargetFigures& tf = r.targets[t];
        const eval::PackedFigures& f = tf.total;
        const eval::AclComparison c = ref.given && ref.unusable.empty() ? ref.per_target[t] : eval::AclComparison{};
        s << "packed," << tf.max_error_cm << ',' << f.bytes << ',' << f.float32_bytes << ',' << f.ratio_float32() << ','
          << f.bytes_per_second() << ',' << f.bits_per_joint_frame() << ',' << f.max_cm << ',' << f.p99_cm << ','
          << f.rmse_cm << ',' << f.encode_seconds << ',' << tf.pose_microseconds << ',' << f.stream_mb_per_second()
          << ',' << cell(c.bytes_at_max) << ',' << cell(c.smaller_at_max) << ',' << cell(c.bytes_at_rmse) << ','
          << cell(c.smaller_at_rmse) << ",,," << tf.indexed_pose_microseconds << ',' << tf.index_bytes << ','
          << (c.max_lower_bound ? 1 : 0) << ',' << (c.rmse_lower_bound ? 1 : 0) << '\n';
    }
    const eval::LosslessFigures& l = r.lossless;
    const double bps = r.lossless_bytes_per_second();
    s << "lossless,0," << l.bytes << ',' << l.float32_bytes << ',' << l.ratio_float32() << ',' << bps
      << ",,0,0,0,,,,,,,," << (l.gzip_available ? std::to_string(l.gzip_bytes) : "") << ','
      << (l.gzip_available ? general(l.gzip_ratio_float32(), 9) : "") << ",,,,\n";
    return s.str();
}

std::string render_svg(const CollectionReportArgs& a, const eval::CollectionReport& r, const Reference& ref) {
    PlotSpec spec;
    spec.title = "Whole collection: bytes against max joint-position error";
    spec.x_label = "measured max joint-position error (cm, forward kinematics, every joint and frame), log";
    spec.y_label = "bytes (everything the decoder needs), log";
    PlotSeries ours{"packed tier (ours)", {}, {}};
    for (const eval::TargetFigures& t : r.targets) {
        ours.x.push_back(t.total.max_cm);
        ours.y.push_back(static_cast<double>(t.total.bytes));
    }
    spec.series.push_back(ours);
    if (ref.given && ref.unusable.empty()) {
        PlotSeries acl{"ACL (reference table)", {}, {}};
        for (const eval::AclSetting& s : ref.acl.settings) {
            acl.x.push_back(s.max_cm);
            acl.y.push_back(static_cast<double>(s.bytes));
        }
        spec.series.push_back(acl);
    }
    // Exact tiers have no error to place on a log axis: drawn flat across the measured range.
    double lo = std::numeric_limits<double>::infinity(), hi = 0.0;
    for (const PlotSeries& s : spec.series)
        for (double x : s.x)
            if (x > 0) {
                lo = std::min(lo, x);
                hi = std::max(hi, x);
            }
    if (hi > 0) {
        if (r.lossless.bytes > 0)
            spec.series.push_back({"lossless tier (exact, flat)",
                                   {lo, hi},
                                   {static_cast<double>(r.lossless.bytes), static_cast<double>(r.lossless.bytes)}});
        if (r.lossless.gzip_available)
            spec.series.push_back(
                {"gzip -9 source text (flat)",
                 {lo, hi},
                 {static_cast<double>(r.lossless.gzip_bytes), static_cast<double>(r.lossless.gzip_bytes)}});
        spec.series.push_back({"float32 channels (flat)",
                               {lo, hi},
                               {static_cast<double>(r.float32_bytes), static_cast<double>(r.float32_bytes)}});
    }
    spec.note = a.db + ": " + std::to_string(r.clips) + " clips, " + std::to_string(r.frames) + " frames, " +
                std::to_string(r.groups) + (r.groups == 1 ? " group" : " groups") + "; lower is better";
    return render_line_plot(spec);
}

std::string render_text(const CollectionReportArgs& a, const eval::CollectionReport& r, const Reference& ref) {
    std::string out;
    char line[512];
    std::snprintf(line, sizeof line,
                  "%s: %zu clips, %zu frames, %.1f s of motion, %zu group%s (skeleton topology x frame rate); "
                  "float32 channels %llu bytes\n",
                  a.db.c_str(), r.clips, r.frames, r.motion_seconds, r.groups, r.groups == 1 ? "" : "s",
                  static_cast<unsigned long long>(r.float32_bytes));
    out += line;
    if (r.clips == 0) out += "the database has no clips: nothing to pack (every figure below is 0)\n";
    if (ref.given) {
        std::string files;
        for (const auto& f : ref.table.files) files += (files.empty() ? "" : ", ") + f.string();
        out += "ACL reference: " + files;
        if (ref.unusable.empty()) {
            out += " (" + std::to_string(ref.acl.requested) + " clips matched; settings";
            for (const eval::AclSetting& s : ref.acl.settings)
                out += " " + general(s.precision_cm) + " cm: " + std::to_string(s.bytes) + " B max " +
                       fixed(s.max_cm, 4) + " rmse " + fixed(s.rmse_cm, 4) + ";";
            out.back() = ')';
            out += "\n";
        } else {
            out += ": no comparison, " + ref.unusable + "\n";
        }
    }
    out += "\n";
    std::snprintf(line, sizeof line, "%6s %11s %8s %8s %8s %9s %9s %9s %7s %8s %7s %7s %12s %9s %12s %9s\n", "E cm",
                  "bytes", "vs f32", "B/s", "bit/j/f", "max cm", "p99 cm", "rmse cm", "enc s", "pose us", "idx us",
                  "MB/s", "ACL B @max", "x smaller", "ACL B @rmse", "x smaller");
    out += line;
    for (std::size_t t = 0; t < r.targets.size(); ++t) {
        const eval::TargetFigures& tf = r.targets[t];
        const eval::PackedFigures& f = tf.total;
        const bool usable = ref.given && ref.unusable.empty();
        const eval::AclComparison c = usable ? ref.per_target[t] : eval::AclComparison{};
        std::snprintf(line, sizeof line,
                      "%6s %11llu %7.2f:1 %8.0f %8.3f %9.5f %9.5f %9.5f %7.2f %8.1f %7.2f %7.1f %12s %9s %12s %9s\n",
                      general(tf.max_error_cm).c_str(), static_cast<unsigned long long>(f.bytes), f.ratio_float32(),
                      f.bytes_per_second(), f.bits_per_joint_frame(), f.max_cm, f.p99_cm, f.rmse_cm, f.encode_seconds,
                      tf.pose_microseconds, tf.indexed_pose_microseconds, f.stream_mb_per_second(),
                      opt_bytes(c.bytes_at_max, usable, c.max_lower_bound).c_str(),
                      opt_ratio(c.smaller_at_max, usable, c.max_lower_bound).c_str(),
                      opt_bytes(c.bytes_at_rmse, usable, c.rmse_lower_bound).c_str(),
                      opt_ratio(c.smaller_at_rmse, usable, c.rmse_lower_bound).c_str());
        out += line;
    }
    const eval::LosslessFigures& l = r.lossless;
    std::snprintf(
        line, sizeof line,
        "\nlossless tier: %llu bytes in the file (channel data %llu, HDF5 objects %llu), %.2f:1 against float32 "
        "channels; ",
        static_cast<unsigned long long>(l.bytes), static_cast<unsigned long long>(l.channel_bytes),
        static_cast<unsigned long long>(l.bytes - std::min(l.bytes, l.channel_bytes)), l.ratio_float32());
    out += line;
    if (l.gzip_available) {
        std::snprintf(line, sizeof line,
                      "gzip -9 of the source text: %llu bytes, %.2f:1 (lossless tier %.2fx smaller)\n",
                      static_cast<unsigned long long>(l.gzip_bytes), l.gzip_ratio_float32(), l.gzip_over_lossless());
        out += line;
    } else {
        out += "gzip -9 of the source text: not available (" + l.gzip_reason + ")\n";
    }
    if (r.groups > 1) {
        out += "\nper group:\n";
        std::snprintf(line, sizeof line, "%6s %-16s %-14s %8s %6s %9s %11s %8s %9s %9s\n", "E cm", "skeleton",
                      "first clip", "rate Hz", "clips", "frames", "bytes", "vs f32", "max cm", "rmse cm");
        out += line;
        for (const eval::TargetFigures& tf : r.targets)
            for (const eval::GroupFigures& g : tf.groups) {
                std::snprintf(line, sizeof line, "%6s %-16s %-14s %8.6g %6zu %9zu %11llu %6.2f:1 %9.5f %9.5f\n",
                              general(tf.max_error_cm).c_str(), g.skeleton.c_str(), g.first_clip.c_str(), g.frame_rate,
                              g.figures.clips, g.figures.frames, static_cast<unsigned long long>(g.figures.bytes),
                              g.figures.ratio_float32(), g.figures.max_cm, g.figures.rmse_cm);
                out += line;
            }
    }
    out +=
        "\nbytes: everything the decoder needs (skeletons, bases, contexts, tables, payloads); errors: FK positions of "
        "every joint and end site at every source frame, decoded vs source; bit/j/f counts end sites as joints; "
        "pose us: random access, one thread, a channel row from the packed bytes; idx us: the same poses as local "
        "transforms through an index of the group held in memory (PoseIndex";
    for (std::size_t t = 0; t < r.targets.size(); ++t)
        out += (t ? ", " : ": ") + fixed(static_cast<double>(r.targets[t].index_bytes) / 1e6, 2) + " MB at " +
               general(r.targets[t].max_error_cm) + " cm";
    out += "); MB/s: float32 channels decoded per second, streaming.\n";
    if (ref.given && ref.unusable.empty())
        out +=
            "ACL: bytes interpolated log-linearly at our measured error over the same clips (as compare.py); "
            "'outside': our error is above ACL's measured range (no extrapolation); '>=': our error is below "
            "that of ACL's most precise setting, whose bytes are given (a lower bound on ACL's bytes at our error).\n";
    return out;
}

}  // namespace

void run_collection_report(const CollectionReportArgs& a) {
    refuse_existing({a.csv, a.svg}, a.force);
    eval::CollectionReportOptions options;
    if (!a.max_error_cm.empty()) options.max_error_cm = a.max_error_cm;
    options.threads = a.threads;
    options.random_poses = a.poses;
    for (const std::string& d : a.source_dirs) options.source_dirs.emplace_back(d);
    Reference ref = eval::read_collection_acl(a.references);
    eval::CollectionReport r;
    {
        const Database db(a.db);
        ProgressBar bar("report");
        r = eval::collection_report(db, options, bar.callback());
    }
    eval::compare_collection_with_acl(ref, r);
    if (!a.csv.empty()) {
        const std::string text = render_csv(r, ref);
        write_file_atomically(a.csv, [&](std::ostream& out) { out << text; });
    }
    if (!a.svg.empty()) {
        const std::string text = render_svg(a, r, ref);
        write_file_atomically(a.svg, [&](std::ostream& out) { out << text; });
    }
    const std::string text = a.json ? render_json(a, r, ref) : render_text(a, r, ref);
    std::fputs(text.c_str(), stdout);
}

}  // namespace mocapdb::cli
