#include "mocapdb/eval/loo_prediction.hpp"

#include <chrono>
#include <cmath>

#include "mocapdb/core/error.hpp"
#include "mocapdb/compression/joint_error.hpp"

namespace mocapdb::eval {
namespace {

// The extractors' values on the whole synthesized clip; empty where a quantity is undefined (a jump
// without a flight, a gait measure without a cycle): a miss, not an error.
std::vector<std::optional<double>> measure_back(const Clip& clip, const std::vector<ParameterExtractor>& extractors) {
    std::vector<std::optional<double>> out;
    for (const ParameterExtractor& e : extractors) {
        try {
            const VecX v = extract_parameters(clip, 0, clip.frame_count(), {e});
            out.insert(out.end(), v.data(), v.data() + v.size());
        } catch (const InvalidArgument&) {
            out.resize(out.size() + e.names().size());
        }
    }
    return out;
}

}  // namespace

MatX frame_joint_errors(const Skeleton& skeleton, const Eigen::Ref<const MatX>& reference,
                        const Eigen::Ref<const MatX>& approx, bool root_relative) {
    if (reference.rows() != approx.rows() || reference.cols() != approx.cols() || reference.rows() < 6)
        throw InvalidArgument("frame_joint_errors: the two pose sequences differ in shape");
    MatX qa = reference, qb = approx;
    if (root_relative) {
        for (Eigen::Index r : {0, 2, 4}) {
            qa.row(r).setZero();
            qb.row(r).setZero();
        }
    }
    const MatX a = compression::pose_joint_positions(skeleton, qa);
    const MatX b = compression::pose_joint_positions(skeleton, qb);
    const Eigen::Index joints = a.rows() / 3;
    MatX out(a.cols(), 3);
    for (Eigen::Index t = 0; t < a.cols(); ++t) {
        double sum = 0.0, mx = -1.0;
        Eigen::Index worst = 0;
        for (Eigen::Index j = 0; j < joints; ++j) {
            const double e = (a.block(3 * j, t, 3, 1) - b.block(3 * j, t, 3, 1)).norm();
            sum += e;
            if (e > mx) {
                mx = e;
                worst = j;
            }
        }
        out(t, 0) = sum / static_cast<double>(joints);
        out(t, 1) = mx;
        out(t, 2) = static_cast<double>(worst);
    }
    return out;
}

std::vector<Eigen::Index> loo_training(Eigen::Index n, Eigen::Index i,
                                       const std::vector<std::vector<Eigen::Index>>& twins) {
    if (i < 0 || i >= n) throw InvalidArgument("loo_training: sample index out of range");
    std::vector<bool> out_of_fold(static_cast<std::size_t>(n), false);
    out_of_fold[static_cast<std::size_t>(i)] = true;
    if (!twins.empty()) {
        if (static_cast<Eigen::Index>(twins.size()) != n)
            throw InvalidArgument("loo_training: " + std::to_string(twins.size()) + " twin lists for " +
                                  std::to_string(n) + " samples");
        for (Eigen::Index t : twins[static_cast<std::size_t>(i)]) {
            if (t < 0 || t >= n) throw InvalidArgument("loo_training: twin index out of range");
            out_of_fold[static_cast<std::size_t>(t)] = true;
        }
    }
    std::vector<Eigen::Index> keep;
    for (Eigen::Index j = 0; j < n; ++j)
        if (!out_of_fold[static_cast<std::size_t>(j)]) keep.push_back(j);
    return keep;
}

std::vector<std::vector<Eigen::Index>> subset_twins(const std::vector<std::vector<Eigen::Index>>& twins,
                                                    const std::vector<Eigen::Index>& keep) {
    if (twins.empty()) return {};
    std::vector<Eigen::Index> position(twins.size(), -1);
    for (std::size_t k = 0; k < keep.size(); ++k) {
        if (keep[k] < 0 || keep[k] >= static_cast<Eigen::Index>(twins.size()))
            throw InvalidArgument("subset_twins: index out of range");
        position[static_cast<std::size_t>(keep[k])] = static_cast<Eigen::Index>(k);
    }
    std::vector<std::vector<Eigen::Index>> out(keep.size());
    for (std::size_t k = 0; k < keep.size(); ++k)
        for (Eigen::Index t : twins[static_cast<std::size_t>(keep[k])])
            if (t >= 0 && t < static_cast<Eigen::Index>(twins.size()) && position[static_cast<std::size_t>(t)] >= 0)
                out[k].push_back(position[static_cast<std::size_t>(t)]);
    return out;
}

LooResult leave_one_out(const EvalSet& set, const std::vector<MethodSpec>& methods, const LooOptions& options,
                        const ProgressCallback& progress) {
    const Eigen::Index n = set.size();
    if (n < 4) throw InvalidArgument("leave_one_out: at least 4 samples are needed, the set has " + std::to_string(n));
    LooResult out;
    out.samples = options.samples;
    if (out.samples.empty())
        for (Eigen::Index i = 0; i < n; ++i) out.samples.push_back(i);
    for (Eigen::Index i : out.samples)
        if (i < 0 || i >= n) throw InvalidArgument("leave_one_out: sample index out of range");
    const auto m = static_cast<Eigen::Index>(out.samples.size());
    const Eigen::Index frames = set.aligned.frames();
    const bool measure = options.measure_parameters && !set.extractors.empty();
    for (const MethodSpec& spec : methods) {
        LooMethodResult r;
        r.method = spec.name;
        r.sample_mean_cm = VecX::Zero(m);
        r.sample_max_cm = VecX::Zero(m);
        r.frame_mean_cm = VecX::Zero(frames);
        r.frame_max_cm = VecX::Zero(frames);
        r.sample_pose_mean_cm = VecX::Zero(m);
        r.sample_pose_max_cm = VecX::Zero(m);
        r.frame_pose_mean_cm = VecX::Zero(frames);
        r.duration_error_s = VecX::Zero(m);
        if (options.foot_skating) r.skating_cm_per_s = VecX::Zero(m);
        if (measure) r.measured.resize(static_cast<std::size_t>(m));
        out.methods.push_back(std::move(r));
    }
    if (options.foot_skating) out.original_skating_cm_per_s = VecX::Zero(m);
    SynthesizedMotion motion;
    std::vector<Eigen::Index> rho_folds(methods.size(), 0);  // per method: folds that gave a rho
    for (Eigen::Index k = 0; k < m; ++k) {
        const Eigen::Index i = out.samples[static_cast<std::size_t>(k)];
        const std::vector<Eigen::Index> keep = loo_training(n, i, options.twins);
        if (keep.size() < 3)
            throw InvalidArgument("leave_one_out: set '" + set.set.name + "': leaving out sample " +
                                  set.labels[static_cast<std::size_t>(i)] + " with its twins leaves " +
                                  std::to_string(keep.size()) + " training samples; at least 3 are needed");
        const EvalSet training = subset(set, keep);
        const MatX truth = aligned_sample(set.aligned, i);
        const VecX c = set.set.parameters.row(i).transpose();
        const Clip& original = set.samples[static_cast<std::size_t>(i)];
        if (options.foot_skating) out.original_skating_cm_per_s(k) = foot_skating(original).cm_per_s;
        for (std::size_t q = 0; q < methods.size(); ++q) {
            LooMethodResult& r = out.methods[q];
            const auto synth = build_synthesizer(methods[q], training);
            r.build_seconds += synth->build_seconds / static_cast<double>(m);
            const auto start = std::chrono::steady_clock::now();
            synth->synthesize(c, motion);
            r.synth_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() /
                               static_cast<double>(m);
            const MatX e = frame_joint_errors(*set.skeleton, truth, motion.aligned);
            r.sample_mean_cm(k) = e.col(0).mean();
            r.sample_max_cm(k) = e.col(1).maxCoeff();
            r.frame_mean_cm += e.col(0) / static_cast<double>(m);
            r.frame_max_cm = r.frame_max_cm.cwiseMax(e.col(1));
            const MatX ep = frame_joint_errors(*set.skeleton, truth, motion.aligned, true);
            r.sample_pose_mean_cm(k) = ep.col(0).mean();
            Eigen::Index worst_t = 0;
            r.sample_pose_max_cm(k) = ep.col(1).maxCoeff(&worst_t);
            if (r.sample_pose_max_cm(k) > r.pose_max_cm || r.pose_worst_sample < 0) {
                r.pose_max_cm = r.sample_pose_max_cm(k);
                r.pose_worst_sample = i;
                r.pose_worst_frame = worst_t;
                r.pose_worst_joint = set.skeleton->joint(static_cast<std::size_t>(ep(worst_t, 2))).name;
            }
            r.frame_pose_mean_cm += ep.col(0) / static_cast<double>(m);
            const double synth_duration = motion.warp(motion.warp.size() - 1) / set.frame_rate;
            r.duration_error_s(k) = std::abs(synth_duration - original.duration());
            if (options.foot_skating || measure) {
                const Clip clip = motion_clip(motion, set.skeleton, set.frame_rate);
                if (options.foot_skating) r.skating_cm_per_s(k) = foot_skating(clip).cm_per_s;
                if (measure) r.measured[static_cast<std::size_t>(k)] = measure_back(clip, set.extractors);
            }
            if (options.reliability) {
                const VecX rho = synth->reliability_batch(c.transpose());
                if (rho.size() == 1) {
                    if (r.reliability.size() == 0) r.reliability = VecX::Zero(m);
                    r.reliability(k) = rho(0);
                    ++rho_folds[q];
                }
            }
        }
        if (progress)
            progress({static_cast<std::uint64_t>(k + 1), static_cast<std::uint64_t>(m),
                      set.labels[static_cast<std::size_t>(i)]});
    }
    for (std::size_t q = 0; q < methods.size(); ++q) {
        LooMethodResult& r = out.methods[q];
        if (rho_folds[q] != m) r.reliability.resize(0);  // a rho for every fold or none
        r.mean_cm = r.sample_mean_cm.mean();
        r.max_cm = r.sample_max_cm.maxCoeff();
        r.pose_mean_cm = r.sample_pose_mean_cm.mean();
    }
    return out;
}

}  // namespace mocapdb::eval
