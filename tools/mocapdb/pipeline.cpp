#include "pipeline.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <optional>
#include <sstream>

#include "mocapdb/core/error.hpp"
#include "mocapdb/dataset/dropout_repair.hpp"
#include "option_lists.hpp"
#include "progress_bar.hpp"
#include "svg_plot.hpp"

namespace mocapdb::cli {
namespace {

std::string megabytes(std::uint64_t bytes) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.1f MB", static_cast<double>(bytes) / 1e6);
    return buffer;
}

std::string target_text(double t) {
    if (t == 0.0) return "lossless";
    std::ostringstream s;
    s << "<=" << t << "cm";
    return s.str();
}

}  // namespace

const std::map<std::string, tensor::TuckerMethod>& tucker_methods() {
    static const std::map<std::string, tensor::TuckerMethod> methods{{"hosvd", tensor::TuckerMethod::Hosvd},
                                                                     {"sthosvd", tensor::TuckerMethod::StHosvd},
                                                                     {"hooi", tensor::TuckerMethod::Hooi}};
    return methods;
}

// ---- import -------------------------------------------------------------------------------------

constexpr std::size_t kListedDuplicates = 10;

ImportOutcome import_clips(const std::filesystem::path& db, const std::vector<std::filesystem::path>& inputs,
                           const workflow::ImportOptions& options, bool force, std::ostream& notes) {
    ImportOutcome o;
    {
        ProgressBar bar("import");
        o = workflow::import_clips(db, inputs, options, force, bar.callback());
    }
    for (const workflow::ImportMessage& m : o.messages)
        std::cerr << "mocapdb: " << (m.kind == workflow::ImportMessage::Kind::Error ? "error: " : "warning: ") << m.text
                  << "\n";
    // A few duplicates are listed; thousands (re-importing a folder) are counted.
    if (o.not_added.size() <= kListedDuplicates) {
        for (const std::string& d : o.not_added) notes << d << "\n";
    } else {
        notes << o.not_added.size() << " files skipped: already stored (same sha256)\n";
    }
    return o;
}

std::string describe_import(const std::filesystem::path& db, const ImportOutcome& o) {
    const workflow::ImportSummary& s = o.summary;
    char line[512];
    if (s.added == 0 && !o.existed) {
        std::snprintf(line, sizeof line, "imported no clip (%zu file%s failed); %s was not created\n", s.failed,
                      s.failed == 1 ? "" : "s", db.string().c_str());
        return line;
    }
    std::snprintf(line, sizeof line,
                  "imported %zu clip%s (%zu skipped as duplicates): %zu frames, %.1f s of motion; read %s in %.2f s "
                  "(%.1f MB/s, %.1f clips/s); %s now holds %zu clips, %s\n",
                  s.added, s.added == 1 ? "" : "s", s.skipped, s.frames, s.seconds, megabytes(s.bytes_read).c_str(),
                  o.seconds, o.seconds > 0 ? static_cast<double>(s.bytes_read) / 1e6 / o.seconds : 0.0,
                  o.seconds > 0 ? static_cast<double>(s.files) / o.seconds : 0.0, db.string().c_str(), o.clips_in_db,
                  megabytes(o.file_bytes).c_str());
    return line;
}

// ---- set create ---------------------------------------------------------------------------------

std::vector<std::pair<std::string, double>> periodic_parameters(const std::vector<std::string>& specs) {
    std::vector<std::pair<std::string, double>> out;
    for (const std::string& spec : specs) {
        const auto eq = spec.find('=');
        double period = 0.0;
        std::size_t used = 0;
        try {
            if (eq != std::string::npos && eq > 0) period = std::stod(spec.substr(eq + 1), &used);
        } catch (const std::exception&) {
            used = 0;
        }
        if (eq == std::string::npos || eq == 0 || used == 0 || eq + 1 + used != spec.size())
            throw InvalidArgument("--periodic '" + spec + "': expected NAME=PERIOD, e.g. bearing=360");
        out.emplace_back(spec.substr(0, eq), period);
    }
    return out;
}

