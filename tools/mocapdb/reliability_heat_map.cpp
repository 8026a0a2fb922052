// The reliability map of a set as a heat map (pipeline.hpp): rho over two parameters, the samples as
// points, the other parameters' slice values as a note.
#include <cstdio>
#include <string>

#include "pipeline.hpp"

namespace mocapdb::cli {

HeatMapSpec reliability_heat_map(const synthesis::SynthesisModel& model, const std::string& set,
                                 const workflow::SliceAxis& gx, const workflow::SliceAxis& gy, const VecX& base,
                                 const workflow::ReliabilityMap& m) {
    const auto& names = model.parameter_names();
    const auto& units = model.parameter_units();
    const auto axis_label = [&](Eigen::Index k) {
        const std::string& u = units[static_cast<std::size_t>(k)];
        return names[static_cast<std::size_t>(k)] + (u.empty() ? "" : " [" + u + "]");
    };
    HeatMapSpec spec;
    spec.title = "Reliability of synthesis: set '" + set + "' (" + model.kind() + " model)";
    spec.x_label = axis_label(gx.axis);
    spec.y_label = axis_label(gy.axis);
    spec.value_label = "rho";
    spec.x_lo = gx.lo;
    spec.x_hi = gx.hi;
    spec.y_lo = gy.lo;
    spec.y_hi = gy.hi;
    spec.values = m.values;
    spec.value_lo = 0.0;
    spec.value_hi = 1.0;
    const MatX& sp = model.sample_parameters();
    for (Eigen::Index n = 0; n < sp.rows(); ++n) {
        spec.point_x.push_back(sp(n, gx.axis));
        spec.point_y.push_back(sp(n, gy.axis));
    }
    spec.point_label = "samples (" + std::to_string(sp.rows()) + ")";
    if (model.parameters() > 2) {
        std::string fixed;
        for (Eigen::Index k = 0; k < model.parameters(); ++k)
            if (k != gx.axis && k != gy.axis) {
                char buf[64];
                std::snprintf(buf, sizeof buf, "%s%s = %g", fixed.empty() ? "" : ", ",
                              names[static_cast<std::size_t>(k)].c_str(), base(k));
                fixed += buf;
            }
        spec.note = "slice at " + fixed;
    }
    return spec;
}

}  // namespace mocapdb::cli
