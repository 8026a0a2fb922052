#include "mocapdb/workflow/reliability_map.hpp"

namespace mocapdb::workflow {

VecX samples_mean(const synthesis::SynthesisModel& model) {
    return model.sample_parameters().colwise().mean().transpose();
}

ReliabilityMap reliability_map(const synthesis::SynthesisModel& model, const SliceAxis& gx, const SliceAxis& gy,
                               const VecX& base) {
    ReliabilityMap m;
    m.queries.resize(gx.count * gy.count, model.parameters());
    for (Eigen::Index j = 0; j < gy.count; ++j)
        for (Eigen::Index i = 0; i < gx.count; ++i) {
            VecX c = base;
            c(gx.axis) = gx.at(i);
            c(gy.axis) = gy.at(j);
            m.queries.row(j * gx.count + i) = c.transpose();
        }
    m.rho = model.reliability_batch(m.queries);
    m.values.resize(gy.count, gx.count);
    for (Eigen::Index j = 0; j < gy.count; ++j)
        for (Eigen::Index i = 0; i < gx.count; ++i) m.values(j, i) = m.rho(j * gx.count + i);
    m.fraction_trusted = (m.rho.array() >= kTrustedReliability).cast<double>().mean();
    if (m.rho.size()) {
        m.rho_min = m.rho.minCoeff();
        m.rho_mean = m.rho.mean();
        m.rho_max = m.rho.maxCoeff();
    }
    return m;
}

}  // namespace mocapdb::workflow