std::vector<std::pair<std::string, std::string>> category_parameters(const std::vector<std::string>& specs) {
    std::vector<std::pair<std::string, std::string>> out;
    for (const std::string& spec : specs) {
        const auto eq = spec.find('=');
        if (eq == std::string::npos || eq == 0 || eq + 1 == spec.size())
            throw InvalidArgument("--category '" + spec + "': expected NAME=REGEX, e.g. 'style=_([a-z]+)_[0-9]+$'");
        out.emplace_back(spec.substr(0, eq), spec.substr(eq + 1));
    }
    return out;
}

SetOutcome create_set(const std::string& db_path, SetRequest r) {
    ProgressBar bar("set create");
    r.progress = bar.callback();
    SetOutcome o = workflow::create_set(db_path, r);
    bar.clear();
    for (const std::string& id : o.skipped)
        std::cerr << "mocapdb: warning: clip '" << id << "' yields no sample (" << r.segment << ") and is left out\n";
    return o;
}

std::string describe_set(const SetOutcome& o) {
    const char* kind = "whole clips";
    if (o.segmentation == Segmentation::GaitCycles) kind = "gait cycles";
    if (o.segmentation == Segmentation::Windows) kind = "windows";
    if (o.segmentation == Segmentation::Flights) kind = "the jump of each clip";
    std::string how = kind;
    if (o.auto_segmentation && o.segmentation == Segmentation::Flights) {
        how += ", chosen because a jump length is measured; --segment none for whole clips";
    } else if (o.auto_segmentation) {
        const std::string share = std::to_string(static_cast<int>(std::lround(100.0 * kAutoGaitShare))) + " %";
        how += o.segmentation == Segmentation::GaitCycles
                   ? ", chosen because most clips have a gait cycle; --segment none for whole clips"
                   : ", chosen because fewer than " + share +
                         " of the clips have a gait cycle or no parameters are measured";
    }
    char line[640];
    std::snprintf(line, sizeof line, "set '%s': %zu samples (%s) from %zu clips, %zu parameters (%s)\n",
                  o.set.name.c_str(), o.set.samples.size(), how.c_str(), o.clips, o.set.parameter_names.size(),
                  o.set.parameter_source.empty() ? "none" : o.set.parameter_source.c_str());
    std::string out = line;
    // Repairs are never silent: one line naming the clips (set show lists joints and frames).
    const RepairSummary repairs = summarize_repairs(o.set.repairs);
    const std::vector<std::string>& clips = repairs.clips;
    if (!clips.empty()) {
        std::string names;
        for (const std::string& c : clips) names += (names.empty() ? "" : ", ") + c;
        const std::size_t frames = repairs.longest_run;
        out += "repaired solver dropouts in " + std::to_string(clips.size()) + " clip" +
               (clips.size() == 1 ? "" : "s") + " (" + std::to_string(o.set.repairs.size()) + " joint runs of up to " +
               std::to_string(frames) + " frames): " + names + "; 'mocapdb set show' lists them\n";
    }
    return out;
}

// ---- align --------------------------------------------------------------------------------------

AlignOutcome align_set(const std::string& db_path, AlignRequest request) {
    ProgressBar read_bar("align: read");
    request.read_progress = read_bar.callback();
    std::optional<ProgressBar> bar;  // started when reading is done, so that its clock counts the alignment
    if (read_bar.enabled())
        request.progress = [&](const Progress& p) {
            if (!bar) {
                read_bar.clear();
                bar.emplace("align");
            }
            bar->update(p);
        };
    return workflow::align_set(db_path, request);
}

