#include "mocapdb/dataset/alignment.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "mocapdb/dataset/dtw.hpp"
#include "mocapdb/dataset/pose_distance.hpp"
#include "mocapdb/core/error.hpp"

namespace mocapdb {
namespace {

// Columns of `m` (values at frames 0..cols−1) linearly interpolated at fractional frame x.
VecX column_at(const MatX& m, double x) {
    const Eigen::Index last = m.cols() - 1;
    const double t = std::clamp(x, 0.0, static_cast<double>(last));
    const auto i = std::min<Eigen::Index>(static_cast<Eigen::Index>(t), last);
    const double a = t - static_cast<double>(i);
    if (i == last || a == 0.0) return m.col(i);
    return (1.0 - a) * m.col(i) + a * m.col(i + 1);
}

VecX uniform(Eigen::Index frames, double last) { return VecX::LinSpaced(frames, 0.0, last); }

std::size_t median_length_sample(const std::vector<Clip>& samples) {
    std::vector<std::size_t> order(samples.size());
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return samples[a].frame_count() < samples[b].frame_count(); });
    return order[(order.size() - 1) / 2];
}

void check_samples(const std::vector<Clip>& samples) {
    if (samples.empty()) throw InvalidArgument("align: no samples");
    for (std::size_t n = 0; n < samples.size(); ++n) {
        validate(samples[n]);
        if (samples[n].frame_count() < 2)
            throw InvalidArgument("align: sample " + std::to_string(n) + " ('" + samples[n].name +
                                  "') has fewer than 2 frames");
        if (!samples[n].skeleton->same_structure(*samples.front().skeleton))
            throw InvalidArgument("align: sample " + std::to_string(n) + " ('" + samples[n].name +
                                  "') has a different skeleton from sample 0");
    }
}

}  // namespace

