#include "mocapdb/synthesis/synthesis_model.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "mocapdb/core/error.hpp"
#include "mocapdb/kriging/rbf.hpp"
#include "mocapdb/kriging/trend_interpolator.hpp"
#include "mocapdb/motion/pose_vector.hpp"

namespace mocapdb::synthesis {
namespace {

// The mean of the weights of several interpolators over the same samples (the Average predictor). The
// kriging member is the model's own (not owned: the model cannot move), the others are owned.
class MeanOfPredictors final : public kriging::Interpolator {
public:
    MeanOfPredictors(const kriging::Interpolator* kriging, std::vector<std::unique_ptr<kriging::Interpolator>> owned)
        : owned_(std::move(owned)) {
        if (kriging) members_.push_back(kriging);
        for (const auto& p : owned_) members_.push_back(p.get());
    }
    Eigen::Index num_samples() const override { return members_.front()->num_samples(); }
    Eigen::Index dimension() const override { return members_.front()->dimension(); }
    void weights(const Eigen::Ref<const VecX>& c, Eigen::Ref<VecX> out, kriging::QueryWorkspace& ws) const override {
        VecX one(out.size());
        members_.front()->weights(c, out, ws);
        for (std::size_t k = 1; k < members_.size(); ++k) {
            members_[k]->weights(c, one, ws);
            out += one;
        }
        out /= static_cast<double>(members_.size());
    }
    void weights_batch(const Eigen::Ref<const MatX>& queries, Eigen::Ref<MatX> out) const override {
        MatX one(out.rows(), out.cols());
        members_.front()->weights_batch(queries, out);
        for (std::size_t k = 1; k < members_.size(); ++k) {
            members_[k]->weights_batch(queries, one);
            out += one;
        }
        out /= static_cast<double>(members_.size());
    }
    using Interpolator::weights;
    using Interpolator::weights_batch;

private:
    std::vector<std::unique_ptr<kriging::Interpolator>> owned_;
    std::vector<const kriging::Interpolator*> members_;
};

}  // namespace

void use_predictor_choice(const PredictorChoice& choice, SynthesisOptions& options) {
    options.predictor = choice.chosen;
    options.averaged = choice.chosen == Predictor::Average ? choice.members() : std::vector<Predictor>{};
}

Eigen::Index Timing::frame_count() const {
    if (warp.size() == 0) return 0;
    // The rounding slack keeps a sample's own timing (warp(T-1) = frames - 1 up to summation error).
    return static_cast<Eigen::Index>(std::floor(warp(warp.size() - 1) + 1e-9)) + 1;
}

double Timing::aligned_frame(double f) const {
    const Eigen::Index t_count = warp.size();
    if (t_count < 2 || !(f > warp(0))) return 0.0;
    if (f >= warp(t_count - 1)) return static_cast<double>(t_count - 1);
    const double* begin = warp.data();
    const double* it = std::upper_bound(begin, begin + t_count, f);  // first warp > f; it - 1 >= begin
    const Eigen::Index k = static_cast<Eigen::Index>(it - begin) - 1;
    const double span = warp(k + 1) - warp(k);
    return static_cast<double>(k) + (span > 0.0 ? (f - warp(k)) / span : 0.0);
}

AlignedTiming SynthesisModel::checked_timing(const AlignedSet& aligned) {
    validate(aligned);
    return timing_of(aligned);
}

SynthesisModel::SynthesisModel(const AlignedTiming& aligned, const MotionSet& set,
                               std::shared_ptr<const Skeleton> skeleton, double frame_rate,
                               const std::function<MatX()>& sample_values, std::uint64_t key,
                               const SynthesisOptions& options, const char* where) {
    const auto start = std::chrono::steady_clock::now();
    validate(aligned);
    validate(set);
    const Eigen::Index n = aligned.samples();
    if (static_cast<Eigen::Index>(set.samples.size()) != n || set.parameters.rows() != n) {
        throw InvalidArgument(std::string(where) + ": the set '" + set.name + "' has " +
                              std::to_string(set.parameters.rows()) + " samples but the aligned tensor " +
                              std::to_string(n));
    }
    if (n < 2)
        throw InvalidArgument(std::string(where) + ": synthesis needs at least 2 samples, the set has " +
                              std::to_string(n));
    if (!skeleton) throw InvalidArgument(std::string(where) + ": no skeleton");
    if (static_cast<Eigen::Index>(PoseLayout(*skeleton).dof_count()) != aligned.dofs()) {
        throw InvalidArgument(std::string(where) + ": the skeleton's pose vector has " +
                              std::to_string(static_cast<Eigen::Index>(PoseLayout(*skeleton).dof_count())) +
                              " dofs, the aligned tensor " + std::to_string(aligned.dofs()));
    }
    if (!(frame_rate > 0.0) || !std::isfinite(frame_rate))
        throw InvalidArgument(std::string(where) + ": frame rate must be positive and finite");
    if (!(options.min_increment_fraction > 0.0 && options.min_increment_fraction <= 1.0))
        throw InvalidArgument(std::string(where) + ": min_increment_fraction must be in (0, 1]");
    if (!(options.max_increment_factor >= 1.0) || !std::isfinite(options.max_increment_factor))
        throw InvalidArgument(std::string(where) + ": max_increment_factor must be >= 1");
    // Above the bound the local kriging: nothing may build an N x N system.
    const bool local = static_cast<std::size_t>(n) > options.max_exact_samples;
    if (local) {
        const std::string bound = " (the set has " + std::to_string(n) + " samples, more than max_exact_samples = " +
                                  std::to_string(options.max_exact_samples) + ": local kriging)";
        if (options.local_neighbours < 1)
            throw InvalidArgument(std::string(where) + ": local_neighbours must be >= 1" + bound);
        if (options.timing_kernel == SynthesisOptions::TimingKernel::Separate)
            throw InvalidArgument(std::string(where) +
                                  ": the separate timing kernel solves an N x N kriging system; use the shared one" +
                                  bound);
        const bool rbf = options.predictor == Predictor::Rbf ||
                         (options.predictor == Predictor::Average &&
                          std::count(options.averaged.begin(), options.averaged.end(), Predictor::Rbf) > 0);
        if (rbf)
            throw InvalidArgument(std::string(where) +
                                  ": the RBF predictor solves an N x N system; use kriging or the trend" + bound);
    }

    dofs_ = aligned.dofs();
    frames_ = aligned.frames();
    names_ = set.parameter_names;
    units_ = set.parameter_units;
    coords_ = set.parameters;
    skeleton_ = std::move(skeleton);
    frame_rate_ = frame_rate;
    if (options.scaling) {
        options.scaling->validate(coords_.cols());
        scaling_ = *options.scaling;
        if (scaling_.period.size() == 0) scaling_.period = set.parameter_periods;    // the set's periodic axes
        if (scaling_.levels.empty()) scaling_.levels = parameter_level_counts(set);  // and categorical ones
    } else {
        scaling_ = kriging::ControlScaling::from_data(coords_, set.parameter_periods, parameter_level_counts(set));
    }
    const MatX xc = scaling_.apply(coords_);

    // Coefficient kernel: variogram on the distances between the samples' values (rows), or the
    // precomputed one of the same inputs.
    if (key != 0 && options.kernel_fit && options.kernel_fit->key == key) {
        kernel_fit_ = *options.kernel_fit;
        kernel_fit_.variogram.validate();
        if (!(kernel_fit_.variogram.total_sill() > 0.0))
            throw InvalidArgument(std::string(where) + ": the precomputed kernel's nugget + sill must be > 0");
        report_.kernel_precomputed = true;
        // The status a model of these inputs reports, stored with the kernel (same key, same inputs);
        // for a kernel stored without it, recomputed from the bounds (no refit, but the sample values:
        // for the compressed model the N x R1 R2 core slices), so that a degenerate fit is reported
        // after loading too.
        if (kernel_fit_.assessed_status) {
            kernel_fit_.status = *kernel_fit_.assessed_status;
        } else {
            const MatX values = sample_values();
            if (values.rows() == n && values.allFinite())
                kernel_fit_.status = assess_coefficient_kernel(xc, values, kernel_fit_.variogram, options);
        }
    } else {
        const MatX values = sample_values();
        if (values.rows() != n || !values.allFinite())
            throw InvalidArgument(std::string(where) + ": sample values must be N by S and finite");
        kernel_fit_ = fit_coefficient_kernel(xc, values, options, where);
        kernel_fit_.key = key;
    }
    const kriging::VariogramModel& model = kernel_fit_.variogram;
    report_.exponent_loo_mse = kernel_fit_.exponent_loo_mse;
    kriging_options_ = options.kriging;
    if (local) {
        local_ = std::make_unique<kriging::LocalKriging>(kriging::LocalKriging::build(
            xc, model, options.kriging, static_cast<Eigen::Index>(options.local_neighbours)));
        report_.local_neighbours = local_->neighbours();
        report_.status = local_->status();
    } else {
        // The stored factorization of the same inputs (same key) spares the O(N^3) step; it is dropped once
        // used (the model keeps its own operators).
        const kriging::CovarianceInverse* system = report_.kernel_precomputed ? kernel_fit_.system.get() : nullptr;
        kriging_ = kriging::Kriging::build(xc, model, options.kriging, system, options.fit_progress);
        report_.system_precomputed = system != nullptr && system->inverse.rows() == kriging_.unique_points().rows();
        report_.status = kriging_.status();
    }
    kernel_fit_.system.reset();
    report_.model = model;
    report_.fit_status = kernel_fit_.status;
    report_.loo_mean_z2 = kernel_fit_.loo_mean_z2;
    // The weights' interpolator: the one asked for, kriging by default (workflow::load_motion_model asks
    // for the stored choice).
    if (report_.kernel_precomputed) report_.predictor_choice = kernel_fit_.predictor;
    report_.predictor = options.predictor.value_or(Predictor::Kriging);
    const auto build_one = [&](Predictor p) -> std::unique_ptr<kriging::Interpolator> {
        if (p == Predictor::Rbf) return std::make_unique<kriging::RbfInterpolator>(kriging::RbfInterpolator::build(xc));
        return std::make_unique<kriging::TrendInterpolator>(
            kriging::TrendInterpolator::build(xc, options.kriging.trend, options.kriging.trend_rank_tolerance));
    };
    if (report_.predictor == Predictor::Rbf || report_.predictor == Predictor::Trend) {
        predictor_ = build_one(report_.predictor);
    } else if (report_.predictor == Predictor::Average) {
        const std::vector<Predictor>& members = options.averaged;
        bool distinct = members.size() >= 2;
        for (std::size_t k = 0; k < members.size(); ++k)
            for (std::size_t m = 0; m < k; ++m) distinct = distinct && members[k] != members[m];
        if (!distinct || std::count(members.begin(), members.end(), Predictor::Average) > 0)
            throw InvalidArgument(std::string(where) +
                                  ": the average predictor needs two or three distinct of kriging, rbf and trend");
        const kriging::Interpolator* kriged = nullptr;
        std::vector<std::unique_ptr<kriging::Interpolator>> owned;
        for (const Predictor p : members) {
            if (p == Predictor::Kriging)
                kriged = local_ ? static_cast<const kriging::Interpolator*>(local_.get())
                                : static_cast<const kriging::Interpolator*>(&kriging_);
            else owned.push_back(build_one(p));
        }
        predictor_ = std::make_unique<MeanOfPredictors>(kriged, std::move(owned));
    }

    // Timing kernel on the inverse-warp increments.
    const MatX inc = aligned.inverse_warp_increments();  // T - 1 by N
    kriging::MotionKrigingOptions mk;
    mk.scope = kriging::KernelScope::PerSet;
    mk.scaling = scaling_;
    mk.exponent = options.timing_exponent;
    mk.variogram = options.variogram;
    mk.fit = options.fit;
    mk.kriging = options.kriging;
    increments_ = inc.transpose();
    timing_kernel_ = options.timing_kernel;
    if (timing_kernel_ == SynthesisOptions::TimingKernel::Separate) {
        timing_ = kriging::MotionKriging::build(coords_, increments_, MatX(), MatX(), mk);
        report_.timing_exponent = timing_.report().exponent;
    } else {
        report_.timing_exponent = model.paper_p();
    }
    min_increment_ = options.min_increment_fraction * inc.mean();
    max_increment_ = options.max_increment_factor * inc.maxCoeff();
    report_.precompute_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

const kriging::Kriging& SynthesisModel::kernel() const {
    if (local_)
        throw InvalidArgument("SynthesisModel::kernel: the model of " + std::to_string(samples()) +
                              " samples uses local kriging of " + std::to_string(local_->neighbours()) +
                              " neighbours, which has no global kriging system");
    return kriging_;
}

const kriging::Interpolator& SynthesisModel::weight_interpolator() const {
    if (predictor_) return *predictor_;
    if (local_) return *local_;
    return kriging_;
}

VecX SynthesisModel::kernel_reliability(const Eigen::Ref<const MatX>& xc) const {
    return local_ ? local_->reliability(xc) : kriging_.reliability(xc);
}

std::size_t SynthesisModel::memory_bytes() const {
    // Per kriging kernel: the variogram matrix and the inverse data block (N by N each), the weight
    // operator (N by N + P + 1) and the single-query operator (the lower half of the N by N block).
    // Kernels: the coefficient kernel, and a Separate timing kernel (which keeps its own copy of the
    // increments); plus the increments.
    const auto n = static_cast<std::size_t>(samples());
    const auto k = static_cast<std::size_t>(parameters()) + 1;
    // The local kriging keeps the normalized points only (its k by k systems live during a query).
    const std::size_t kernel =
        local_ ? n * static_cast<std::size_t>(local_->dimension()) : 2 * n * n + n * (n + k) + n * (n + 1) / 2;
    const std::size_t increments = n * static_cast<std::size_t>(frames_ - 1);
    const bool separate = timing_kernel_ == SynthesisOptions::TimingKernel::Separate;
    return sizeof(double) *
           (static_cast<std::size_t>(coords_.size()) + kernel + increments + (separate ? kernel + increments : 0));
}

void SynthesisModel::normalize(const Eigen::Ref<const VecX>& c, VecX& out, const char* where) const {
    if (c.size() != parameters()) {
        throw InvalidArgument(std::string(where) + ": c must have P = " + std::to_string(parameters()) +
                              " entries, got " + std::to_string(c.size()));
    }
    if (!c.allFinite()) throw InvalidArgument(std::string(where) + ": c must be finite");
    scaling_.apply_point(c, out);
}

void SynthesisModel::weights(const Eigen::Ref<const VecX>& c, Eigen::Ref<VecX> out, Workspace& ws) const {
    normalize(c, ws.c_normalized, "SynthesisModel::weights");
    if (out.size() != samples()) {
        throw InvalidArgument("SynthesisModel::weights: out must have N = " + std::to_string(samples()) + " entries");
    }
    weight_interpolator().weights(ws.c_normalized, out, ws.kriging);
}

void SynthesisModel::coefficients(const Eigen::Ref<const VecX>& c, Eigen::Ref<VecX> out, Workspace& ws) const {
    if (out.size() != coefficient_size()) {
        throw InvalidArgument("SynthesisModel::coefficients: out must have S = " + std::to_string(coefficient_size()) +
                              " entries, got " + std::to_string(out.size()));
    }
    if (!folded_.empty()) {
        normalize(c, ws.c_normalized, "SynthesisModel::coefficients");
        folded_.predict(ws.c_normalized, out, ws.kriging);
        return;
    }
    if (ws.weights.size() != samples()) ws.weights.resize(samples());
    weights(c, ws.weights, ws);
    coefficients_from_weights(ws.weights, out);
}

void SynthesisModel::pose(const Eigen::Ref<const VecX>& c, double t, Eigen::Ref<VecX> out, Workspace& ws,
                          Eigen::Index level) const {
    if (ws.coefficients.size() != coefficient_size()) ws.coefficients.resize(coefficient_size());
    coefficients(c, ws.coefficients, ws);
    pose_from_coefficients(ws.coefficients, t, out, ws, level);
}

VecX SynthesisModel::pose(const Eigen::Ref<const VecX>& c, double t, Eigen::Index level) const {
    Workspace ws;
    VecX out(dofs_);
    pose(c, t, out, ws, level);
    return out;
}

void SynthesisModel::poses(const Eigen::Ref<const MatX>& C, double t, Eigen::Ref<MatX> out, BatchWorkspace& ws,
                           Eigen::Index level) const {
    if (C.cols() != parameters() || !C.allFinite()) {
        throw InvalidArgument("SynthesisModel::poses: C must be Q by P = " + std::to_string(parameters()) +
                              " and finite, got " + std::to_string(C.rows()) + "x" + std::to_string(C.cols()));
    }
    const Eigen::Index q = C.rows();
    if (scaling_.has_periodic_axis() || scaling_.has_categorical_axis()) {
        ws.c_normalized = scaling_.apply(C);
    } else {
        if (ws.c_normalized.rows() != q || ws.c_normalized.cols() != parameters())
            ws.c_normalized.resize(q, parameters());
        ws.c_normalized =
            ((C.rowwise() - scaling_.offset.transpose()).array().rowwise() / scaling_.scale.transpose().array())
                .matrix();
    }
    if (!folded_.empty()) {
        if (ws.coefficients.rows() != coefficient_size() || ws.coefficients.cols() != q)
            ws.coefficients.resize(coefficient_size(), q);
        folded_.predict_batch(ws.c_normalized, ws.coefficients, ws.kriging);
    } else if (local_ && !predictor_) {
        // One local system per character, its coefficients straight from its weights (no N by Q matrix).
        if (ws.coefficients.rows() != coefficient_size() || ws.coefficients.cols() != q)
            ws.coefficients.resize(coefficient_size(), q);
        kriging::QueryWorkspace kws;
        VecX w(samples());
        for (Eigen::Index k = 0; k < q; ++k) {
            local_->weights(ws.c_normalized.row(k).transpose(), w, kws);
            coefficients_from_weights(w, ws.coefficients.col(k));
        }
    } else {
        if (ws.weights.rows() != samples() || ws.weights.cols() != q) ws.weights.resize(samples(), q);
        weight_interpolator().weights_batch(ws.c_normalized, ws.weights);
        coefficients_from_weights_batch(ws.weights, ws.coefficients);
    }
    poses_from_coefficients(ws.coefficients, t, out, ws, level);
}

void SynthesisModel::frame_pair(double t, Eigen::Index level, Eigen::Index& t0, Eigen::Index& t1, double& a,
                                const char* where) const {
    if (!(t >= 0.0 && t <= static_cast<double>(frames_ - 1))) {
        throw InvalidArgument(std::string(where) + ": aligned frame t = " + std::to_string(t) + " outside [0, " +
                              std::to_string(frames_ - 1) + "]");
    }
    if (level < 0 || level >= levels()) {
        throw InvalidArgument(std::string(where) + ": level " + std::to_string(level) + " outside [0, " +
                              std::to_string(levels() - 1) + "]");
    }
    t0 = std::min(static_cast<Eigen::Index>(std::floor(t)), frames_ - 1);
    a = t - static_cast<double>(t0);
    t1 = std::min(t0 + 1, frames_ - 1);
}

Timing SynthesisModel::timing(const Eigen::Ref<const VecX>& c) const {
    VecX cn;
    normalize(c, cn, "SynthesisModel::timing");
    Timing tm;
    tm.increments.resize(frames_ - 1);
    if (timing_kernel_ == SynthesisOptions::TimingKernel::Separate) {
        timing_.predict(c, tm.increments);
    } else {
        kriging::QueryWorkspace kws;
        VecX w(samples());
        weight_interpolator().weights(cn, w, kws);
        tm.increments.noalias() = increments_.transpose() * w;
    }
    tm.warp.resize(frames_);
    tm.warp(0) = 0.0;
    for (Eigen::Index k = 0; k + 1 < frames_; ++k) {
        double& v = tm.increments(k);
        if (v < min_increment_) {
            v = min_increment_;
            ++tm.clamped;
        } else if (v > max_increment_) {
            v = max_increment_;
            ++tm.clamped;
        }
        tm.warp(k + 1) = tm.warp(k) + v;
    }
    return tm;
}

MatX SynthesisModel::motion_poses(const Eigen::Ref<const VecX>& c, Eigen::Index level) const {
    const Timing tm = timing(c);
    Workspace ws;
    VecX u(coefficient_size());
    coefficients(c, u, ws);
    const Eigen::Index f_count = tm.frame_count();
    MatX poses(dofs_, f_count);
    for (Eigen::Index f = 0; f < f_count; ++f) {
        pose_from_coefficients(u, tm.aligned_frame(static_cast<double>(f)), poses.col(f), ws, level);
    }
    return poses;
}

Clip SynthesisModel::motion(const Eigen::Ref<const VecX>& c, Eigen::Index level) const {
    const MatX poses = motion_poses(c, level);
    Clip clip;
    clip.skeleton = skeleton_;
    clip.frame_rate = frame_rate_;
    clip.channels = from_pose_vectors(*skeleton_, poses, Canonicalization{});
    clip.name = "synthesized";
    return clip;
}

double SynthesisModel::reliability(const Eigen::Ref<const VecX>& c) const {
    VecX cn;
    normalize(c, cn, "SynthesisModel::reliability");
    return kernel_reliability(cn.transpose())(0);
}

double SynthesisModel::variance_ratio(const Eigen::Ref<const VecX>& c) const {
    VecX cn;
    normalize(c, cn, "SynthesisModel::variance_ratio");
    if (local_) return local_->estimate(cn).variance / local_->model().total_sill();
    return kriging_.estimate(cn).variance / kriging_.model().total_sill();
}

VecX SynthesisModel::reliability_batch(const Eigen::Ref<const MatX>& C) const {
    if (C.cols() != parameters() || !C.allFinite()) {
        throw InvalidArgument("SynthesisModel::reliability_batch: C must be Q by P = " + std::to_string(parameters()) +
                              " and finite");
    }
    return kernel_reliability(scaling_.apply(C));
}

}  // namespace mocapdb::synthesis