std::string describe_alignment(const std::string& set, const AlignOutcome& o) {
    char line[512];
    std::snprintf(line, sizeof line,
                  "aligned set '%s' (%s, reference %s): tensor %lld dofs x %lld frames x %lld samples; "
                  "mean pose distance to the reference %.2f cm; %.2f s\n",
                  set.c_str(), o.aligned.method.c_str(), o.labels[o.aligned.reference].c_str(),
                  static_cast<long long>(o.aligned.dofs()), static_cast<long long>(o.aligned.frames()),
                  static_cast<long long>(o.aligned.samples()), o.distance, o.seconds);
    std::string out = line;
    if (o.phase) {
        std::snprintf(line, sizeof line,
                      "phase check (same forward foot per aligned frame, %s/%s): min %.0f %%, mean %.0f %%",
                      o.phase->feet[0].c_str(), o.phase->feet[1].c_str(), 100.0 * o.phase->min, 100.0 * o.phase->mean);
        out += line;
        const auto low = o.phase->below(0.8);
        std::string ranges;
        for (const auto& [a, b] : low)
            ranges += (ranges.empty() ? "" : ", ") + std::to_string(a) + (a == b ? "" : "-" + std::to_string(b));
        // The remedy (samples cut at one gait phase) is named only when the samples are not cut so already.
        const std::string remedy = o.cut_at_gait_phase
                                       ? "; the samples already start at one gait phase)\n"
                                       : "; for locomotion, samples that start at one gait phase avoid it: set create "
                                         "--segment gait)\n";
        out += low.empty() ? std::string("; no aligned frame below 80 %\n")
                           : "; below 80 % at aligned frames " + ranges +
                                 " (left-foot-forward and right-foot-forward poses blend there" + remedy;
    }
    return out;
}

// ---- compress -----------------------------------------------------------------------------------

CompressOutcome compress_set(const std::string& db, CompressRequest r) {
    ProgressBar bar("compress");
    r.progress = bar.callback();
    r.kernel_progress = bar.callback();  // item "kernel": the synthesis kernel's candidates
    return workflow::compress_set(db, r);
}

std::string describe_compression(const std::string& set, const CompressOutcome& o) {
    const tensor::TuckerModel& t = o.model.tucker;
    char buffer[2048];
    std::snprintf(
        buffer, sizeof buffer,
        "compressed set '%s' (%s): %s -> ranks %s, %s%s\n"
        "  bytes %llu (float32 model + timing/parameters) vs raw aligned float32 %llu: ratio %.2f:1; "
        "model in file %llu bytes\n"
        "  relative error %.3g (HOSVD bound %.3g); joint error: rmse %.3f cm, mean %.3f cm, p99 %.3f cm, "
        "max %.3f cm (sample %lld, frame %lld, %s)\n"
        "  load %.2f s, bases %.2f s, rank search %.2f s, decomposition %.3f s, synthesis kernel %.2f s%s, %.3f us per pose, store %.2f s; %.2f s in all\n",
        set.c_str(), o.criterion.c_str(), ranks_text(o.dims).c_str(), ranks_text(t.ranks).c_str(),
        tensor::to_string(t.method), o.target_met ? "" : " (target NOT met: closest ranks)",
        static_cast<unsigned long long>(o.bytes), static_cast<unsigned long long>(o.raw_bytes), o.ratio(),
        static_cast<unsigned long long>(o.stored_bytes), 1.0 - t.fit, t.error_bound / t.data_norm, o.stats.rmse_cm,
        o.stats.mean_cm, o.stats.p99_cm, o.stats.max_cm, static_cast<long long>(o.stats.worst.sample),
        static_cast<long long>(o.stats.worst.frame), o.stats.worst.joint.c_str(), o.load_s, o.bases_s, o.search_s,
        o.fit_s, o.kernel_s, o.kernel_stored ? "" : (" (not stored: " + o.kernel_not_stored_reason + ")").c_str(),
        o.us_per_pose, o.store_s, o.total_s);
    std::string text = buffer;
    if (o.kernel_stored) {
        const auto n = static_cast<std::size_t>(o.dims[2]);
        text += "  synthesis kernel: " + o.kernel_variogram + " (fit " +
                std::string(kriging::to_string(o.kernel_status)) +
                (o.kernel_fit_samples < n ? "; variogram chosen on " + std::to_string(o.kernel_fit_samples) +
                                                " of the " + std::to_string(n) + " samples"
                                          : std::string()) +
                ")\n";
    }
    if (o.kernel_predictor) text += "  synthesis predictor: " + synthesis::describe(*o.kernel_predictor) + "\n";
    if (o.kernel_edge_warning) text += "  reliability: " + synthesis::describe(*o.kernel_edge_warning) + "\n";
    if (!o.kernel_warning.empty()) text += "  warning: " + o.kernel_warning + "\n";
    return text;
}

