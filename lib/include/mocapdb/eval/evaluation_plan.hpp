#pragma once
// What one run of the evaluation (`mocapdb eval`) does: which sets of CMU clips it builds,
// which experiments it runs on each, and with which options, for the three sizes of run (full, quick
// for smoke tests, tiny for sanitizer builds), and the methods compared on a set (the Tucker ranks
// resolved against the set's error targets). Pure data; evaluation.hpp runs a plan.
// Errors: methods_for_set throws what ranks_for_max_error throws. Threads: no shared state.
#include <string>
#include <vector>

#include "mocapdb/eval/constraint_accuracy.hpp"
#include "mocapdb/eval/eval_set.hpp"
#include "mocapdb/eval/kernel_headroom.hpp"
#include "mocapdb/eval/reduction_curve.hpp"
#include "mocapdb/eval/runtime_scaling.hpp"
#include "mocapdb/eval/synthesis_method.hpp"

namespace mocapdb::eval {

enum class EvalMode { Full, Quick, Tiny };

/// "full", "quick", "tiny".
const char* to_string(EvalMode mode);

struct EvalPlan {
    struct SetPlan {
        EvalSetSpec spec;
        bool loo = true;
        Eigen::Index loo_stride = 1;  ///< leave out every k-th sample
        bool constraint = true;
        bool reduction = false;
        bool compression = true;
    };
    std::vector<SetPlan> sets;
    std::vector<double> tucker_targets = {1.0, 3.0};  ///< max-error targets (cm) of the tucker-Ecm methods
    ConstraintOptions constraint;
    ReductionCurveOptions reduction;
    std::vector<double> compression_targets = {5.0, 2.0, 1.0, 0.5};
    bool hooi = true;
    std::vector<std::string> hooi_sets;  ///< when not empty: HOOI rows only for these sets
    /// The grid of the kernel headroom (kernel_headroom.hpp), run on every set with leave-one-out, over
    /// its left-out samples.
    KernelHeadroomOptions headroom;
    std::string runtime_set;  ///< the set the runtime study uses
    RuntimeOptions runtime;
};

/// The plan of a run of `mode` (full: five sets of subjects 13, 16 and 105; quick and tiny: subject
/// 16's walks with fewer frames, folds and grid points).
EvalPlan make_eval_plan(EvalMode mode);

/// The methods compared on `set`, in report order, and per Tucker method the max-error target (cm) its
/// ranks meet (one entry per TuckerKriging method, in order).
struct SetMethods {
    std::vector<MethodSpec> methods;
    std::vector<double> tucker_targets_cm;
};
SetMethods methods_for_set(const EvalSet& set, const std::vector<double>& tucker_targets);

}  // namespace mocapdb::eval
