#include "mocapdb/eval/edge_evaluation.hpp"

#include <algorithm>
#include <limits>

#include "mocapdb/compression/dof_weights.hpp"
#include "mocapdb/compression/set_model.hpp"
#include "mocapdb/core/error.hpp"
#include "mocapdb/synthesis/kernel_fit.hpp"
#include "mocapdb/synthesis/motion_model.hpp"
#include "mocapdb/workflow/synthesis_warnings.hpp"

namespace mocapdb::eval {

EdgeEvaluation evaluate_edge_warning(const EvalSet& set, const tensor::Ranks& ranks,
                                     const workflow::EdgeCalibrationOptions& options) {
    if (ranks[0] < 1 || ranks[1] < 1 || ranks[2] < 1)
        throw InvalidArgument("evaluate_edge_warning: Tucker ranks must be >= 1");
    const tensor::Ranks r{std::min(ranks[0], set.aligned.dofs()), std::min(ranks[1], set.aligned.frames()),
                          std::min(ranks[2], set.size())};
    const VecX weight = compression::position_error_weights(*set.skeleton);
    const compression::SetModel sm =
        compression::fit_set_model(set.aligned.tensor, weight, r, tensor::TuckerMethod::Hosvd);
    // The model synth loads after `compress`: the stored kernel and the predictor chosen with it.
    synthesis::SynthesisOptions so;
    so.kernel_fit = synthesis::fit_kernel(sm, set.aligned, set.set, so);
    if (so.kernel_fit->predictor) synthesis::use_predictor_choice(*so.kernel_fit->predictor, so);
    const synthesis::MotionModel model(sm, set.aligned, set.set, set.skeleton, set.frame_rate, so);

    EdgeEvaluation e;
    e.options = options;
    e.calibration = workflow::calibrate_edge_warning(workflow::edge_probes(model, set.set, options), set.set, options);
    workflow::EdgeCalibrationOptions fresh_options = options;
    fresh_options.seed = options.seed + 1;
    const std::vector<workflow::EdgeProbe> fresh = workflow::edge_probes(model, set.set, fresh_options);
    for (const workflow::EdgeProbe& p : fresh) ++(p.inside ? e.fresh_inside : e.fresh_beyond);
    e.calibrated = workflow::flag_rates(fresh, e.calibration, set.set);
    e.fixed_threshold = workflow::kLowReliability;
    synthesis::EdgeWarning fixed;  // rho < 0.5 alone
    fixed.variance_ratio = 1.0 - e.fixed_threshold;
    fixed.beyond_sd = std::numeric_limits<double>::infinity();
    e.fixed = workflow::flag_rates(fresh, fixed, set.set);
    return e;
}

}  // namespace mocapdb::eval
