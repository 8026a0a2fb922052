#include "mocapdb/eval/reduction_curve.hpp"

#include <algorithm>
#include <random>
#include <set>

#include "mocapdb/compression/dof_weights.hpp"
#include "mocapdb/core/error.hpp"
#include "mocapdb/eval/loo_prediction.hpp"
#include "mocapdb/eval/synthesis_method.hpp"
#include "mocapdb/kriging/reduction.hpp"
#include "mocapdb/synthesis/naive_motion_model.hpp"

namespace mocapdb::eval {
namespace {

struct RemovedError {
    double mean = 0.0, max = 0.0, pose_mean = 0.0;
};

// Mean (over removed samples) of the mean joint error, the max, and the mean root-relative pose error,
// predicting `removed` from `kept`.
RemovedError removed_error(const EvalSet& set, const std::vector<Eigen::Index>& kept,
                           const std::vector<Eigen::Index>& removed) {
    MethodSpec naive;
    naive.kind = MethodKind::NaiveKriging;
    const auto synth = build_synthesizer(naive, subset(set, kept));
    SynthesizedMotion motion;
    RemovedError out;
    for (Eigen::Index i : removed) {
        synth->synthesize(set.set.parameters.row(i).transpose(), motion);
        const MatX truth = aligned_sample(set.aligned, i);
        const MatX e = frame_joint_errors(*set.skeleton, truth, motion.aligned);
        out.mean += e.col(0).mean();
        out.max = std::max(out.max, e.col(1).maxCoeff());
        out.pose_mean += frame_joint_errors(*set.skeleton, truth, motion.aligned, true).col(0).mean();
    }
    if (!removed.empty()) {
        out.mean /= static_cast<double>(removed.size());
        out.pose_mean /= static_cast<double>(removed.size());
    }
    return out;
}

std::vector<Eigen::Index> complement(Eigen::Index n, const std::vector<Eigen::Index>& removed) {
    std::set<Eigen::Index> r(removed.begin(), removed.end());
    std::vector<Eigen::Index> out;
    for (Eigen::Index i = 0; i < n; ++i)
        if (!r.count(i)) out.push_back(i);
    return out;
}

}  // namespace

ReductionCurve reduction_curve(const EvalSet& set, const ReductionCurveOptions& options,
                               const ProgressCallback& progress) {
    const Eigen::Index n = set.size();
    if (n < 5) throw InvalidArgument("reduction_curve: at least 5 samples are needed");
    if (options.checkpoints < 1 || options.random_orders < 0)
        throw InvalidArgument("reduction_curve: checkpoints must be >= 1 and random_orders >= 0");
    const VecX weight = compression::position_error_weights(*set.skeleton);
    const synthesis::NaiveMotionModel model(set.aligned, set.set, set.skeleton, set.frame_rate, weight);
    const MatX xc = model.scaling().apply(model.sample_parameters());
    kriging::ReductionOptions ro;
    ro.kriging = model.kriging_options();
    ro.tau = options.tau;
    const kriging::ReductionResult at_tau = kriging::reduce_samples(xc, model.report().model, ro);
    ro.tau = 0.0;  // never stops on the threshold: the full order down to the minimum
    const kriging::ReductionResult full = kriging::reduce_samples(xc, model.report().model, ro);

    ReductionCurve out;
    out.samples = n;
    out.removal_order = full.removed;
    out.max_reliability = full.max_reliability;
    out.kept_at_tau = static_cast<Eigen::Index>(at_tau.kept.size());
    // The minimum size the naive model can be built on is 3 (build_synthesizer); keep at least 4.
    const Eigen::Index min_kept = std::max<Eigen::Index>(4, n - static_cast<Eigen::Index>(full.removed.size()));
    std::set<Eigen::Index, std::greater<>> sizes;
    for (Eigen::Index k = 0; k < options.checkpoints; ++k) {
        const double f =
            options.checkpoints == 1 ? 1.0 : static_cast<double>(k) / static_cast<double>(options.checkpoints - 1);
        sizes.insert(std::max(min_kept, static_cast<Eigen::Index>(std::lround(
                                            static_cast<double>(n - 1) - f * static_cast<double>(n - 1 - min_kept)))));
    }
    if (out.kept_at_tau >= min_kept && out.kept_at_tau < n) sizes.insert(out.kept_at_tau);
    std::mt19937 rng(options.seed);
    std::vector<std::vector<Eigen::Index>> random_orders;
    for (int r = 0; r < options.random_orders; ++r) {
        std::vector<Eigen::Index> perm(static_cast<std::size_t>(n));
        for (Eigen::Index i = 0; i < n; ++i) perm[static_cast<std::size_t>(i)] = i;
        std::shuffle(perm.begin(), perm.end(), rng);
        random_orders.push_back(perm);
    }
    std::uint64_t done = 0;
    for (Eigen::Index kept : sizes) {
        ReductionCurvePoint p;
        p.kept = kept;
        const auto removed_count = static_cast<std::size_t>(n - kept);
        if (removed_count > full.removed.size()) continue;
        const std::vector<Eigen::Index> removed(full.removed.begin(),
                                                full.removed.begin() + static_cast<std::ptrdiff_t>(removed_count));
        p.max_reliability = removed_count < full.max_reliability.size() ? full.max_reliability[removed_count] : 0.0;
        const auto g = removed_error(set, complement(n, removed), removed);
        p.greedy_mean_cm = g.mean;
        p.greedy_max_cm = g.max;
        p.greedy_pose_mean_cm = g.pose_mean;
        for (const auto& perm : random_orders) {
            const std::vector<Eigen::Index> rr(perm.begin(), perm.begin() + static_cast<std::ptrdiff_t>(removed_count));
            const RemovedError e = removed_error(set, complement(n, rr), rr);
            p.random_mean_cm += e.mean / static_cast<double>(random_orders.size());
            p.random_pose_mean_cm += e.pose_mean / static_cast<double>(random_orders.size());
        }
        out.points.push_back(p);
        if (progress) progress({++done, static_cast<std::uint64_t>(sizes.size()), "reduction"});
    }
    return out;
}

}  // namespace mocapdb::eval
