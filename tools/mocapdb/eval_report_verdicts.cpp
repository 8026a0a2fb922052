// The verdict texts of REPORT.md (eval_report_parts.hpp).
#include "eval_report_parts.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>

#include "mocapdb/dataset/dropout_repair.hpp"

namespace mocapdb::cli::eval_report {

// ---------------------------------------------------------------------------------------------------
// REPORT.md

MetricText metric_text(const eval::MetricVerdict& v) {
    switch (v.metric) {
        case eval::Metric::LooPoseMean: return {"leave-one-out mean pose error (root-relative)", " cm"};
        case eval::Metric::LooPoseMax: return {"leave-one-out max pose error (root-relative)", " cm"};
        case eval::Metric::LooMotionMean: return {"leave-one-out mean motion error (with root trajectory)", " cm"};
        case eval::Metric::LooMotionMax: return {"leave-one-out max motion error (with root trajectory)", " cm"};
        case eval::Metric::LooDuration: return {"leave-one-out duration error", " s"};
        case eval::Metric::FootSkating: return {"foot skating of the synthesized motions", " cm/s"};
        case eval::Metric::ConstraintReliableRmse:
            return {"constraint RMSE |c - c_hat| where rho >= " + fmt(v.threshold), " (normalized)"};
        case eval::Metric::ConstraintRmse: return {"constraint RMSE over the whole grid", " (normalized)"};
    }
    return {"", ""};
}

const eval::LooMethodResult* loo_method(const SetResults& r, const std::string& n) {
    for (const auto& m : r.loo.methods)
        if (m.method == n) return &m;
    return nullptr;
}

const eval::ConstraintMethodResult* constraint_method(const SetResults& r, const std::string& n) {
    for (const auto& m : r.constraint.methods)
        if (m.method == n) return &m;
    return nullptr;
}

std::string split_text(const eval::MetricVerdict& v) {
    if (!v.split) return "";
    const eval::EdgeSplit& s = *v.split;
    const std::string contrast =
        v.best.method.rfind("nn-blend", 0) == 0
            ? "Kriging's linear trend extrapolates beyond the remaining samples; the nearest-neighbour blend is a "
              "convex combination of its neighbours and cannot leave them."
            : "RBF has the same linear trend; the two differ in how the residuals are interpolated (fitted "
              "variogram vs cubic B-splines with support twice the nearest-neighbour distance).";
    std::ostringstream w;
    w << "Mean error split by position of the left-out sample: on the " << s.edge_samples
      << " samples at the edge of the parameter range (the fold must extrapolate) " << v.best.method << " "
      << fmt(s.best_edge) << " cm vs " << v.best_kriging.method << " " << fmt(s.kriging_edge) << " cm; on the "
      << s.interior_samples << " interior samples " << fmt(s.best_interior) << " cm vs " << fmt(s.kriging_interior)
      << " cm. ";
    switch (s.location) {
        case eval::LossLocation::BothMoreAtEdge:
            w << "Kriging loses on both groups, more at the edge, where the fold extrapolates. " << contrast;
            break;
        case eval::LossLocation::BothMoreInterior:
            w << "Kriging loses on both groups, more on interior samples, so this is not (only) extrapolation: "
                 "with these samples the fitted variograms and trend predict a left-out motion worse than a "
                 "local blend of its neighbours.";
            break;
        case eval::LossLocation::InteriorOnly:
            w << "The loss is on interior samples only (kriging is better at the edge): with these samples the "
                 "fitted variograms and trend predict an interior motion worse than a local blend of its neighbours.";
            break;
        case eval::LossLocation::EdgeOnly:
            w << "The loss comes from the edge samples only, where the fold extrapolates. " << contrast;
            break;
        case eval::LossLocation::None: break;
    }
    return w.str();
}

std::string why_text(const SetResults& r, const eval::MetricVerdict& v) {
    const eval::EvalSet& s = *r.set;
    switch (v.metric) {
        case eval::Metric::LooPoseMean:
        case eval::Metric::LooMotionMean: return split_text(v);
        case eval::Metric::LooPoseMax: {
            const auto* base = loo_method(r, v.best.method);
            const auto* kr = loo_method(r, v.best_kriging.method);
            if (!base || !kr || base->pose_worst_sample < 0 || kr->pose_worst_sample < 0) return std::string();
            return "A single worst frame over all folds: " + v.best.method + " at " +
                   s.labels[static_cast<std::size_t>(base->pose_worst_sample)] + " frame " +
                   std::to_string(base->pose_worst_frame) + " (" + base->pose_worst_joint + "), " +
                   v.best_kriging.method + " at " + s.labels[static_cast<std::size_t>(kr->pose_worst_sample)] +
                   " frame " + std::to_string(kr->pose_worst_frame) + " (" + kr->pose_worst_joint + ").";
        }
        case eval::Metric::LooMotionMax:
            return "A single worst frame over all folds; see the per-sample maxima in loo_" + s.spec.name + ".csv.";
        case eval::Metric::LooDuration:
            return "Every method predicts the duration from the samples' inverse-warp increments (Tucker and naive with "
                   "their coefficient kernel, per-pose / per-element kriging and RBF with a per-set kernel of their own, the "
                   "blend with its weights; lib/include/mocapdb/eval/synthesis_method.hpp).";
        case eval::Metric::FootSkating:
            return "The original samples skate " + fmt(eval::mean_if_any(r.loo.original_skating_cm_per_s)) +
                   " cm/s by the same measure (the nearest-neighbour blend mixes at most 3 samples, kriging all of them).";
        case eval::Metric::ConstraintReliableRmse: {
            const auto* base = constraint_method(r, v.best.method);
            const auto* kr = constraint_method(r, v.best_kriging.method);
            if (!base || !kr) return std::string();
            return "Over the whole grid (including rho < " + fmt(v.threshold) + "): " + v.best.method + " RMSE " +
                   fmt(base->all.rmse) + ", " + v.best_kriging.method + " " + fmt(kr->all.rmse) +
                   ". The achieved parameters are measured on the synthesized clips with the same extractors; "
                   "a blend that stays close to one captured sample reproduces that sample's measured parameters.";
        }
        case eval::Metric::ConstraintRmse: return "";
    }
    return "";
}

std::string losses_section(const EvalResults& e) {
    const eval::Verdicts verdicts = eval::judge(e);
    std::ostringstream o;
    o << "## Where our kriging loses\n\n"
      << "Generated from the numbers above: for every set and metric, the best method overall against the best of our "
         "kriging methods (per-pose, per-element, Tucker + kriging, naive). Lower is better everywhere. A line starting "
         "with **LOSES** means a baseline (RBF or the nearest-neighbour blend) beat every kriging variant on that metric.\n\n";
    for (const eval::SetVerdicts& sv : verdicts.sets) {
        const SetResults& r = *sv.results;
        o << "### " << r.set->spec.name << "\n\n";
        for (const eval::MetricVerdict& v : sv.metrics) {
            const MetricText t = metric_text(v);
            const std::string& unit = t.unit;
            switch (v.outcome) {
                case eval::Outcome::Tie:
                    o << "- " << t.name << ": tie — " << v.best.method << " " << fmt(v.best.value) << unit
                      << ", best kriging (" << v.best_kriging.method << ") " << fmt(v.best_kriging.value) << unit
                      << ", within 5 % or " << fmt(eval::tie_floor(v.metric)) << unit << ".\n";
                    break;
                case eval::Outcome::KrigingWins:
                    o << "- " << t.name << ": kriging wins (" << v.best.method << " " << fmt(v.best.value) << unit
                      << ").\n";
                    break;
                case eval::Outcome::Loses:
                    o << "- **LOSES** " << t.name << ": " << v.best.method << " " << fmt(v.best.value) << unit
                      << " against the best kriging variant, " << v.best_kriging.method << ", "
                      << fmt(v.best_kriging.value) << unit << " (" << percent(v.kriging_worse_percent) << " worse). "
                      << why_text(r, v) << "\n";
                    break;
            }
        }
        for (const eval::CompressionVerdict& c : sv.compression) {
            if (c.tucker_wins) {
                o << "- compression at max error <= " << fmt(c.target_cm) << " cm: a Tucker variant wins ("
                  << c.best.method << ", ratio " << fmt(c.best.ratio) << ").\n";
            } else {
                o << "- **LOSES** compression at max error <= " << fmt(c.target_cm) << " cm: " << c.best.method
                  << " ratio " << fmt(c.best.ratio) << " against plain Tucker " << fmt(c.tucker.ratio)
                  << ". The Tucker model is what synthesis needs (pose-level random access in "
                  << fmt(c.tucker.us_per_pose) << " us/pose); " << c.best.method << " is "
                  << (c.best.access == "stream" ? "a stream codec (decodes the whole set: " : "(")
                  << fmt(c.best.us_per_pose) << " us/pose).\n";
            }
        }
        o << "\n";
    }
    if (verdicts.runtime) {
        const eval::RuntimeVerdicts& v = *verdicts.runtime;
        o << "### Runtime (" << e.runtime_set << ")\n\n";
        if (v.fastest_build && v.slowest_kriging_build) {
            const eval::RuntimeRow& fb = *v.fastest_build;
            o << "- " << (v.build_loses ? "**LOSES** preprocessing" : "preprocessing") << " at N = " << v.samples
              << ": fastest is " << fb.method << " (" << fmt(fb.build_seconds) << " s); the fastest kriging variant, "
              << (v.fastest_kriging_build ? v.fastest_kriging_build->method : std::string("-")) << ", takes "
              << (v.fastest_kriging_build ? fmt(v.fastest_kriging_build->build_seconds) : std::string("-"))
              << " s, the slowest, " << v.slowest_kriging_build->method << ", "
              << fmt(v.slowest_kriging_build->build_seconds)
              << " s. Kriging fits variograms (per-element: one per dof and frame; per-pose: one per frame) and factorizes "
                 "a system per kernel; RBF factorizes one system and the blend only stores the samples.\n";
        }
        if (v.fastest_synthesis) {
            o << "- " << (v.synthesis_loses ? "**LOSES** synthesis time" : "synthesis time") << " at N = " << v.samples
              << ": fastest is " << v.fastest_synthesis->method << " (" << fmt(v.fastest_synthesis->synth_us_per_frame)
              << " us per frame).\n";
        }
        o << "\n";
    }
    o << "In all: a baseline beats every kriging variant in " << verdicts.losses << " of " << verdicts.comparisons
      << " comparisons (" << verdicts.ties << " more are ties within 5 %).\n\n";
    return o.str();
}

}  // namespace mocapdb::cli::eval_report
