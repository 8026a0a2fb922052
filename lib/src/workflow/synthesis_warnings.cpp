#include "mocapdb/workflow/synthesis_warnings.hpp"

namespace mocapdb::workflow {

SynthesisWarnings synthesis_warnings(const synthesis::SynthesisModel& model, double rho) {
    SynthesisWarnings w;
    w.low_reliability = is_low_reliability(rho);
    w.kernel_fit = synthesis::fit_status_warning(model.kernel_fit());
    const kriging::KrigingStatus& st = model.report().status;
    w.regularized = st.factorization == kriging::FactorizationStatus::Regularized;
    w.jittered = !w.regularized && st.factorization == kriging::FactorizationStatus::Jittered &&
                 st.jitter > 1e-8 * model.report().model.total_sill();
    return w;
}

}  // namespace mocapdb::workflow