// ---- rate-distortion report ---------------------------------------------------------------------

std::string rate_table_text(const std::string& set, const RateOutcome& o) {
    const compression::RateReport& r = o.report;
    std::string text;
    char line[1024];
    std::snprintf(
        line, sizeof line,
        "set '%s': %lld dofs x %lld frames x %lld samples (%.1f s of motion); raw aligned float32 %llu bytes, "
        "source channels float32 %llu bytes; every row includes %llu bytes of timing/parameters\n",
        set.c_str(), static_cast<long long>(r.dims[0]), static_cast<long long>(r.dims[1]),
        static_cast<long long>(r.dims[2]), o.seconds, static_cast<unsigned long long>(r.raw_bytes),
        static_cast<unsigned long long>(o.clip_bytes), static_cast<unsigned long long>(r.side_bytes));
    text += line;
    std::snprintf(line, sizeof line, "%-16s %-9s %-10s %10s %8s %9s %9s %9s %11s %11s %s\n", "method", "target",
                  "ranks", "bytes", "ratio", "rmse_cm", "p99_cm", "max_cm", "precomp_s", "us/pose", "");
    text += line;
    for (const compression::RateRow& row : r.rows) {
        std::snprintf(line, sizeof line, "%-16s %-9s %-10s %10llu %8.2f %9.4f %9.4f %9.4f %11.4f %11.3f %s%s\n",
                      row.method.c_str(), target_text(row.target_cm).c_str(), ranks_text(row.ranks).c_str(),
                      static_cast<unsigned long long>(row.bytes), row.ratio, row.stats.rmse_cm, row.stats.p99_cm,
                      row.stats.max_cm, row.precompute_s, row.us_per_pose, row.access.c_str(),
                      row.target_met ? "" : "  (target not met)");
        text += line;
    }
    text += "us/pose: 'pose' = one pose synthesized from the model; 'stream' = decoding the whole set / poses.\n";
    return text;
}

std::string rate_csv(const RateOutcome& o) {
    std::ostringstream s;
    s.precision(9);
    s << "method,target_cm,target_met,ranks,setting,bytes,ratio,ratio_clips,rmse_cm,mean_cm,max_cm,p99_cm,"
         "precompute_s,us_per_pose,access\n";
    for (const compression::RateRow& row : o.report.rows)
        s << row.method << ',' << row.target_cm << ',' << (row.target_met ? 1 : 0) << ',' << ranks_text(row.ranks)
          << ',' << row.setting << ',' << row.bytes << ',' << row.ratio << ','
          << static_cast<double>(o.clip_bytes) / static_cast<double>(row.bytes) << ',' << row.stats.rmse_cm << ','
          << row.stats.mean_cm << ',' << row.stats.max_cm << ',' << row.stats.p99_cm << ',' << row.precompute_s << ','
          << row.us_per_pose << ',' << row.access << '\n';
    return s.str();
}

std::string rate_svg(const std::string& set, const RateOutcome& o) {
    const compression::RateReport& r = o.report;
    PlotSpec spec;
    spec.title = "Set '" + set + "': compression ratio against max joint error";
    spec.x_label = "max joint-position error (cm, after forward kinematics), log";
    spec.y_label = "compression ratio (raw aligned float32 / stored bytes), log";
    for (const compression::RateRow& row : r.rows) {
        if (row.target_cm == 0.0 || !row.target_met) continue;
        auto it = std::find_if(spec.series.begin(), spec.series.end(),
                               [&](const PlotSeries& p) { return p.name == row.method; });
        if (it == spec.series.end()) {
            spec.series.push_back({row.method, {}, {}});
            it = spec.series.end() - 1;
        }
        it->x.push_back(row.stats.max_cm);
        it->y.push_back(row.ratio);
    }
    spec.note = "tensor " + std::to_string(r.dims[0]) + " dofs x " + std::to_string(r.dims[1]) + " frames x " +
                std::to_string(r.dims[2]) +
                " samples; every method charged the same side information; higher is better";
    return render_line_plot(spec);
}

}  // namespace mocapdb::cli
