#pragma once
// How well rho warns where synthesis misses on one evaluation set: the Tucker model
// synthesis uses (ranks given, kernel and predictor chosen as `compress` chooses them), calibrated on one
// draw of probes (workflow/edge_calibration.hpp, seed 1) and judged on a fresh draw (seed 2), beside the
// fixed threshold workflow::kLowReliability on the same fresh probes. Details: docs/evaluation.md.
// Errors: InvalidArgument for ranks < 1 or a set whose parameters are not measured back.
// Threads: pure. Cost: 2 x (inside + beyond) syntheses and one kernel fit.
#include "mocapdb/eval/eval_set.hpp"
#include "mocapdb/synthesis/edge_warning.hpp"
#include "mocapdb/tensor/tucker.hpp"
#include "mocapdb/workflow/edge_calibration.hpp"

namespace mocapdb::eval {

struct EdgeEvaluation {
    workflow::EdgeCalibrationOptions options;  ///< of the calibration (the fresh draw: seed + 1)
    synthesis::EdgeWarning calibration;        ///< threshold and rates on the calibration probes
    workflow::FlagRates calibrated;            ///< that threshold on the fresh probes
    double fixed_threshold = 0.0;              ///< workflow::kLowReliability (rho; a variance ratio of 1 - it)
    workflow::FlagRates fixed;                 ///< the fixed threshold on the fresh probes
    std::size_t fresh_inside = 0, fresh_beyond = 0;
};

EdgeEvaluation evaluate_edge_warning(const EvalSet& set, const tensor::Ranks& ranks,
                                     const workflow::EdgeCalibrationOptions& options = {});

}  // namespace mocapdb::eval
