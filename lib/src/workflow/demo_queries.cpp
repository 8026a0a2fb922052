#include "mocapdb/workflow/demo_queries.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <set>

#include "mocapdb/core/error.hpp"
#include "mocapdb/kriging/trend.hpp"
#include "mocapdb/procedural/humanoid.hpp"
#include "mocapdb/procedural/reach.hpp"
#include "mocapdb/workflow/synthesis_step.hpp"

namespace mocapdb::workflow {
namespace {

constexpr double kPi = 3.14159265358979323846;

}  // namespace

std::vector<VecX> between_samples(const MatX& samples, std::size_t count) {
    std::vector<VecX> out;
    const Eigen::Index n = samples.rows();
    if (n < 2) return out;
    const MatX xn = kriging::ControlScaling::from_data(samples).apply(samples);
    std::set<std::pair<Eigen::Index, Eigen::Index>> used;
    for (std::size_t q = 0; q < count; ++q) {
        const auto i = static_cast<Eigen::Index>((static_cast<double>(q) + 0.5) * static_cast<double>(n) /
                                                 static_cast<double>(count));
        Eigen::Index nearest = -1;
        double best = std::numeric_limits<double>::infinity();
        for (Eigen::Index j = 0; j < n; ++j) {
            const double d = (xn.row(j) - xn.row(i)).norm();
            if (j != i && d > 1e-9 && d < best) {
                best = d;
                nearest = j;
            }
        }
        if (nearest < 0 || !used.insert({std::min(i, nearest), std::max(i, nearest)}).second) continue;
        out.push_back(0.5 * (samples.row(i) + samples.row(nearest)).transpose());
    }
    return out;
}

std::vector<VecX> reach_cell_centres(const procedural::ReachGrid& g) {
    std::vector<VecX> out;
    if (g.angle.count < 2 || g.height.count < 2) return out;
    const std::size_t na = g.angle.count - 1, nh = g.height.count - 1;
    const std::vector<std::pair<std::size_t, std::size_t>> cells{
        {0, 0}, {na / 3, nh - 1}, {na / 2, 0}, {(2 * na) / 3, nh / 2}, {na - 1, nh - 1}};
    std::set<std::pair<std::size_t, std::size_t>> seen;
    for (const auto& [a, h] : cells) {
        if (!seen.insert({a, h}).second) continue;
        VecX c(2);
        c << 0.5 * (g.angle.value(a) + g.angle.value(a + 1)), 0.5 * (g.height.value(h) + g.height.value(h + 1));
        out.push_back(c);
    }
    return out;
}

bool inside_box(const MatX& samples, const VecX& c) {
    for (Eigen::Index k = 0; k < c.size(); ++k)
        if (c(k) < samples.col(k).minCoeff() || c(k) > samples.col(k).maxCoeff()) return false;
    return true;
}

VecX least_trusted_outside(const synthesis::SynthesisModel& model) {
    const MatX& samples = model.sample_parameters();
    const VecX mean = samples.colwise().mean().transpose();
    VecX best = mean;
    double best_rho = 2.0;
    for (Eigen::Index k = 0; k < samples.cols(); ++k)
        for (const double side : {1.0, -1.0}) {
            const double lo = samples.col(k).minCoeff(), hi = samples.col(k).maxCoeff();
            VecX c = mean;
            c(k) = side > 0 ? hi + (hi - lo) : lo - (hi - lo);
            const double rho = model.reliability(c);
            if (rho < best_rho) {
                best_rho = rho;
                best = c;
            }
        }
    return best;
}

DemoMeasurement choose_measurement(const MotionSet& set, const Skeleton& skeleton) {
    const auto& names = set.parameter_names;
    DemoMeasurement m;
    m.extractors = source_extractors(set.parameter_source);
    m.extractor_names = set.parameter_source;
    if (m.extractors.empty()) {  // parameters from a CSV named like extractors (the walks' speed, turn)
        try {
            for (const std::string& n : names) {
                m.extractors.push_back(ParameterExtractor::parse(n));
                if (m.extractors.back().names() != std::vector<std::string>{n}) throw InvalidArgument(n);
            }
            m.extractor_names = "extract:";
            for (std::size_t k = 0; k < names.size(); ++k) m.extractor_names += (k ? "," : "") + names[k];
        } catch (const InvalidArgument&) {
            m.extractors.clear();
        }
    }
    const bool reach_names = std::all_of(names.begin(), names.end(), [](const std::string& n) {
        return n == "angle" || n == "height" || n == "distance";
    });
    if (!m.extractors.empty()) m.kind = DemoMeasure::Extractors;
    else if (reach_names && skeleton.find(procedural::HumanoidNames::right_hand_end)) m.kind = DemoMeasure::ReachTarget;
    return m;
}

VecX measure_reach_target(const Clip& clip, const std::vector<std::string>& names) {
    const std::optional<Vec3> hold = procedural::reach_hold_point(clip);
    if (!hold) return {};
    const Vec3& h = *hold;
    VecX out(static_cast<Eigen::Index>(names.size()));
    for (std::size_t k = 0; k < names.size(); ++k) {
        const auto i = static_cast<Eigen::Index>(k);
        if (names[k] == "angle") out(i) = std::atan2(h.x(), h.z()) * 180.0 / kPi;
        else if (names[k] == "height") out(i) = h.y();
        else if (names[k] == "distance") out(i) = std::hypot(h.x(), h.z());
        else return {};
    }
    return out;
}

VecX measure_synthesis(const DemoMeasurement& m, const Clip& clip, const std::vector<std::string>& names) {
    if (m.kind == DemoMeasure::Extractors && clip.frame_count() >= 2)
        return extract_parameters(clip, 0, clip.frame_count(), m.extractors);
    if (m.kind == DemoMeasure::ReachTarget) return measure_reach_target(clip, names);
    return {};
}

SliceAxis padded_axis(const MatX& samples, const std::vector<VecX>& points, Eigen::Index axis, Eigen::Index count) {
    double lo = samples.col(axis).minCoeff(), hi = samples.col(axis).maxCoeff();
    for (const VecX& p : points) {
        lo = std::min(lo, p(axis));
        hi = std::max(hi, p(axis));
    }
    const double pad = 0.15 * std::max(hi - lo, 1e-6);
    return SliceAxis{axis, lo - pad, hi + pad, count};
}

}  // namespace mocapdb::workflow
