#include "runtime_transform.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <string>

#include "mocapdb/core/parallel_tasks.hpp"
#include "mocapdb/motion/forward_kinematics.hpp"

namespace mocapdb::packing::detail {

namespace {

/// Coarsest step index in [0, kMaxStep] for which passes(k) holds, galloping from `start`; -1 if none.
template <class F>
int rt_coarsest_step(int start, F passes) {
    int lo = -1, hi = -1;
    if (passes(start)) {
        lo = start;
        for (int stride = 1; lo < kMaxStep; stride *= 2) {
            const int c = std::min(kMaxStep, lo + stride);
            if (!passes(c)) {
                hi = c;
                break;
            }
            lo = c;
        }
    } else {
        hi = start;
        for (int stride = 1; lo < 0 && hi > 0; stride *= 2) {
            const int c = std::max(0, hi - stride);
            if (passes(c)) lo = c;
            else hi = c;
        }
    }
    while (hi >= 0 && lo >= 0 && hi - lo > 1) {
        const int mid = (lo + hi) / 2;
        if (passes(mid)) lo = mid;
        else hi = mid;
    }
    return lo;
}

/// The frames frame t of level spacing h is predicted from: lo and hi (t -+ h), and the far end of
/// the parent interval (t + 3h when t - h starts it, else t - 3h), with "near" the neighbour on its side.
struct RtPredictorFrames {
    Eigen::Index lo, hi, near, far, third;
};
RtPredictorFrames rt_predictor_frames(int t, int h) {
    const bool third_hi = (t - h) % (4 * h) == 0;
    return {t - h, t + h, third_hi ? t + h : t - h, third_hi ? t - h : t + h, third_hi ? t + 3 * h : t - 3 * h};
}

/// Predictor c of row d (the decoder's expressions, runtime_decoder.cpp rt_combine / rt_combine3).
double rt_predict(int c, const MatX& yh, Eigen::Index d, Eigen::Index t0, const RtPredictorFrames& f) {
    if (c == 0) return 0.5 * (yh(d, t0 + f.lo) + yh(d, t0 + f.hi));
    const double* w = kRuntimePredictorWeights[c];
    return w[0] * yh(d, t0 + f.near) + w[1] * yh(d, t0 + f.far) + w[2] * yh(d, t0 + f.third);
}

std::int32_t rt_quantize(double v, double inv_step, double rounding) {
    const double a = std::abs(v) * inv_step;
    const auto m = static_cast<std::int32_t>(std::floor(a + rounding));
    return v < 0 ? -m : m;
}

}  // namespace

RuntimeCoefficients runtime_transform(const GroupModel& m, const RuntimePosePlan& plan,
                                      const std::vector<const Clip*>& clips, double E, int W, int key_offset,
                                      double rounding, int threads, const ClipDone& clip_done) {
    RuntimeCoefficients r;
    r.window = W;
    r.key_offset = key_offset;
    while ((1 << r.levels) < W) ++r.levels;
    const auto Da = static_cast<Eigen::Index>(m.active.size());
    const MatX Uinv = Da > 0 ? MatX(m.dof_basis.partialPivLu().inverse()) : MatX(0, 0);
    // Clip by clip on the workers, each clip's search from the same start: the bytes do not depend
    // on the thread count.
    const int k_start = std::clamp(static_cast<int>(std::lround(12.0 * (std::log2(E) + 14.0))), 0, kMaxStep);
    std::vector<std::vector<RuntimeEntry>> clip_entries(clips.size());
    std::vector<double> clip_max(clips.size(), 0.0);
    const std::size_t workers = std::min<std::size_t>(static_cast<std::size_t>(std::max(1, threads)), clips.size());
    // Longest clips first, so that no worker is left alone with a long clip at the end.
    std::vector<std::size_t> order(clips.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return clips[a]->frame_count() > clips[b]->frame_count(); });
    run_on_workers(workers, clips.size(), [&](std::size_t task, std::size_t) {
        const std::size_t i = order[task];
        std::vector<double> row, p(static_cast<std::size_t>(m.dofs));
        GlobalPose pose;
        int kk_prev = k_start;
        std::vector<int> k_level(kMaxLevels + 1, k_start);
        std::vector<std::int32_t> q(static_cast<std::size_t>(Da * W)), kept_q(q.size());
        std::vector<double> kept_y(q.size());
        VecX tmp(Da);
        std::vector<RuntimeEntry>& entries = clip_entries[i];
        double& max_error_cm = clip_max[i];
        const Clip& clip = *clips[i];
        const ClipEntry& e = m.clips[i];
        if (clip.frame_count() == 0) return;
        const Skeleton& sk = *m.skeletons[e.skeleton].skeleton;
        row.resize(sk.channel_count());
        const MatX x = m.weighted_active(clip, m.skeletons[e.skeleton], e.canonical);
        const MatX source = joint_positions(clip);
        const auto F = static_cast<Eigen::Index>(clip.frame_count());
        const auto J = static_cast<Eigen::Index>(sk.size());
        const Eigen::Index nw = (F - 1 + W - 1) / W;
        const Eigen::Index T = nw * W + 1;
        MatX y(Da, T), yh(Da, T);
        for (Eigen::Index t = 0; t < T; ++t) y.col(t) = Uinv * x.col(std::min(t, F - 1));
        double worst = 0.0;
        // Decoded frame t (a source frame) within E, by the decoder's routine.
        auto frame_ok = [&](Eigen::Index t, const double* yt) {
            runtime_dofs(plan, e, yt, p.data());
            m.row_of(e, p.data(), row.data());
            forward_kinematics(sk, row.data(), pose);
            for (Eigen::Index j = 0; j < J; ++j) {
                const double d = (pose.positions[static_cast<std::size_t>(j)] - source.block<3, 1>(3 * j, t)).norm();
                if (!(d <= E)) return false;
                worst = std::max(worst, d);
            }
            return true;
        };
        const std::string where =
            "runtime tier: clip " + std::to_string(i) + (clip.name.empty() ? "" : " (" + clip.name + ")");
        // Keys.
        std::vector<std::vector<std::int32_t>> key_q(static_cast<std::size_t>(nw + 1));
        std::vector<int> key_step(static_cast<std::size_t>(nw + 1));
        for (Eigen::Index w = 0; w <= nw; ++w) {
            const Eigen::Index t = w * W;
            const Eigen::Index real = std::min(t, F - 1);
            auto passes = [&](int k) {
                const double step = step_of(k), inv = 1.0 / step;
                for (Eigen::Index d = 0; d < Da; ++d) tmp[d] = rt_quantize(y(d, t), inv, rounding) * step;
                return frame_ok(real, tmp.data());
            };
            int k = rt_coarsest_step(kk_prev, passes);
            if (k < 0)
                throw PackingFailed(where + ": key frame " + std::to_string(real) + " fails E even at the finest step");
            kk_prev = k;
            // A finer step for the key (better predictions); the bound is not monotone in the step,
            // so the key is checked again and made finer until it holds.
            auto& kq = key_q[static_cast<std::size_t>(w)];
            kq.resize(static_cast<std::size_t>(Da));
            for (k = std::max(0, k - key_offset);; --k) {
                if (k < 0)
                    throw PackingFailed(where + ": key frame " + std::to_string(real) +
                                        " fails E even at the finest step");
                const double step = step_of(k), inv = 1.0 / step;
                for (Eigen::Index d = 0; d < Da; ++d) {
                    kq[static_cast<std::size_t>(d)] = rt_quantize(y(d, t), inv, rounding);
                    yh(d, t) = kq[static_cast<std::size_t>(d)] * step;
                }
                worst = 0.0;
                if (frame_ok(real, yh.col(t).data())) break;
            }
            key_step[static_cast<std::size_t>(w)] = k;
            max_error_cm = std::max(max_error_cm, worst);
        }
        // Windows.
        std::vector<int> tree_level, tree_frame;
        runtime_tree_order(W, tree_level, tree_frame);
        for (Eigen::Index w = 0; w < nw; ++w) {
            const Eigen::Index t0 = w * W;
            RuntimeEntry entry;
            entry.level_step.assign(static_cast<std::size_t>(r.levels), 0);
            entry.level_predictor.assign(static_cast<std::size_t>(r.levels), 0);
            // Level by level: a frame's error is its own column's, so each level takes the coarsest
            // step for which its own frames hold, given the levels above it as decoded.
            for (int j = 1; j <= r.levels; ++j) {
                const int h = W >> j;
                int& kp = k_level[static_cast<std::size_t>(j)];
                // The predictor: the one whose residuals (against the decoded frames) cost the fewest
                // bits at the previous window's step of this level, by an estimate.
                int pm = 0;
                if (j > 1) {
                    const double inv = 1.0 / step_of(kp);
                    double best = 0.0;
                    for (int c = 0; c < kRuntimePredictors; ++c) {
                        double cost = 0.0;
                        for (int t = h; t < W && t0 + t < F; t += 2 * h) {
                            const RtPredictorFrames f = rt_predictor_frames(t, h);
                            for (Eigen::Index d = 0; d < Da; ++d)
                                cost += std::log2(1.0 + std::abs(y(d, t0 + t) - rt_predict(c, yh, d, t0, f)) * inv);
                        }
                        if (c == 0 || cost < best) {
                            best = cost;
                            pm = c;
                        }
                    }
                }
                bool zeros = true;              // the last encode quantized every value to 0
                int zeros_from = kMaxStep + 1;  // a step from which on the level is zeros and holds
                auto encode = [&](int k) {
                    const double step = step_of(k), inv = 1.0 / step;
                    zeros = true;
                    for (int t = h; t < W; t += 2 * h) {
                        const RtPredictorFrames f = rt_predictor_frames(t, h);
                        for (Eigen::Index d = 0; d < Da; ++d) {
                            const double pred = rt_predict(pm, yh, d, t0, f);
                            const std::int32_t v = rt_quantize(y(d, t0 + t) - pred, inv, rounding);
                            q[static_cast<std::size_t>(t * Da + d)] = v;
                            zeros = zeros && v == 0;
                            yh(d, t0 + t) = v ? pred + v * step : pred;  // the decoder's form: zeros add nothing
                        }
                    }
                };
                // The level's values, decoded frames and max error at the last step that held (the
                // search's last passing step is the one it returns: no encode again).
                auto keep = [&](bool restore) {
                    std::size_t at = 0;
                    for (int t = h; t < W; t += 2 * h)
                        for (Eigen::Index d = 0; d < Da; ++d, ++at) {
                            if (restore) {
                                q[static_cast<std::size_t>(t * Da + d)] = kept_q[at];
                                yh(d, t0 + t) = kept_y[at];
                            } else {
                                kept_q[at] = q[static_cast<std::size_t>(t * Da + d)];
                                kept_y[at] = yh(d, t0 + t);
                            }
                        }
                };
                double kept_worst = 0.0;
                int kept_k = -1;
                // Zeros at step k stay zeros at any coarser step, with the same decoded frames.
                auto passes = [&](int k) {
                    if (k >= zeros_from && kept_k >= zeros_from) {
                        kept_k = k;  // the kept state is the zeros'
                        return true;
                    }
                    encode(k);
                    worst = 0.0;
                    for (int t = h; t < W && t0 + t < F; t += 2 * h)
                        if (!frame_ok(t0 + t, yh.col(t0 + t).data())) return false;
                    if (zeros) zeros_from = k;
                    keep(false);
                    kept_worst = worst;
                    kept_k = k;
                    return true;
                };
                int k;
                if (t0 + h >= F) {
                    k = j > 1 ? entry.level_step[static_cast<std::size_t>(j - 2)]
                              : kp;  // no source frame at this level
                    encode(k);
                } else {
                    k = rt_coarsest_step(kp, passes);
                    if (k < 0)
                        throw PackingFailed(where + ": window " + std::to_string(w) +
                                            " fails E even at the finest step");
                    // The bound is not monotone in the step: two coarser steps are tried as well.
                    for (const int c : {k + 2, k + 4})
                        if (c <= kMaxStep && passes(c)) k = c;
                    if (kept_k != k) {  // the kept state is the last step that held, k's (a safeguard)
                        zeros_from = kMaxStep + 1;
                        passes(k);
                    }
                    keep(true);
                    max_error_cm = std::max(max_error_cm, kept_worst);
                    kp = k;
                }
                entry.level_step[static_cast<std::size_t>(j - 1)] = k;
                entry.level_predictor[static_cast<std::size_t>(j - 1)] = pm;
            }
            entry.key_step = key_step[static_cast<std::size_t>(w)];
            entry.key = std::move(key_q[static_cast<std::size_t>(w)]);
            entry.step = entry.level_step[0];
            for (int t : tree_frame) entry.columns.emplace_back(q.begin() + t * Da, q.begin() + (t + 1) * Da);
            entries.push_back(std::move(entry));
        }
        RuntimeEntry end;
        end.key_step = key_step[static_cast<std::size_t>(nw)];
        end.key = std::move(key_q[static_cast<std::size_t>(nw)]);
        entries.push_back(std::move(end));
        if (clip_done) clip_done(i);
    });
    for (std::size_t i = 0; i < clips.size(); ++i) {
        r.clip_first.push_back(r.entries.size());
        for (RuntimeEntry& entry : clip_entries[i]) r.entries.push_back(std::move(entry));
        r.max_error_cm = std::max(r.max_error_cm, clip_max[i]);
    }
    r.clip_first.push_back(r.entries.size());
    return r;
}

}  // namespace mocapdb::packing::detail