AlignedSet align_samples(const std::vector<Clip>& samples, const AlignOptions& options) {
    check_samples(samples);
    if (options.method != "dtw" && options.method != "linear")
        throw InvalidArgument("align: method must be 'dtw' or 'linear', found '" + options.method + "'");
    if (options.frames < 2) throw InvalidArgument("align: at least 2 aligned frames are needed");
    if (options.canonical != "travel" && options.canonical != "first-frame")
        throw InvalidArgument("align: canonical must be 'travel' or 'first-frame', found '" + options.canonical + "'");
    const auto canonical_of = [&](const Clip& c) {
        return options.canonical == "travel" ? travel_canonicalization(c, options.travel).canonical
                                             : canonicalization_of(c);
    };
    // Beyond a few times the longest sample, more aligned frames only interpolate, and the tensor
    // (D x T x N doubles) grows without bound.
    std::size_t longest = 0;
    for (const Clip& s : samples) longest = std::max(longest, s.frame_count());
    const auto most = static_cast<Eigen::Index>(std::max<std::size_t>(4 * longest, kAlignedFramesAlwaysAllowed));
    if (options.frames > most) {
        const double bytes = 8.0 * static_cast<double>(PoseLayout(*samples.front().skeleton).dof_count()) *
                             static_cast<double>(options.frames) * static_cast<double>(samples.size());
        throw InvalidArgument("align: " + std::to_string(options.frames) + " aligned frames for samples of at most " +
                              std::to_string(longest) + " frames would only interpolate and take " +
                              std::to_string(static_cast<long long>(bytes / 1e6)) + " MB; use at most " +
                              std::to_string(most) + " (4x the longest sample, or " +
                              std::to_string(kAlignedFramesAlwaysAllowed) + ")");
    }
    const std::size_t count = samples.size();
    const std::size_t ref = options.reference.value_or(median_length_sample(samples));
    if (ref >= count) throw InvalidArgument("align: reference sample " + std::to_string(ref) + " out of range");
    const Eigen::Index frames = options.frames;

    AlignedSet out;
    out.method = options.method;
    out.reference = ref;
    out.warps.resize(frames, static_cast<Eigen::Index>(count));
    const double ref_last = static_cast<double>(samples[ref].frame_count() - 1);
    const VecX tau = uniform(frames, ref_last);  // reference frame shown at each aligned frame
    const auto report = [&](std::size_t done, const char* what) {
        if (options.progress) options.progress({done, 2 * count, what});
    };
    if (options.method == "linear") {
        for (std::size_t n = 0; n < count; ++n)
            out.warps.col(static_cast<Eigen::Index>(n)) =
                uniform(frames, static_cast<double>(samples[n].frame_count() - 1));
    } else {
        const MatX ref_features = align::pose_features(samples[ref]);
        for (std::size_t n = 0; n < count; ++n) {
            if (n == ref) {
                out.warps.col(static_cast<Eigen::Index>(n)) = tau;
                continue;
            }
            const MatX features = align::pose_features(samples[n]);
            const MatX cost = align::pose_distance_matrix(features, ref_features);
            const align::DtwPath path = align::dtw(cost, options.band);
            const VecX w = align::warp_from_path(path, cost.rows(), cost.cols());
            out.warps.col(static_cast<Eigen::Index>(n)) = align::interpolate(w, tau);
            report(n + 1, "warp");
        }
    }
    report(count, "warp");

    // Pose vectors; the reference's first pose fixes the exp-map branches for every sample.
    out.canonical.resize(count);
    out.canonical[ref] = canonical_of(samples[ref]);
    const MatX ref_poses = to_pose_vectors(samples[ref], out.canonical[ref]);
    const VecX branch = ref_poses.col(0);
    const Eigen::Index dofs = ref_poses.rows();
    out.tensor.resize(dofs, frames, static_cast<Eigen::Index>(count));
    for (std::size_t n = 0; n < count; ++n) {
        if (n != ref) out.canonical[n] = canonical_of(samples[n]);
        const MatX poses = n == ref ? ref_poses : to_pose_vectors(samples[n], out.canonical[n], branch);
        for (Eigen::Index t = 0; t < frames; ++t) {
            const VecX p = column_at(poses, out.warps(t, static_cast<Eigen::Index>(n)));
            for (Eigen::Index d = 0; d < dofs; ++d) out.tensor(d, t, static_cast<Eigen::Index>(n)) = p[d];
        }
        report(count + n + 1, "poses");
    }

    // Per-dof mean and standard deviation over frames and samples.
    const Eigen::Index cols = frames * static_cast<Eigen::Index>(count);
    const Eigen::Map<const MatX> flat(out.tensor.data(), dofs, cols);
    out.mean = flat.rowwise().mean();
    out.scale = ((flat.colwise() - out.mean).array().square().rowwise().sum() / static_cast<double>(cols)).sqrt();
    for (Eigen::Index d = 0; d < dofs; ++d)
        if (!(out.scale[d] > 1e-9)) out.scale[d] = 1.0;
    validate(out);
    return out;
}

double mean_alignment_distance(const std::vector<Clip>& samples, const AlignedSet& aligned) {
    check_samples(samples);
    if (static_cast<Eigen::Index>(samples.size()) != aligned.samples())
        throw InvalidArgument("mean_alignment_distance: sample count differs from the aligned set");
    const std::size_t ref = aligned.reference;
    const MatX ref_features = align::pose_features(samples[ref]);
    double sum = 0.0;
    std::size_t terms = 0;
    for (std::size_t n = 0; n < samples.size(); ++n) {
        if (n == ref) continue;
        const MatX features = align::pose_features(samples[n]);
        for (Eigen::Index t = 0; t < aligned.frames(); ++t) {
            sum += align::pose_distance(column_at(features, aligned.warps(t, static_cast<Eigen::Index>(n))),
                                        column_at(ref_features, aligned.warps(t, static_cast<Eigen::Index>(ref))));
            ++terms;
        }
    }
    return terms ? sum / static_cast<double>(terms) : 0.0;
}

}  // namespace mocapdb
