#include "mocapdb/core/stopwatch.hpp"
#include "mocapdb/eval/synthesis_method.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "mocapdb/compression/dof_weights.hpp"
#include "mocapdb/compression/rank_search.hpp"
#include "mocapdb/compression/set_model.hpp"
#include "mocapdb/core/error.hpp"
#include "mocapdb/dataset/set_scaling.hpp"
#include "mocapdb/dataset/unwarp.hpp"
#include "mocapdb/compression/joint_error.hpp"
#include "mocapdb/kriging/motion_kriging.hpp"
#include "mocapdb/kriging/trend.hpp"
#include "mocapdb/synthesis/motion_model.hpp"
#include "mocapdb/synthesis/naive_motion_model.hpp"

namespace mocapdb::eval {
namespace {

using Clock = std::chrono::steady_clock;

// N by (D*T): row i = sample i, column t*D + k (the tensor's storage order per sample).
MatX sample_rows(const AlignedSet& a) {
    const Eigen::Index dt = a.dofs() * a.frames();
    return Eigen::Map<const MatX>(a.tensor.data(), dt, a.samples()).transpose();
}

struct IncrementClamp {
    double lo = 0.0;
    double hi = 0.0;
    MatX increments;  // N by T - 1
    explicit IncrementClamp(const AlignedSet& a) : increments(a.inverse_warp_increments().transpose()) {
        lo = 0.05 * increments.mean();
        hi = 4.0 * increments.maxCoeff();
    }
    VecX warp(const Eigen::Ref<const VecX>& inc) const {
        VecX w(inc.size() + 1);
        w(0) = 0.0;
        for (Eigen::Index k = 0; k < inc.size(); ++k) w(k + 1) = w(k) + std::clamp(inc(k), lo, hi);
        return w;
    }
};

class KrigingSynthesizer final : public Synthesizer {
public:
    KrigingSynthesizer(const MethodSpec& m, const EvalSet& s)
        : clamp_(s.aligned), dofs_(s.aligned.dofs()), frames_(s.aligned.frames()) {
        kriging::MotionKrigingOptions o;
        o.dofs_per_frame = dofs_;
        MatX signal;
        if (m.kind == MethodKind::PerPoseKriging) {
            o.scope = kriging::KernelScope::PerPose;
            o.root_dofs = {0, 1, 2, 4};
            signal = pose_signal(s);
        } else if (m.kind == MethodKind::PerElementKriging) {
            o.scope = kriging::KernelScope::PerElement;
        } else {
            o.scope = kriging::KernelScope::PerSet;
            o.method = kriging::InterpolationMethod::Rbf;
        }
        o.scaling = set_control_scaling(s.set);  // the set's periodic and categorical axes
        poses_ = kriging::MotionKriging::build(s.set.parameters, sample_rows(s.aligned), signal, MatX(), o);
        kriging::MotionKrigingOptions t;
        t.scaling = o.scaling;
        t.scope = kriging::KernelScope::PerSet;
        t.method = o.method;
        timing_ = kriging::MotionKriging::build(s.set.parameters, clamp_.increments, MatX(), MatX(), t);
    }
    void synthesize(const Eigen::Ref<const VecX>& c, SynthesizedMotion& out) const override {
        VecX flat(dofs_ * frames_);
        poses_.predict(c, flat);
        out.aligned = Eigen::Map<const MatX>(flat.data(), dofs_, frames_);
        VecX inc(frames_ - 1);
        timing_.predict(c, inc);
        out.warp = clamp_.warp(inc);
    }

private:
    IncrementClamp clamp_;
    Eigen::Index dofs_, frames_;
    kriging::MotionKriging poses_;
    kriging::MotionKriging timing_;
};

// The linear trend alone: one OLS hyperplane per element of the motion rows and of the increments.
class TrendSynthesizer final : public Synthesizer {
public:
    explicit TrendSynthesizer(const EvalSet& s)
        : clamp_(s.aligned),
          scaling_(set_control_scaling(s.set)),
          basis_(kriging::TrendBasis::build(scaling_.apply(s.set.parameters), kriging::TrendKind::Linear)),
          motion_(kriging::fit_trend_ols(basis_, sample_rows(s.aligned)).coefficients),
          timing_(kriging::fit_trend_ols(basis_, clamp_.increments).coefficients),
          dofs_(s.aligned.dofs()),
          frames_(s.aligned.frames()) {}
    void synthesize(const Eigen::Ref<const VecX>& c, SynthesizedMotion& out) const override {
        const MatX cn = scaling_.apply(c.transpose());
        const VecX flat = kriging::evaluate_trend(basis_, motion_, cn).row(0).transpose();
        out.aligned = Eigen::Map<const MatX>(flat.data(), dofs_, frames_);
        out.warp = clamp_.warp(kriging::evaluate_trend(basis_, timing_, cn).row(0).transpose());
    }

private:
    IncrementClamp clamp_;
    kriging::ControlScaling scaling_;
    kriging::TrendBasis basis_;
    MatX motion_;  // K by D T
    MatX timing_;  // K by T - 1
    Eigen::Index dofs_, frames_;
};

class ModelSynthesizer final : public Synthesizer {
public:
    explicit ModelSynthesizer(std::unique_ptr<synthesis::SynthesisModel> model) : model_(std::move(model)) {}
    void synthesize(const Eigen::Ref<const VecX>& c, SynthesizedMotion& out) const override {
        synthesis::Workspace ws;
        VecX u(model_->coefficient_size());
        model_->coefficients(c, u, ws);
        out.aligned.resize(model_->dofs(), model_->frames());
        VecX pose(model_->dofs());
        for (Eigen::Index t = 0; t < model_->frames(); ++t) {
            model_->pose_from_coefficients(u, static_cast<double>(t), pose, ws);
            out.aligned.col(t) = pose;
        }
        out.warp = model_->timing(c).warp;
    }
    VecX reliability_batch(const Eigen::Ref<const MatX>& c) const override { return model_->reliability_batch(c); }

private:
    std::unique_ptr<synthesis::SynthesisModel> model_;
};

class NeighbourSynthesizer final : public Synthesizer {
public:
    NeighbourSynthesizer(const MethodSpec& m, const EvalSet& s)
        : clamp_(s.aligned),
          scaling_(set_control_scaling(s.set)),
          blend_(scaling_.apply(s.set.parameters), m.nn),
          rows_(sample_rows(s.aligned)),
          dofs_(s.aligned.dofs()),
          frames_(s.aligned.frames()) {}
    void synthesize(const Eigen::Ref<const VecX>& c, SynthesizedMotion& out) const override {
        const VecX cn = scaling_.apply(c.transpose()).transpose();
        const VecX w = blend_.weights(cn);
        const VecX flat = rows_.transpose() * w;
        out.aligned = Eigen::Map<const MatX>(flat.data(), dofs_, frames_);
        out.warp = clamp_.warp(clamp_.increments.transpose() * w);
    }

private:
    IncrementClamp clamp_;
    kriging::ControlScaling scaling_;
    NearestNeighbourBlend blend_;
    MatX rows_;
    Eigen::Index dofs_, frames_;
};

// The mean of several methods' motions: each built on the same samples, their aligned poses and warps
// averaged.
class AverageSynthesizer final : public Synthesizer {
public:
    AverageSynthesizer(const MethodSpec& m, const EvalSet& s) {
        if (m.averaged.size() < 2)
            throw InvalidArgument("build_synthesizer: the average of methods needs at least two of them");
        for (const MethodKind kind : m.averaged) {
            if (kind == MethodKind::Average) throw InvalidArgument("build_synthesizer: an average cannot hold another");
            MethodSpec one;
            one.kind = kind;
            one.name = to_string(kind);
            one.ranks = m.ranks;
            one.nn = m.nn;
            members_.push_back(build_synthesizer(one, s));
        }
    }
    void synthesize(const Eigen::Ref<const VecX>& c, SynthesizedMotion& out) const override {
        SynthesizedMotion one;
        members_.front()->synthesize(c, out);
        for (std::size_t k = 1; k < members_.size(); ++k) {
            members_[k]->synthesize(c, one);
            out.aligned += one.aligned;
            out.warp += one.warp;
        }
        out.aligned /= static_cast<double>(members_.size());
        out.warp /= static_cast<double>(members_.size());
    }

private:
    std::vector<std::unique_ptr<Synthesizer>> members_;
};

}  // namespace

const char* to_string(MethodKind kind) {
    switch (kind) {
        case MethodKind::PerPoseKriging: return "per-pose kriging";
        case MethodKind::PerElementKriging: return "per-element kriging";
        case MethodKind::TuckerKriging: return "Tucker + kriging";
        case MethodKind::NaiveKriging: return "naive kriging";
        case MethodKind::Rbf: return "RBF (Rose et al.)";
        case MethodKind::NearestNeighbour: return "nearest-neighbour blend";
        case MethodKind::TrendOnly: return "linear trend only";
        case MethodKind::Average: return "average";
    }
    return "?";
}

MatX aligned_sample(const AlignedSet& a, Eigen::Index i) {
    if (i < 0 || i >= a.samples()) throw InvalidArgument("aligned_sample: sample index out of range");
    return Eigen::Map<const MatX>(a.tensor.data() + i * a.dofs() * a.frames(), a.dofs(), a.frames());
}

MatX pose_signal(const EvalSet& s) {
    const AlignedSet& a = s.aligned;
    auto positions = [&](Eigen::Index i) {
        MatX q = aligned_sample(a, i);
        q.row(0).setZero();
        q.row(2).setZero();
        q.row(4).setZero();
        return compression::pose_joint_positions(*s.skeleton, q);
    };
    const MatX ref = positions(0);
    const Eigen::Index joints = ref.rows() / 3;
    MatX out(a.samples(), a.frames());
    for (Eigen::Index i = 0; i < a.samples(); ++i) {
        const MatX p = positions(i);
        for (Eigen::Index t = 0; t < a.frames(); ++t)
            out(i, t) = std::sqrt((p.col(t) - ref.col(0)).squaredNorm() / static_cast<double>(joints));
    }
    return out;
}

tensor::Ranks ranks_for_max_error(const EvalSet& set, double max_cm) {
    const VecX weight = compression::position_error_weights(*set.skeleton);
    const compression::PreparedSet prepared = compression::prepare_set(set.aligned.tensor, weight);
    const compression::JointErrorMeter meter(set.skeleton, set.aligned.tensor);
    return compression::search_ranks_for_max_error(prepared, meter, max_cm).model.tucker.ranks;
}

std::unique_ptr<Synthesizer> build_synthesizer(const MethodSpec& m, const EvalSet& s) {
    if (s.size() < 3) throw InvalidArgument("build_synthesizer: the training set needs at least 3 samples");
    const auto start = Clock::now();
    std::unique_ptr<Synthesizer> out;
    switch (m.kind) {
        case MethodKind::PerPoseKriging:
        case MethodKind::PerElementKriging:
        case MethodKind::Rbf: out = std::make_unique<KrigingSynthesizer>(m, s); break;
        case MethodKind::TuckerKriging: {
            const VecX weight = compression::position_error_weights(*s.skeleton);
            tensor::Ranks r = m.ranks;
            if (r[0] < 1 || r[1] < 1 || r[2] < 1) throw InvalidArgument("build_synthesizer: Tucker ranks must be >= 1");
            r[0] = std::min(r[0], s.aligned.dofs());
            r[1] = std::min(r[1], s.aligned.frames());
            r[2] = std::min(r[2], s.size());
            const compression::SetModel sm =
                compression::fit_set_model(s.aligned.tensor, weight, r, tensor::TuckerMethod::Hosvd);
            out = std::make_unique<ModelSynthesizer>(
                std::make_unique<synthesis::MotionModel>(sm, s.aligned, s.set, s.skeleton, s.frame_rate));
            break;
        }
        case MethodKind::NaiveKriging: {
            const VecX weight = compression::position_error_weights(*s.skeleton);
            out = std::make_unique<ModelSynthesizer>(
                std::make_unique<synthesis::NaiveMotionModel>(s.aligned, s.set, s.skeleton, s.frame_rate, weight));
            break;
        }
        case MethodKind::NearestNeighbour: out = std::make_unique<NeighbourSynthesizer>(m, s); break;
        case MethodKind::TrendOnly: out = std::make_unique<TrendSynthesizer>(s); break;
        case MethodKind::Average: out = std::make_unique<AverageSynthesizer>(m, s); break;
    }
    out->build_seconds = seconds_since(start);
    return out;
}

Clip motion_clip(const SynthesizedMotion& motion, std::shared_ptr<const Skeleton> skeleton, double frame_rate) {
    const Eigen::Index t = motion.warp.size();
    if (t < 2 || motion.aligned.cols() != t) throw InvalidArgument("motion_clip: warp and aligned poses disagree");
    const auto frames = static_cast<Eigen::Index>(std::floor(motion.warp(t - 1) + 1e-9)) + 1;
    const MatX poses = poses_at_sample_frames(motion.aligned, motion.warp, frames);
    return clip_from_pose_vectors(std::move(skeleton), poses, Canonicalization{}, frame_rate, "synthesized");
}

}  // namespace mocapdb::eval
