#include "mocapdb/compression/joint_error.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>

#include "mocapdb/core/error.hpp"
#include "mocapdb/core/parallel_tasks.hpp"
#include "mocapdb/motion/forward_kinematics.hpp"
#include "mocapdb/motion/pose_vector.hpp"
#include "mocapdb/motion/pose_vector_positions.hpp"

namespace mocapdb::compression {
namespace {

Eigen::Map<const MatX> sample_slice(const Tensor3& a, Eigen::Index n) {
    const Eigen::Index d = a.dimension(0), t = a.dimension(1);
    return Eigen::Map<const MatX>(a.data() + n * d * t, d, t);
}

void check_same_shape(const Tensor3& reference, const Tensor3& approx) {
    for (int m = 0; m < 3; ++m)
        if (reference.dimension(m) != approx.dimension(m))
            throw InvalidArgument("joint error: the approximation is " + std::to_string(approx.dimension(0)) + " x " +
                                  std::to_string(approx.dimension(1)) + " x " + std::to_string(approx.dimension(2)) +
                                  ", the reference " + std::to_string(reference.dimension(0)) + " x " +
                                  std::to_string(reference.dimension(1)) + " x " +
                                  std::to_string(reference.dimension(2)));
}

// Samples per task of the parallel measurements: enough samples that an approximation computed per
// call amortizes its set-up (a product with a large matrix, which Eigen packs anew at every call: at
// 64 samples the packing was a fifth of the product's time), few enough that a failing check
// stops soon (256 samples: about 0.1 s of joint positions).
constexpr Eigen::Index kSamplesPerChunk = 256;

// The slices of an approximation held in memory, as a SampleApproximation.
SampleApproximation slices_of(const Tensor3& approx) {
    return [&approx](const std::vector<Eigen::Index>& ids, MatX& out) {
        const Eigen::Index d = approx.dimension(0), t = approx.dimension(1);
        out.resize(d, t * static_cast<Eigen::Index>(ids.size()));
        for (std::size_t i = 0; i < ids.size(); ++i)
            out.middleCols(static_cast<Eigen::Index>(i) * t, t) = sample_slice(approx, ids[i]);
    };
}

// Throws unless there is a skeleton and the reference's values per frame (and, for a weighted
// reference, its mean and weight) match its pose vector's dof count.
void check_dof_count(const Skeleton* skeleton, Eigen::Index values, Eigen::Index mean, Eigen::Index weight) {
    if (!skeleton) throw InvalidArgument("JointErrorMeter: no skeleton");
    const auto dofs = static_cast<Eigen::Index>(PoseLayout(*skeleton).dof_count());
    if (values != dofs || mean != dofs || weight != dofs)
        throw InvalidArgument(
            "JointErrorMeter: the reference has " + std::to_string(values) + " pose values per frame" +
            (mean == values && weight == values
                 ? std::string()
                 : ", its mean " + std::to_string(mean) + " and its weight " + std::to_string(weight)) +
            "; the skeleton's pose vector has " + std::to_string(dofs));
}

// Puts sample n at the front of the suspects (at most 64 kept); nothing when there is no list.
void note_suspect(std::vector<Eigen::Index>* suspects, Eigen::Index n) {
    if (!suspects || n < 0) return;
    suspects->erase(std::remove(suspects->begin(), suspects->end(), n), suspects->end());
    suspects->insert(suspects->begin(), n);
    if (suspects->size() > 64) suspects->resize(64);
}

}  // namespace

MatX pose_joint_positions(const Skeleton& skeleton, const Eigen::Ref<const MatX>& poses) {
    // Without the Euler round trip for joints with three rotation channels.
    return pose_vector_joint_positions(skeleton, poses, Canonicalization{});
}

JointErrorMeter::JointErrorMeter(std::shared_ptr<const Skeleton> skeleton, const Tensor3& reference, Reference hold)
    : skeleton_(std::move(skeleton)) {
    check_dof_count(skeleton_.get(), reference.dimension(0), reference.dimension(0), reference.dimension(0));
    if (hold == Reference::Copied) {
        owned_ = std::make_shared<const Tensor3>(reference);
        reference_ = owned_.get();
    } else {
        reference_ = &reference;
    }
    compute_reference_positions();
}

JointErrorMeter::JointErrorMeter(std::shared_ptr<const Skeleton> skeleton, const Tensor3& weighted_centred,
                                 const VecX& mean, const VecX& weight)
    : skeleton_(std::move(skeleton)), reference_(&weighted_centred), mean_(mean), weight_(weight) {
    check_dof_count(skeleton_.get(), weighted_centred.dimension(0), mean.size(), weight.size());
    if (!(weight.array() > 0.0).all() || !weight.allFinite() || !mean.allFinite())
        throw InvalidArgument("JointErrorMeter: the reference's weights must be finite and > 0, its mean finite");
    compute_reference_positions();
}

Eigen::Map<const MatX> JointErrorMeter::reference_poses(Eigen::Index n, MatX& buffer) const {
    const Eigen::Map<const MatX> slice = sample_slice(*reference_, n);
    if (mean_.size() == 0) return slice;
    // from_weighted_centred's arithmetic, one sample at a time.
    buffer = (slice.array().colwise() / weight_.array()).matrix().colwise() + mean_;
    return Eigen::Map<const MatX>(buffer.data(), buffer.rows(), buffer.cols());
}

void JointErrorMeter::compute_reference_positions() {
    const Eigen::Index samples = reference_->dimension(2);
    reference_positions_.resize(static_cast<std::size_t>(samples));
    const auto chunks = static_cast<std::size_t>((samples + kSamplesPerChunk - 1) / kSamplesPerChunk);
    run_parallel_tasks(chunks, [&](std::size_t c) {
        const Eigen::Index first = static_cast<Eigen::Index>(c) * kSamplesPerChunk;
        MatX buffer;
        for (Eigen::Index n = first; n < std::min(samples, first + kSamplesPerChunk); ++n)
            reference_positions_[static_cast<std::size_t>(n)] =
                pose_joint_positions(*skeleton_, reference_poses(n, buffer));
    });
}

JointErrorStats JointErrorMeter::measure(const Tensor3& approx) const {
    check_same_shape(*reference_, approx);
    return *measure_within(slices_of(approx), std::numeric_limits<double>::infinity());
}

bool JointErrorMeter::exceeds(const Tensor3& approx, double max_cm) const {
    check_same_shape(*reference_, approx);
    return !measure_within(slices_of(approx), max_cm).has_value();
}

// Arrays of N values (errors: N T J), written at sample n's place by whichever thread measures it.
struct JointErrorMeter::SampleFigures {
    float* errors;           // by sample, frame, joint: for the percentile only (#16: half the memory)
    double* sum;             // of the sample's errors
    double* sum_sq;          // of their squares
    double* dof_sq;          // squared pose-vector difference
    double* worst;           // the sample's largest error (its first occurrence, frame then joint)
    Eigen::Index* worst_at;  // where: frame * J + joint
};

Eigen::Index JointErrorMeter::check_samples(const SampleApproximation& approx, const std::vector<Eigen::Index>& ids,
                                            double max_cm, const SampleFigures* figures, char* flagged) const {
    const Tensor3& ref = *reference_;
    const Eigen::Index dofs = ref.dimension(0), frames = ref.dimension(1);
    const auto joints = static_cast<Eigen::Index>(skeleton_->size());
    const Eigen::Index per_sample = frames * joints;
    MatX buffer, reference_buffer;
    approx(ids, buffer);
    const auto count = static_cast<Eigen::Index>(ids.size());
    if (buffer.rows() != dofs || buffer.cols() != frames * count)
        throw InvalidArgument("joint error: the approximation of " + std::to_string(count) + " samples is " +
                              std::to_string(buffer.rows()) + " x " + std::to_string(buffer.cols()) + ", expected " +
                              std::to_string(dofs) + " x " + std::to_string(frames * count));
    for (Eigen::Index i = 0; i < count; ++i) {
        const Eigen::Index n = ids[static_cast<std::size_t>(i)];
        const auto slice = buffer.middleCols(i * frames, frames);
        const MatX p = pose_joint_positions(*skeleton_, slice);
        const MatX& r = reference_positions_[static_cast<std::size_t>(n)];
        float* out = figures ? figures->errors + n * per_sample : nullptr;
        bool over = false;
        double sum = 0.0, sum_sq = 0.0, worst = -1.0;
        Eigen::Index worst_at = 0;
        for (Eigen::Index f = 0; f < frames; ++f)
            for (Eigen::Index j = 0; j < joints; ++j) {
                const double e = (p.block<3, 1>(3 * j, f) - r.block<3, 1>(3 * j, f)).norm();
                if (e > max_cm) {
                    if (!flagged) return n;
                    over = true;
                }
                if (!out) continue;
                out[f * joints + j] = static_cast<float>(e);
                sum += e;
                sum_sq += e * e;
                if (e > worst) {
                    worst = e;
                    worst_at = f * joints + j;
                }
            }
        if (over) flagged[n] = 1;
        if (!figures) continue;
        figures->sum[n] = sum;
        figures->sum_sq[n] = sum_sq;
        figures->worst[n] = worst;
        figures->worst_at[n] = worst_at;
        figures->dof_sq[n] = (slice - reference_poses(n, reference_buffer)).squaredNorm();
    }
    return -1;
}

bool JointErrorMeter::a_suspect_exceeds(const SampleApproximation& approx, double max_cm,
                                        std::vector<Eigen::Index>* suspects) const {
    if (!suspects || suspects->empty()) return false;
    const Eigen::Index total = reference_->dimension(2);
    std::vector<Eigen::Index> ids;
    for (const Eigen::Index n : *suspects)
        if (n >= 0 && n < total) ids.push_back(n);
    const Eigen::Index found = ids.empty() ? -1 : check_samples(approx, ids, max_cm, nullptr, nullptr);
    if (found < 0) return false;
    note_suspect(suspects, found);
    return true;
}

bool JointErrorMeter::exceeds_on(const SampleApproximation& approx, const std::vector<Eigen::Index>& samples,
                                 double max_cm, std::vector<Eigen::Index>* suspects) const {
    const Eigen::Index total = reference_->dimension(2);
    for (const Eigen::Index n : samples)
        if (n < 0 || n >= total)
            throw InvalidArgument("JointErrorMeter::exceeds_on: sample " + std::to_string(n) + " is not in [0, " +
                                  std::to_string(total) + ")");
    if (a_suspect_exceeds(approx, max_cm, suspects)) return true;
    std::atomic<bool> stop{false};
    std::atomic<Eigen::Index> exceeded{-1};
    const auto count = static_cast<Eigen::Index>(samples.size());
    const auto chunks = static_cast<std::size_t>((count + kSamplesPerChunk - 1) / kSamplesPerChunk);
    run_parallel_tasks(chunks, [&](std::size_t c) {
        if (stop) return;
        const Eigen::Index first = static_cast<Eigen::Index>(c) * kSamplesPerChunk;
        const std::vector<Eigen::Index> ids(samples.begin() + first,
                                            samples.begin() + std::min(count, first + kSamplesPerChunk));
        const Eigen::Index found = check_samples(approx, ids, max_cm, nullptr, nullptr);
        if (found >= 0) {
            Eigen::Index none = -1;
            exceeded.compare_exchange_strong(none, found);
            stop = true;
        }
    });
    if (stop) note_suspect(suspects, exceeded.load());
    return stop;
}

std::optional<JointErrorStats> JointErrorMeter::measure_within(const SampleApproximation& approx, double max_cm,
                                                               std::vector<Eigen::Index>* suspects,
                                                               std::vector<Eigen::Index>* beyond) const {
    const Tensor3& ref = *reference_;
    const Eigen::Index frames = ref.dimension(1), samples = ref.dimension(2);
    const auto joints = static_cast<Eigen::Index>(skeleton_->size());
    const Eigen::Index per_sample = frames * joints;
    // Uninitialized until a sample is measured (a failing check touches little of them).
    const auto n_values = static_cast<std::size_t>(samples);
    const std::unique_ptr<float[]> errors(new float[n_values * static_cast<std::size_t>(per_sample)]);
    std::vector<double> sums(n_values), sums_sq(n_values), dof_sq(n_values), worst(n_values);
    std::vector<Eigen::Index> worst_at(n_values);
    const SampleFigures figures{errors.get(),  sums.data(),  sums_sq.data(),
                                dof_sq.data(), worst.data(), worst_at.data()};
    // With `beyond`: per sample, whether it has a joint beyond max_cm (every sample is measured).
    std::vector<char> flagged(beyond ? static_cast<std::size_t>(samples) : 0, 0);

    if (!beyond && std::isfinite(max_cm) && a_suspect_exceeds(approx, max_cm, suspects)) return std::nullopt;

    std::atomic<bool> stop{false};
    std::atomic<Eigen::Index> exceeded{-1};
    const auto chunks = static_cast<std::size_t>((samples + kSamplesPerChunk - 1) / kSamplesPerChunk);
    run_parallel_tasks(chunks, [&](std::size_t c) {
        if (stop) return;
        const Eigen::Index first = static_cast<Eigen::Index>(c) * kSamplesPerChunk;
        std::vector<Eigen::Index> ids;
        for (Eigen::Index n = first; n < std::min(samples, first + kSamplesPerChunk); ++n) ids.push_back(n);
        const Eigen::Index found = check_samples(approx, ids, max_cm, &figures, beyond ? flagged.data() : nullptr);
        if (found >= 0) {
            Eigen::Index none = -1;
            exceeded.compare_exchange_strong(none, found);
            stop = true;
        }
    });
    if (beyond) {
        beyond->clear();
        for (Eigen::Index n = 0; n < samples; ++n)
            if (flagged[static_cast<std::size_t>(n)]) beyond->push_back(n);
        if (!beyond->empty()) {
            note_suspect(suspects, beyond->front());
            return std::nullopt;
        }
    }
    if (stop) {
        note_suspect(suspects, exceeded.load());
        return std::nullopt;
    }

    JointErrorStats s;
    double all_dof_sq = 0.0;
    for (const double v : dof_sq) all_dof_sq += v;
    s.dof_rmse = ref.size() > 0 ? std::sqrt(all_dof_sq / static_cast<double>(ref.size())) : 0.0;
    const Eigen::Index count = samples * per_sample;
    s.positions = count;
    if (count == 0) return s;
    // In sample order, whatever thread measured which sample: the worst is the first largest error
    // in (sample, frame, joint) order.
    double sum = 0.0, sum_sq = 0.0;
    Eigen::Index worst_sample = 0;
    for (Eigen::Index n = 0; n < samples; ++n) {
        const auto i = static_cast<std::size_t>(n);
        sum += sums[i];
        sum_sq += sums_sq[i];
        if (worst[i] > worst[static_cast<std::size_t>(worst_sample)]) worst_sample = n;
    }
    if (frames > 0 && joints > 0) {
        const auto w = static_cast<std::size_t>(worst_sample);
        const Eigen::Index at = worst_at[w];
        s.worst = {worst_sample, at / joints, skeleton_->joint(static_cast<std::size_t>(at % joints)).name, worst[w]};
    }
    const double total = static_cast<double>(count);
    s.mean_cm = sum / total;
    s.rmse_cm = std::sqrt(sum_sq / total);
    s.max_cm = s.worst.error_cm;
    // Nearest-rank percentile: the smallest value with at least 99% of the errors at or below it
    // (rounding to float keeps the order, so this is the exact percentile rounded to float).
    const auto rank = static_cast<std::size_t>(std::ceil(0.99 * total)) - 1;
    float* const e0 = errors.get();
    std::nth_element(e0, e0 + rank, e0 + count);
    s.p99_cm = static_cast<double>(e0[rank]);
    return s;
}

MatX JointErrorMeter::max_error_per_frame(const Tensor3& approx) const {
    check_same_shape(*reference_, approx);
    const Eigen::Index samples = reference_->dimension(2), frames = reference_->dimension(1);
    const auto joints = static_cast<Eigen::Index>(skeleton_->size());
    MatX out = MatX::Zero(frames, samples);
    for (Eigen::Index n = 0; n < samples; ++n) {
        const MatX p = pose_joint_positions(*skeleton_, sample_slice(approx, n));
        const MatX& r = reference_positions_[static_cast<std::size_t>(n)];
        for (Eigen::Index f = 0; f < frames; ++f)
            for (Eigen::Index j = 0; j < joints; ++j)
                out(f, n) = std::max(out(f, n), (p.block<3, 1>(3 * j, f) - r.block<3, 1>(3 * j, f)).norm());
    }
    return out;
}

}  // namespace mocapdb::compression
