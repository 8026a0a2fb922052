#include "mocapdb/eval/constraint_accuracy.hpp"

#include <chrono>
#include <cmath>

#include "mocapdb/compression/dof_weights.hpp"
#include "mocapdb/core/error.hpp"
#include "mocapdb/kriging/trend.hpp"
#include "mocapdb/synthesis/naive_motion_model.hpp"

namespace mocapdb::eval {
namespace {

MatX make_grid(const MatX& params, const ConstraintOptions& o) {
    const Eigen::Index p = params.cols();
    const Eigen::Index per_axis = p == 1 ? o.points_1d : o.points_per_axis_2d;
    if (per_axis < 2) throw InvalidArgument("constraint_accuracy: at least 2 grid points per axis");
    const VecX lo = params.colwise().minCoeff().transpose();
    const VecX hi = params.colwise().maxCoeff().transpose();
    Eigen::Index q = 1;
    for (Eigen::Index k = 0; k < p; ++k) q *= per_axis;
    MatX grid(q, p);
    for (Eigen::Index r = 0; r < q; ++r) {
        Eigen::Index rest = r;
        for (Eigen::Index k = 0; k < p; ++k) {
            const Eigen::Index idx = rest % per_axis;
            rest /= per_axis;
            grid(r, k) = lo(k) + (hi(k) - lo(k)) * static_cast<double>(idx) / static_cast<double>(per_axis - 1);
        }
    }
    return grid;
}

RegionStats region(const ConstraintMethodResult& m, const MatX& grid, const VecX& rho, double threshold) {
    RegionStats s;
    s.threshold = threshold;
    s.axis_rmse = VecX::Zero(grid.cols());
    double sq = 0.0;
    for (Eigen::Index q = 0; q < grid.rows(); ++q) {
        if (!m.valid[static_cast<std::size_t>(q)] || rho(q) < threshold) continue;
        ++s.points;
        s.max = std::max(s.max, m.error(q));
        sq += m.error(q) * m.error(q);
        s.axis_rmse += (grid.row(q) - m.achieved.row(q)).transpose().cwiseAbs2();
    }
    if (s.points > 0) {
        s.rmse = std::sqrt(sq / static_cast<double>(s.points));
        s.axis_rmse = (s.axis_rmse / static_cast<double>(s.points)).cwiseSqrt();
    }
    return s;
}

}  // namespace

double pearson(const Eigen::Ref<const VecX>& a, const Eigen::Ref<const VecX>& b) {
    if (a.size() != b.size()) throw InvalidArgument("pearson: vectors of different lengths");
    if (a.size() < 2) return 0.0;
    const VecX x = a.array() - a.mean();
    const VecX y = b.array() - b.mean();
    const double d = std::sqrt(x.squaredNorm() * y.squaredNorm());
    return d > 0.0 ? x.dot(y) / d : 0.0;
}

ConstraintResult constraint_accuracy(const EvalSet& set, const std::vector<MethodSpec>& methods,
                                     const ConstraintOptions& options, const ProgressCallback& progress) {
    ConstraintResult out;
    out.grid = make_grid(set.set.parameters, options);
    const kriging::ControlScaling scaling = kriging::ControlScaling::from_data(set.set.parameters);
    out.scale = scaling.scale;
    const VecX weight = compression::position_error_weights(*set.skeleton);
    const synthesis::NaiveMotionModel reference(set.aligned, set.set, set.skeleton, set.frame_rate, weight);
    out.reliability = reference.reliability_batch(out.grid);
    {
        const Eigen::Index p = set.set.parameters.cols();
        const VecX lo = set.set.parameters.colwise().minCoeff().transpose();
        const VecX hi = set.set.parameters.colwise().maxCoeff().transpose();
        out.outside_3sd.resize(2 * p, p);
        for (Eigen::Index k = 0; k < p; ++k) {
            VecX c = 0.5 * (lo + hi);
            c(k) = hi(k) + 3.0 * scaling.scale(k);
            out.outside_3sd.row(2 * k) = c.transpose();
            c(k) = lo(k) - 3.0 * scaling.scale(k);
            out.outside_3sd.row(2 * k + 1) = c.transpose();
        }
        out.rho_outside_3sd = reference.reliability_batch(out.outside_3sd).maxCoeff();
        out.loo_mean_z2 = reference.report().loo_mean_z2;
    }
    const Eigen::Index q_count = out.grid.rows();
    SynthesizedMotion motion;
    std::uint64_t done = 0;
    for (const MethodSpec& spec : methods) {
        const auto start = std::chrono::steady_clock::now();
        ConstraintMethodResult r;
        r.method = spec.name;
        r.achieved = out.grid;
        r.error = VecX::Zero(q_count);
        r.valid.assign(static_cast<std::size_t>(q_count), false);
        const auto synth = build_synthesizer(spec, set);
        for (Eigen::Index q = 0; q < q_count; ++q) {
            const VecX c = out.grid.row(q).transpose();
            synth->synthesize(c, motion);
            const Clip clip = motion_clip(motion, set.skeleton, set.frame_rate);
            try {
                const VecX got = extract_parameters(clip, 0, clip.frame_count(), set.extractors);
                r.achieved.row(q) = got.transpose();
                r.error(q) = ((c - got).array() / out.scale.array()).matrix().norm();
                r.valid[static_cast<std::size_t>(q)] = true;
            } catch (const InvalidArgument&) {
                ++r.failures;
            }
        }
        r.reliability = synth->reliability_batch(out.grid);
        r.own_reliability = r.reliability.size() == q_count;
        if (!r.own_reliability) r.reliability = out.reliability;
        if (r.own_reliability) r.rho_outside_3sd = synth->reliability_batch(out.outside_3sd).maxCoeff();
        for (double t : options.thresholds) r.regions.push_back(region(r, out.grid, r.reliability, t));
        r.all = region(r, out.grid, r.reliability, -1.0);
        r.all.threshold = 0.0;
        std::vector<double> rho, err;
        for (Eigen::Index q = 0; q < q_count; ++q)
            if (r.valid[static_cast<std::size_t>(q)]) {
                rho.push_back(r.reliability(q));
                err.push_back(r.error(q));
            }
        r.pearson = pearson(Eigen::Map<const VecX>(rho.data(), static_cast<Eigen::Index>(rho.size())),
                            Eigen::Map<const VecX>(err.data(), static_cast<Eigen::Index>(err.size())));
        r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        out.methods.push_back(std::move(r));
        if (progress) progress({++done, static_cast<std::uint64_t>(methods.size()), spec.name});
    }
    return out;
}

}  // namespace mocapdb::eval
