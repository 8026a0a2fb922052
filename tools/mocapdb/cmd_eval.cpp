// mocapdb eval: builds the evaluation sets from the CMU clips, runs every experiment of the evaluation
// (leave-one-out prediction, constraint accuracy, reliability against error, sample reduction, foot
// skating, compression, runtime; mocapdb/eval/evaluation.hpp) and writes eval/REPORT.md with its
// figures and the numbers as CSV and JSON (eval_report.hpp). This file converts the arguments, draws
// the progress bars and prints the stage lines.
#include <chrono>
#include <cstdarg>
#include <cstdio>
#include <memory>

#include "commands.hpp"
#include "eval_report.hpp"
#include "eval_set_cli.hpp"
#include "mocapdb/core/error.hpp"
#include "mocapdb/eval/evaluation.hpp"
#include "progress_bar.hpp"

namespace mocapdb::cli {
namespace {

using Clock = std::chrono::steady_clock;

struct EvalArgs {
    std::string data;
    std::string out;
    bool quick = false;
    bool tiny = false;
    std::string command;
};

double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

void say(const char* format, ...) __attribute__((format(printf, 1, 2)));
void say(const char* format, ...) {
    va_list args;
    va_start(args, format);
    std::vprintf(format, args);
    va_end(args);
    std::fflush(stdout);
}

std::string bar_label(eval::EvalStage stage, const std::string& set) {
    switch (stage) {
        case eval::EvalStage::LeaveOneOut: return "eval " + set + ": leave-one-out";
        case eval::EvalStage::KernelHeadroom: return "eval " + set + ": kernel headroom";
        case eval::EvalStage::NestedChoice: return "eval " + set + ": nested cross-validation";
        case eval::EvalStage::Constraint: return "eval " + set + ": constraints";
        case eval::EvalStage::EdgeWarning: return "eval " + set + ": edge warning";
        case eval::EvalStage::Reduction: return "eval " + set + ": reduction";
        case eval::EvalStage::Compression: return "eval " + set + ": compression";
        case eval::EvalStage::Runtime: return "eval: runtime";
        case eval::EvalStage::BuildSet: break;
    }
    return "eval " + set;
}

void print_stage(const eval::EvalStageDone& d) {
    const eval::EvalSet& set = *d.set;
    const char* name = set.spec.name.c_str();
    switch (d.stage) {
        case eval::EvalStage::BuildSet:
            say("[eval] set %s: %lld samples, %lld dofs x %lld frames (%.1f s)\n", name,
                static_cast<long long>(set.size()), static_cast<long long>(set.aligned.dofs()),
                static_cast<long long>(set.aligned.frames()), d.seconds);
            break;
        case eval::EvalStage::LeaveOneOut:
            say("[eval] %s: leave-one-out over %zu samples x %zu methods (%.1f s)\n", name,
                d.results->loo.samples.size(), d.results->methods.size(), d.seconds);
            break;
        case eval::EvalStage::KernelHeadroom:
            say("[eval] %s: kernel headroom over %lld kernels (%.1f s)\n", name,
                static_cast<long long>(d.results->headroom.kernels), d.seconds);
            break;
        case eval::EvalStage::NestedChoice:
            say("[eval] %s: nested cross-validation of the predictor choice over %zu folds (%.1f s)\n", name,
                d.results->nested.folds.size(), d.seconds);
            break;
        case eval::EvalStage::Constraint:
            say("[eval] %s: constraint accuracy on %lld grid points (%.1f s)\n", name,
                static_cast<long long>(d.results->constraint.grid.rows()), d.seconds);
            break;
        case eval::EvalStage::EdgeWarning: {
            const eval::EdgeEvaluation& e = d.results->edge;
            say("[eval] %s: edge warning above variance ratio %.3f, %.2f SD beyond or %zu of %zu nearby misses flags "
                "%zu of %zu misses, %zu of %zu hits inside (fresh probes; fixed %.2f: %zu of %zu, %zu of %zu) "
                "(%.1f s)\n",
                name, e.calibration.variance_ratio, e.calibration.beyond_sd, e.calibration.votes,
                e.calibration.neighbours, e.calibrated.flagged_misses, e.calibrated.misses,
                e.calibrated.flagged_inside_hits, e.calibrated.inside_hits, e.fixed_threshold, e.fixed.flagged_misses,
                e.fixed.misses, e.fixed.flagged_inside_hits, e.fixed.inside_hits, d.seconds);
            break;
        }
        case eval::EvalStage::Reduction:
            say("[eval] %s: sample reduction, %lld of %lld kept at tau %.2f (%.1f s)\n", name,
                static_cast<long long>(d.results->reduction.kept_at_tau), static_cast<long long>(set.size()),
                d.results->reduction_options.tau, d.seconds);
            break;
        case eval::EvalStage::Compression: say("[eval] %s: compression report (%.1f s)\n", name, d.seconds); break;
        case eval::EvalStage::Runtime: say("[eval] runtime against N on %s (%.1f s)\n", name, d.seconds); break;
    }
}

void run_eval(const EvalArgs& a) {
    const auto start = Clock::now();
    const std::filesystem::path cmu = std::filesystem::path(a.data) / "cmu-asfamc";
    if (!std::filesystem::is_directory(cmu))
        throw InvalidArgument("--data " + a.data +
                              ": no folder cmu-asfamc inside (expected the shared datasets folder)");
    const eval::EvalMode mode = a.tiny ? eval::EvalMode::Tiny : a.quick ? eval::EvalMode::Quick : eval::EvalMode::Full;
    std::unique_ptr<ProgressBar> bar;
    eval::EvalObserver observer;
    observer.stage_started = [&bar](eval::EvalStage stage, const std::string& set) {
        bar = std::make_unique<ProgressBar>(bar_label(stage, set));
        return bar->callback();
    };
    observer.stage_done = [&bar](const eval::EvalStageDone& done) {
        bar.reset();
        print_stage(done);
    };
    const eval::EvalResults results =
        eval::run_evaluation(eval::make_eval_plan(mode), cmu, eval::describe_run(a.command, mode), observer);
    write_eval_report(results, a.out);
    say("[eval] wrote %s (%.1f s in all)\n", (std::filesystem::path(a.out) / "REPORT.md").string().c_str(),
        since(start));
}

}  // namespace

void setup_eval(CLI::App& app) {
    auto a = std::make_shared<EvalArgs>();
    auto s = std::make_shared<EvalSetArgs>();
    CLI::App* cmd = app.add_subcommand(
        "eval", "Evaluate the predictors on a stored set (DB --set), or the paper's report (--data --out: REPORT.md)");
    cmd->footer(
        "Examples:\n"
        "  mocapdb eval db.h5 --set walks [--json] [--svg loo.svg] [--max-folds 40]\n"
        "  mocapdb eval --data ../shared/datasets --out eval/\n"
        "  mocapdb eval --data ../shared/datasets --out /tmp/eval --quick\n"
        "DB --set NAME: leave-one-out on the stored aligned set (at most --max-folds samples, evenly spread; each\n"
        "fold also leaves out the sample's twins, samples showing the same frames): pose and motion error, parameter\n"
        "hit rate, Pearson(rho, error) for kriging, RBF, the trend alone and Tucker kriging (with a stored model),\n"
        "and the predictor chosen by nested cross-validation (docs/evaluation.md).\n"
        "--data --out:\n"
        "Builds the evaluation sets from DATA/cmu-asfamc in memory (subject 16 walks and runs, forward jumps\n"
        "of subjects 13/16/105, subject 105 jump turns and gait cycles), runs leave-one-out prediction (with the\n"
        "kernel headroom: the best of a grid of fixed kernels in the same folds),\n"
        "constraint accuracy, reliability against error, sample reduction, foot skating, compression and\n"
        "runtime for per-pose / per-element / Tucker / naive kriging, RBF and a nearest-neighbour blend, and\n"
        "writes OUT/REPORT.md, OUT/results.json and CSV and SVG files (replacing those of a previous run).\n"
        "--quick: subject 16 walks only, fewer leave-one-out folds and grid points (every section present).");
    cmd->add_option("db", s->db, "database file (with --set: evaluate that set)");
    cmd->add_option("--set", s->set, "with DB: the aligned set to evaluate");
    cmd->add_flag("--json", s->json, "with DB: print one JSON object (keys: docs/evaluation.md)");
    cmd->add_option("--svg", s->svg, "with DB: plot of the pose error per left-out sample and method");
    cmd->add_option("--max-folds", s->max_folds, "with DB: at most this many left-out samples (default 40)")
        ->check(CLI::PositiveNumber);
    cmd->add_option("--inner-folds", s->inner_folds, "with DB: inner folds of the nested cross-validation (default 15)")
        ->check(CLI::PositiveNumber);
    cmd->add_flag("--force", s->force, "with DB: overwrite the --svg file");
    cmd->add_option("--data", a->data, "the shared datasets folder (holding cmu-asfamc/)");
    cmd->add_option("--out", a->out, "output folder for REPORT.md, results.json, CSV and SVG");
    cmd->add_flag("--quick", a->quick, "a reduced run (subject 16 walks only) for smoke tests");
    cmd->add_flag("--tiny", a->tiny, "")->group("");  // hidden: smallest run, for sanitizer builds
    cmd->callback([a, s, cmd] {
        if (!s->db.empty() || !s->set.empty()) {
            if (s->db.empty() || s->set.empty())
                throw InvalidArgument("eval: give a database and --set NAME together (mocapdb eval DB.h5 --set NAME)");
            if (!a->data.empty() || !a->out.empty())
                throw InvalidArgument("eval: --data/--out write the paper's report; they do not go with DB --set");
            run_set_eval(*s);
            return;
        }
        if (a->data.empty() || a->out.empty())
            throw InvalidArgument("eval: give DB.h5 --set NAME, or --data DIR --out DIR for the report");
        if (s->json || !s->svg.empty()) throw InvalidArgument("eval: --json and --svg go with DB --set");
        EvalArgs args = *a;
        args.command = "mocapdb eval --data " + a->data + " --out " + a->out + (a->quick ? " --quick" : "") +
                       (a->tiny ? " --tiny" : "");
        (void)cmd;
        run_eval(args);
    });
}

}  // namespace mocapdb::cli
