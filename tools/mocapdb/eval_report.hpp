#pragma once
// mocapdb eval: the results of every experiment and the writers of eval/REPORT.md, results.json, the
// CSV tables and the SVG figures (everything generated, nothing hand-edited).
#include <filesystem>
#include <string>
#include <vector>

#include "mocapdb/compression/rate_distortion.hpp"
#include "mocapdb/eval/constraint_accuracy.hpp"
#include "mocapdb/eval/eval_set.hpp"
#include "mocapdb/eval/loo_prediction.hpp"
#include "mocapdb/eval/reduction_curve.hpp"
#include "mocapdb/eval/runtime_scaling.hpp"
#include "mocapdb/eval/synthesis_method.hpp"

namespace mocapdb::cli {

/// Where and how the run happened (the header of every table).
struct RunInfo {
    std::string command;      ///< as the user typed it
    std::string mode;         ///< "full", "quick" or "tiny"
    std::string date;         ///< UTC, from the clock
    std::string machine;      ///< uname -srm, cores, CPU model
    std::string load;         ///< load average at the start
    std::string build;        ///< compiler, optimization
    double wall_seconds = 0.0;
    double cpu_seconds = 0.0;  ///< process CPU time (user + system)
};

struct SetResults {
    const eval::EvalSet* set = nullptr;
    std::vector<eval::MethodSpec> methods;   ///< LOO / constraint methods (Tucker ranks resolved)
    std::vector<double> tucker_targets_cm;   ///< per Tucker method, the max-error target its ranks meet
    double build_seconds = 0.0;              ///< reading, extracting, aligning
    bool has_loo = false;
    eval::LooResult loo;
    double loo_seconds = 0.0;
    bool has_constraint = false;
    eval::ConstraintResult constraint;
    eval::ConstraintOptions constraint_options;
    bool has_reduction = false;
    eval::ReductionCurve reduction;
    eval::ReductionCurveOptions reduction_options;
    bool has_compression = false;
    compression::RateReport compression;
    std::vector<double> compression_targets;
};

struct EvalResults {
    RunInfo info;
    std::vector<SetResults> sets;
    std::string runtime_set;                 ///< name of the set the runtime study used
    std::vector<eval::RuntimeRow> runtime;
};

/// Writes REPORT.md, results.json, *.csv and *.svg into `out` (created; existing files of these names
/// are replaced atomically).
void write_eval_report(const EvalResults& results, const std::filesystem::path& out);

}  // namespace mocapdb::cli
