#pragma once
// The evaluation as a library step (`mocapdb eval`): builds the sets of a plan
// (evaluation_plan.hpp) from the CMU clips and runs every experiment on them (leave-one-out prediction,
// the predictor synthesis chooses by nested cross-validation, constraint accuracy, sample reduction,
// compression, runtime), returning every number; the verdicts
// drawn from them are verdicts.hpp, the renderings (REPORT.md, CSV, JSON, SVG) are the caller's.
// Nothing is printed: the observer hears when a stage starts (and gets a progress callback from it)
// and when it is done.
// Errors: InvalidArgument when `cmu_dir` is not a folder; IoError / ParseError from the clips
// (build_eval_set); InvalidArgument from the experiments' options. Threads: the observer is called
// from the calling thread.
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "mocapdb/compression/rate_distortion.hpp"
#include "mocapdb/core/progress.hpp"
#include "mocapdb/eval/constraint_accuracy.hpp"
#include "mocapdb/eval/edge_evaluation.hpp"
#include "mocapdb/eval/eval_set.hpp"
#include "mocapdb/eval/evaluation_plan.hpp"
#include "mocapdb/eval/kernel_headroom.hpp"
#include "mocapdb/eval/loo_prediction.hpp"
#include "mocapdb/eval/reduction_curve.hpp"
#include "mocapdb/eval/runtime_scaling.hpp"
#include "mocapdb/eval/set_evaluation.hpp"
#include "mocapdb/eval/synthesis_method.hpp"

namespace mocapdb::eval {

/// Where and how the run happened (the header of every table).
struct RunInfo {
    std::string command;  ///< as the user typed it
    std::string mode;     ///< "full", "quick" or "tiny"
    std::string date;     ///< UTC, from the clock
    std::string machine;  ///< uname -srm, cores, CPU model
    std::string load;     ///< load average at the start
    std::string build;    ///< compiler, optimization (of the library)
    double wall_seconds = 0.0;
    double cpu_seconds = 0.0;  ///< process CPU time (user + system)
};

/// The run's description now: `command` as given, the date, machine, load average and build.
RunInfo describe_run(const std::string& command, EvalMode mode);

/// Process CPU time (user + system) so far, seconds (0 when unavailable).
double process_cpu_seconds();

struct SetResults {
    std::shared_ptr<const EvalSet> set;
    std::vector<MethodSpec> methods;        ///< LOO / constraint methods (Tucker ranks resolved)
    std::vector<double> tucker_targets_cm;  ///< per Tucker method, the max-error target its ranks meet
    double build_seconds = 0.0;             ///< reading, extracting, aligning
    bool has_loo = false;
    LooResult loo;
    double loo_seconds = 0.0;
    bool has_headroom = false;  ///< run with the leave-one-out, over its left-out samples
    KernelHeadroom headroom;
    /// Run with the leave-one-out, over its left-out samples: kriging, RBF, trend and the predictor
    /// synthesis would choose, by nested cross-validation (set_evaluation.hpp).
    bool has_nested = false;
    SetEvaluation nested;
    bool has_constraint = false;
    ConstraintResult constraint;
    ConstraintOptions constraint_options;
    /// How well rho warns where synthesis misses (edge_evaluation.hpp), with the constraints, on the
    /// first Tucker method's ranks.
    bool has_edge = false;
    EdgeEvaluation edge;
    bool has_reduction = false;
    ReductionCurve reduction;
    ReductionCurveOptions reduction_options;
    bool has_compression = false;
    compression::RateReport compression;
    std::vector<double> compression_targets;
};

struct EvalResults {
    RunInfo info;
    std::vector<SetResults> sets;
    std::string runtime_set;  ///< name of the set the runtime study used
    std::vector<RuntimeRow> runtime;
};

enum class EvalStage {
    BuildSet,
    LeaveOneOut,
    KernelHeadroom,
    NestedChoice,
    Constraint,
    EdgeWarning,
    Reduction,
    Compression,
    Runtime
};

/// A finished stage: the set it worked on, that set's results so far (null for BuildSet and Runtime)
/// and its wall-clock seconds.
struct EvalStageDone {
    EvalStage stage = EvalStage::BuildSet;
    const EvalSet* set = nullptr;
    const SetResults* results = nullptr;
    double seconds = 0.0;
};

struct EvalObserver {
    /// Called when a long stage on the named set starts; returns the progress callback for it (may be
    /// empty). Not called for BuildSet.
    std::function<ProgressCallback(EvalStage stage, const std::string& set)> stage_started;
    /// Called when a stage is done (after its progress callback is no longer used).
    std::function<void(const EvalStageDone& done)> stage_done;
};

/// Runs `plan` on the clips of `cmu_dir` (the cmu-asfamc folder). `info` is returned in the results
/// with wall_seconds (from the call) and cpu_seconds (the process's) filled in.
EvalResults run_evaluation(const EvalPlan& plan, const std::filesystem::path& cmu_dir, RunInfo info,
                           const EvalObserver& observer = {});

}  // namespace mocapdb::eval
