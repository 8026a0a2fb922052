#include "eval_set_cli.hpp"

#include <cmath>
#include <cstdio>
#include <optional>
#include <ostream>

#include "json_writer.hpp"
#include "mocapdb/eval/set_evaluation.hpp"
#include "mocapdb/io/text_file.hpp"
#include "mocapdb_json/set_evaluation_json.hpp"
#include "output_files.hpp"
#include "progress_bar.hpp"
#include "svg_plot.hpp"

namespace mocapdb::cli {
namespace {

std::string cell(const std::optional<double>& v, const char* format) {
    if (!v) return "n/a";
    char s[32];
    std::snprintf(s, sizeof s, format, *v);
    return s;
}

// "hit/folds", or n/a without measured parameters.
std::string hits(const std::optional<double>& rate, std::size_t folds) {
    if (!rate) return "n/a";
    return std::to_string(std::lround(*rate * static_cast<double>(folds))) + "/" + std::to_string(folds);
}

void print_table(const eval::SetEvaluation& e) {
    std::printf("eval set '%s' of %s: %zu samples, %zu leave-one-out folds%s, %zu inner folds each; T = %lld\n",
                e.set.c_str(), e.file.c_str(), e.labels.size(), e.folds.size(),
                e.folds.size() < e.labels.size() ? " (evenly spread; --max-folds)" : "", e.inner_folds,
                static_cast<long long>(e.frames));
    if (e.twins.groups.empty()) {
        std::printf("twins: none (no overlapping or duplicated samples)\n");
    } else {
        std::size_t members = 0;
        for (const auto& g : e.twins.groups) members += g.size();
        std::printf("twins: %zu group%s (%zu samples) showing the same frames, left out together\n",
                    e.twins.groups.size(), e.twins.groups.size() == 1 ? "" : "s", members);
    }
    std::printf("%-10s %10s %10s %10s %10s %8s %8s %7s\n", "method", "pose cm", "pose max", "motion cm", "motion max",
                "hits", "rho~err", "picked");
    for (std::size_t q = 0; q < e.methods.size(); ++q) {
        const eval::MethodEvaluation& m = e.methods[q];
        std::printf("%-10s %10.3f %10.2f %10.3f %10.2f %8s %8s %7zu\n", m.spec.name.c_str(), m.loo.pose_mean_cm,
                    m.loo.pose_max_cm, m.loo.mean_cm, m.loo.max_cm, hits(m.hit_rate, e.folds.size()).c_str(),
                    cell(m.rho_pose_pearson, "%+.2f").c_str(), e.chosen.counts[q]);
    }
    const eval::ChosenEvaluation& c = e.chosen;
    std::printf("%-10s %10.3f %10.2f %10.3f %10.2f %8s %8s %7s\n", "chosen", c.pose_mean, c.pose_max, c.motion_mean,
                c.motion_max, hits(c.hit_rate, e.folds.size()).c_str(), "", "");
    if (c.counts.size() > e.methods.size() && c.counts[e.methods.size()] > 0)
        std::printf("%zu fold%s averaged predictors the inner cross-validation could not tell apart\n",
                    c.counts[e.methods.size()], c.counts[e.methods.size()] == 1 ? "" : "s");
    std::printf("chosen - best single (%s): %+.3f cm, paired standard error %s cm over %zu folds\n",
                e.methods[c.best].spec.name.c_str(), c.diff_mean_cm, cell(c.diff_se_cm, "%.3f").c_str(),
                e.folds.size());
    std::printf("pose: mean joint error (cm) with the root's floor position and heading removed; motion: with them\n");
    if (e.parameters_measured) {
        std::string tol;
        for (std::size_t p = 0; p < e.parameter_names.size(); ++p)
            tol += (tol.empty() ? "" : ", ") + e.parameter_names[p] + " " + cell(e.hit_tolerance[p], "%.3g") + " " +
                   e.parameter_units[p];
        std::printf("hits: every parameter measured back on the synthesized clip within %.2f x its SD (%s)\n",
                    e.hit_share, tol.c_str());
    } else {
        std::printf("hits: n/a (the set's parameters were not measured by extractors)\n");
    }
    std::printf(
        "chosen: per fold, the method of lowest pose error in an inner leave-one-out on that fold's training\n"
        "samples (nested cross-validation); docs/evaluation.md\n");
    for (const std::string& s : e.not_evaluated) std::printf("%s\n", s.c_str());
}

std::string plot(const eval::SetEvaluation& e) {
    PlotSpec spec;
    spec.title = "leave-one-out pose error per left-out sample, set " + e.set;
    spec.x_label = "left-out sample (fold)";
    spec.y_label = "mean joint error, pose (cm)";
    spec.log_x = false;
    spec.log_y = false;
    auto series = [&](const std::string& name, const VecX& y) {
        PlotSeries s;
        s.name = name;
        for (Eigen::Index k = 0; k < y.size(); ++k) {
            s.x.push_back(static_cast<double>(k + 1));
            s.y.push_back(y(k));
        }
        spec.series.push_back(std::move(s));
    };
    for (const eval::MethodEvaluation& m : e.methods) series(m.spec.name, m.loo.sample_pose_mean_cm);
    series("chosen", e.chosen.pose_mean_cm);
    spec.note = e.file + ": " + std::to_string(e.folds.size()) + " folds of " + std::to_string(e.labels.size()) +
                " samples, " + std::to_string(e.twins.groups.size()) + " twin groups";
    return render_line_plot(spec);
}

}  // namespace

void run_set_eval(const EvalSetArgs& a) {
    refuse_existing({a.svg}, a.force);
    eval::SetEvaluationOptions options;
    options.max_folds = a.max_folds;
    options.inner_folds = a.inner_folds;
    eval::SetEvaluation e;
    {
        ProgressBar bar("eval " + a.set);
        e = eval::evaluate_stored_set(a.db, a.set, options, bar.callback());
    }
    if (!a.svg.empty()) {
        const std::string svg = plot(e);
        write_file_atomically(a.svg, [&](std::ostream& out) { out << svg; });
    }
    if (a.json) {
        JsonWriter j;
        json::write_set_evaluation(j, e);
        std::fputs(j.str().c_str(), stdout);
        return;
    }
    print_table(e);
    if (!a.svg.empty()) std::printf("wrote %s\n", a.svg.c_str());
}

}  // namespace mocapdb::cli
