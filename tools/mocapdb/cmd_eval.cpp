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
        case eval::EvalStage::Constraint: return "eval " + set + ": constraints";
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
        case eval::EvalStage::Constraint:
            say("[eval] %s: constraint accuracy on %lld grid points (%.1f s)\n", name,
                static_cast<long long>(d.results->constraint.grid.rows()), d.seconds);
            break;
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
    CLI::App* cmd =
        app.add_subcommand("eval", "Evaluate the interpolators and compressors against the baselines (REPORT.md)");
    cmd->footer(
        "Examples:\n"
        "  mocapdb eval --data ../shared/datasets --out eval/\n"
        "  mocapdb eval --data ../shared/datasets --out /tmp/eval --quick\n"
        "Builds the evaluation sets from DATA/cmu-asfamc in memory (subject 16 walks and runs, forward jumps\n"
        "of subjects 13/16/105, subject 105 jump turns and gait cycles), runs leave-one-out prediction (with the\n"
        "kernel headroom: the best of a grid of fixed kernels in the same folds),\n"
        "constraint accuracy, reliability against error, sample reduction, foot skating, compression and\n"
        "runtime for per-pose / per-element / Tucker / naive kriging, RBF and a nearest-neighbour blend, and\n"
        "writes OUT/REPORT.md, OUT/results.json and CSV and SVG files (replacing those of a previous run).\n"
        "--quick: subject 16 walks only, fewer leave-one-out folds and grid points (every section present).");
    cmd->add_option("--data", a->data, "the shared datasets folder (holding cmu-asfamc/)")->required();
    cmd->add_option("--out", a->out, "output folder for REPORT.md, results.json, CSV and SVG")->required();
    cmd->add_flag("--quick", a->quick, "a reduced run (subject 16 walks only) for smoke tests");
    cmd->add_flag("--tiny", a->tiny, "")->group("");  // hidden: smallest run, for sanitizer builds
    cmd->callback([a, cmd] {
        EvalArgs args = *a;
        args.command = "mocapdb eval --data " + a->data + " --out " + a->out + (a->quick ? " --quick" : "") +
                       (a->tiny ? " --tiny" : "");
        (void)cmd;
        run_eval(args);
    });
}

}  // namespace mocapdb::cli
