#include "mocapdb/core/float32.hpp"
#include "mocapdb/packing/packed_group.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>
#include <mutex>
#include <sstream>

#include <zdict.h>
#include <zstd.h>

#include "group_model.hpp"
#include "mocapdb/core/parallel_tasks.hpp"
#include "mocapdb/motion/forward_kinematics.hpp"

namespace mocapdb::packing {
namespace {

using detail::GroupModel;
using detail::step_of;

void check_options(const PackOptions& o) {
    if (!(o.max_error_cm > 0) || !std::isfinite(o.max_error_cm))
        throw InvalidArgument("pack: max error must be a finite number > 0 cm, got " + std::to_string(o.max_error_cm));
    if (o.window < 2 || o.window > 256)
        throw InvalidArgument("pack: window must be 2..256 frames, got " + std::to_string(o.window));
    if (!(o.rounding >= 0.1 && o.rounding <= 0.5))
        throw InvalidArgument("pack: rounding must be in [0.1, 0.5], got " + std::to_string(o.rounding));
    if (o.threads < 1) throw InvalidArgument("pack: threads must be >= 1");
    if (o.trim_tail < 0) throw InvalidArgument("pack: trim_tail must be >= 0");
}

/// Window `w` of x (D by F) as D by W, the last frame repeated past the end.
MatX window_of(const MatX& x, int w, int length) {
    MatX out(x.rows(), length);
    const Eigen::Index f0 = static_cast<Eigen::Index>(w) * length;
    for (int t = 0; t < length; ++t) out.col(t) = x.col(std::min(f0 + t, x.cols() - 1));
    return out;
}

/// Descending eigen-decomposition of a symmetric matrix; basis rounded to multiples of kBasisStep
/// (as stored).
void eigen_basis(const MatX& moment, MatX& out_basis, std::vector<double>& out_values) {
    const auto n = moment.rows();
    out_basis.resize(n, n);
    out_values.resize(static_cast<std::size_t>(n));
    if (n == 0) return;  // every dof constant
    Eigen::SelfAdjointEigenSolver<MatX> solver(moment);
    for (Eigen::Index i = 0; i < n; ++i) {
        out_basis.col(i) =
            (solver.eigenvectors().col(n - 1 - i) / detail::kBasisStep).array().round() * detail::kBasisStep;
        out_values[static_cast<std::size_t>(i)] = std::max(0.0, solver.eigenvalues()[n - 1 - i]);
    }
}

struct WindowResult {
    std::uint8_t step = 0;
    std::vector<std::int32_t> q;  // scan order, trimmed after the last nonzero
    std::vector<double> raw;      // step == kRawStep: the window's source channel rows, row-major
};

struct ThreadState {
    explicit ThreadState(double e) : errors(e) {}
    ErrorAccumulator errors;
    ContextCounts counts;
    std::size_t probes = 0;
    std::size_t raw_windows = 0;
};

/// zstd's sizes for the windows' coefficients (see PackStats::zstd_*).
void measure_zstd(const std::vector<WindowResult>& results, PackStats& out) {
    std::vector<std::uint8_t> all;
    std::vector<std::size_t> sizes;
    for (const WindowResult& r : results) {
        const std::size_t before = all.size();
        all.push_back(r.step);
        for (std::int32_t v : r.q) {
            auto z = static_cast<std::uint32_t>((v << 1) ^ (v >> 31));
            while (z >= 0x80) {
                all.push_back(static_cast<std::uint8_t>(z | 0x80));
                z >>= 7;
            }
            all.push_back(static_cast<std::uint8_t>(z));
        }
        sizes.push_back(all.size() - before);
    }
    const int level = 19;
    std::vector<std::uint8_t> buffer(ZSTD_compressBound(all.size()));
    out.zstd_stream_bytes = ZSTD_compress(buffer.data(), buffer.size(), all.data(), all.size(), level);
    std::vector<std::uint8_t> dictionary(16384);
    const std::size_t dict_size = ZDICT_trainFromBuffer(dictionary.data(), dictionary.size(), all.data(), sizes.data(),
                                                        static_cast<unsigned>(sizes.size()));
    const bool have_dict = !ZDICT_isError(dict_size);
    ZSTD_CCtx* cctx = ZSTD_createCCtx();
    ZSTD_CDict* cdict = have_dict ? ZSTD_createCDict(dictionary.data(), dict_size, level) : nullptr;
    out.zstd_window_bytes = 0;
    out.zstd_dictionary_bytes = have_dict ? dict_size : 0;
    std::size_t offset = 0;
    for (std::size_t size : sizes) {
        const std::size_t plain =
            ZSTD_compressCCtx(cctx, buffer.data(), buffer.size(), all.data() + offset, size, level);
        out.zstd_window_bytes += plain;
        out.zstd_dictionary_bytes +=
            cdict ? ZSTD_compress_usingCDict(cctx, buffer.data(), buffer.size(), all.data() + offset, size, cdict)
                  : plain;
        offset += size;
    }
    ZSTD_freeCDict(cdict);
    ZSTD_freeCCtx(cctx);
}

}  // namespace

std::vector<std::vector<std::size_t>> group_clips(const std::vector<const Clip*>& clips) {
    std::vector<std::vector<std::size_t>> groups;
    std::vector<const Clip*> firsts;
    for (std::size_t i = 0; i < clips.size(); ++i) {
        const Clip& c = *clips[i];
        std::size_t g = 0;
        for (; g < firsts.size(); ++g)
            if (firsts[g]->frame_rate == c.frame_rate && detail::same_topology(*firsts[g]->skeleton, *c.skeleton))
                break;
        if (g == firsts.size()) {
            firsts.push_back(&c);
            groups.emplace_back();
        }
        groups[g].push_back(i);
    }
    return groups;
}

PackedGroup pack_group(const std::vector<const Clip*>& clips, const PackOptions& options,
                       const ProgressCallback& progress) {
    check_options(options);
    const auto started = std::chrono::steady_clock::now();
    PackedGroup result;
    GroupModel m;
    for (const Clip* c : clips) {
        if (c == nullptr) throw InvalidArgument("pack: null clip");
        validate(*c);
        if (c->frame_count() == 0) throw InvalidArgument("pack: clip '" + c->name + "' has no frames");
        if (c->frame_rate != clips.front()->frame_rate ||
            !detail::same_topology(*c->skeleton, *clips.front()->skeleton))
            throw InvalidArgument("pack: clip '" + c->name + "' has another topology or frame rate than '" +
                                  clips.front()->name + "' (use group_clips)");
    }
    if (!clips.empty() && (options.time_basis == TimeBasis::Auto || options.dof_basis == DofBasis::Auto)) {
        // Try each candidate on a sample; estimate the whole group's bytes as header + payload and
        // tables scaled by frames.
        const std::size_t every = (clips.size() + 7) / 8;
        std::vector<Clip> sample;
        std::size_t all_frames = 0, sample_frames = 0;
        for (const Clip* c : clips) all_frames += c->frame_count();
        for (std::size_t i = 0; i < clips.size(); i += every) {
            sample.push_back(clips[i]->frame_count() > 4000 ? slice(*clips[i], 0, 4000) : *clips[i]);
            sample.back().name = clips[i]->name;
            sample_frames += sample.back().frame_count();
        }
        std::vector<const Clip*> sample_ptrs;
        for (const Clip& c : sample) sample_ptrs.push_back(&c);
        std::vector<TimeBasis> times{options.time_basis};
        if (options.time_basis == TimeBasis::Auto) times = {TimeBasis::Learned, TimeBasis::Cosine};
        std::vector<DofBasis> dofs{options.dof_basis};
        if (options.dof_basis == DofBasis::Auto) dofs = {DofBasis::Learned, DofBasis::Identity};
        PackOptions best = options;
        double best_bytes = 0.0;
        bool first = true;
        for (TimeBasis tb : times)
            for (DofBasis db : dofs) {
                PackOptions trial = options;
                trial.time_basis = tb;
                trial.dof_basis = db;
                trial.compare_zstd = false;
                const PackStats s = pack_group(sample_ptrs, trial).stats;
                const double estimate = static_cast<double>(s.header_bytes) +
                                        static_cast<double>(s.payload_bytes + s.table_bytes) *
                                            static_cast<double>(all_frames) / static_cast<double>(sample_frames);
                if (first || estimate < best_bytes) {
                    best = trial;
                    best_bytes = estimate;
                    first = false;
                }
            }
        best.compare_zstd = options.compare_zstd;
        PackedGroup chosen = pack_group(clips, best, progress);
        chosen.stats.encode_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
        return chosen;
    }
    result.stats.time_basis = options.time_basis == TimeBasis::Auto ? TimeBasis::Learned : options.time_basis;
    result.stats.dof_basis = options.dof_basis == DofBasis::Auto ? DofBasis::Learned : options.dof_basis;
    if (clips.empty()) {
        m.write_header(result.bytes, &result.stats.parts);
        result.stats.bytes = result.stats.header_bytes = result.bytes.size();
        return result;
    }

    // Layout shared by the group.
    const Skeleton& s0 = *clips.front()->skeleton;
    m.frame_rate = clips.front()->frame_rate;
    m.window = options.window;
    m.pose_dofs = static_cast<int>(PoseLayout(s0).dof_count());
    m.extra_columns = detail::extra_position_columns(s0);
    m.dofs = m.pose_dofs + static_cast<int>(m.extra_columns.size());
    const int W = m.window;

    // Distinct skeletons (float32-rounded, as the decoder will see them) and per-clip entries.
    std::vector<const Skeleton*> sources;
    m.clips.resize(clips.size());
    std::uint64_t window_total = 0;
    for (std::size_t i = 0; i < clips.size(); ++i) {
        const Skeleton& s = *clips[i]->skeleton;
        std::size_t k = 0;
        while (k < sources.size() && !(sources[k] == &s || sources[k]->same_structure(s, 0.0))) ++k;
        if (k == sources.size()) {
            sources.push_back(&s);
            m.skeletons.push_back(detail::make_entry(s, m.pose_dofs, m.extra_columns.size()));
        }
        detail::ClipEntry& e = m.clips[i];
        e.skeleton = static_cast<std::uint32_t>(k);
        e.frames = clips[i]->frame_count();
        const Canonicalization c = canonicalization_of(*clips[i]);
        Canonicalization rounded;
        rounded.translation = Vec3(float32_value(c.translation.x()), 0.0, float32_value(c.translation.z()));
        rounded.yaw = float32_value(c.yaw);
        e.set_canonical(rounded);
        e.first_window = window_total;
        window_total += (e.frames + static_cast<std::uint64_t>(W) - 1) / static_cast<std::uint64_t>(W);
    }
    const auto total_units = static_cast<std::uint64_t>(2 * window_total);
    std::atomic<std::uint64_t> units_done{0};
    std::mutex progress_mutex;
    auto report = [&](const Clip& c) {
        if (!progress) return;
        std::lock_guard<std::mutex> lock(progress_mutex);
        progress(Progress{units_done.load(), total_units, c.name});
    };

    // One state per worker; an exception on any worker reaches the caller (run_on_workers).
    auto run_parallel = [&](auto&& per_clip, auto& states) {
        run_on_workers(states.size(), clips.size(), [&](std::size_t i, std::size_t t) { per_clip(i, states[t]); });
    };
    const std::size_t threads =
        static_cast<std::size_t>(std::min<std::size_t>(static_cast<std::size_t>(options.threads), clips.size()));

    // Pre-pass: which dofs vary in the group (the others are stored as constants).
    struct Range {
        VecX lo, hi;
    };
    std::vector<Range> ranges(threads, Range{VecX::Constant(m.dofs, 1e300), VecX::Constant(m.dofs, -1e300)});
    run_parallel(
        [&](std::size_t i, Range& r) {
            const MatX x = m.dofs_of(*clips[i], m.clips[i].canonical);
            r.lo = r.lo.cwiseMin(x.rowwise().minCoeff());
            r.hi = r.hi.cwiseMax(x.rowwise().maxCoeff());
        },
        ranges);
    for (std::size_t t = 1; t < threads; ++t) {
        ranges[0].lo = ranges[0].lo.cwiseMin(ranges[t].lo);
        ranges[0].hi = ranges[0].hi.cwiseMax(ranges[t].hi);
    }
    m.constant.assign(static_cast<std::size_t>(m.dofs), 0.0);
    for (int d = 0; d < m.dofs; ++d) {
        if (ranges[0].hi[d] - ranges[0].lo[d] > detail::kConstantTolerance) m.active.push_back(d);
        else m.constant[static_cast<std::size_t>(d)] = 0.5 * (ranges[0].hi[d] + ranges[0].lo[d]);
    }
    m.fold_constant_joints();
    const auto D = static_cast<Eigen::Index>(m.active.size());

    // Pass 0: the group's second moments along dofs and along time (ST-HOSVD at full rank).
    // Per clip, summed in clip order afterwards: the bases (and so the bytes) do not depend on
    // how clips were spread over threads.
    struct Moments {
        MatX dof, time;
        std::uint64_t windows = 0;
    };
    std::vector<Moments> per_clip(clips.size());
    std::vector<int> no_state(threads);
    run_parallel(
        [&](std::size_t i, int&) {
            const detail::ClipEntry& e = m.clips[i];
            const MatX x = m.weighted_active(*clips[i], m.skeletons[e.skeleton], e.canonical);
            const auto nw =
                static_cast<int>((e.frames + static_cast<std::uint64_t>(W) - 1) / static_cast<std::uint64_t>(W));
            Moments mo{MatX::Zero(D, D), MatX::Zero(W, W), 0};
            for (int w = 0; w < nw; ++w) {
                ++mo.windows;
                if (D == 0)
                    continue;  // every dof constant: no moments (and Eigen's rankUpdate of an empty matrix is UB)
                const MatX xw = window_of(x, w, W);
                mo.dof.selfadjointView<Eigen::Lower>().rankUpdate(xw);
                mo.time.selfadjointView<Eigen::Lower>().rankUpdate(xw.transpose());
            }
            per_clip[i] = std::move(mo);
            units_done += static_cast<std::uint64_t>(nw);
            report(*clips[i]);
        },
        no_state);
    Moments sum{MatX::Zero(D, D), MatX::Zero(W, W), 0};
    for (Moments& mo : per_clip) {
        sum.dof += mo.dof;
        sum.time += mo.time;
        sum.windows += mo.windows;
        mo = Moments{};
    }
    {
        const MatX dof_moment = sum.dof.selfadjointView<Eigen::Lower>();
        const MatX time_moment = sum.time.selfadjointView<Eigen::Lower>();
        std::vector<double> dof_values, time_values;
        eigen_basis(dof_moment, m.dof_basis, dof_values);
        eigen_basis(time_moment, m.time_basis, time_values);
        if (options.time_basis == TimeBasis::Cosine) {
            // Orthonormal DCT-II, rounded like a learned basis; energies as the learned ones'.
            for (int k = 0; k < W; ++k) {
                const double scale = std::sqrt((k == 0 ? 1.0 : 2.0) / W);
                for (int t = 0; t < W; ++t)
                    m.time_basis(t, k) =
                        std::round(scale * std::cos(kPi * (t + 0.5) * k / W) / detail::kBasisStep) * detail::kBasisStep;
                time_values[static_cast<std::size_t>(k)] =
                    std::max(0.0, m.time_basis.col(k).dot(time_moment * m.time_basis.col(k)));
            }
        }
        if (options.dof_basis == DofBasis::Identity) {
            m.dof_basis.setIdentity();
            for (Eigen::Index d = 0; d < D; ++d)
                dof_values[static_cast<std::size_t>(d)] = std::max(0.0, dof_moment(d, d));
        }
        double total = 0.0;
        for (double v : dof_values) total += v;
        const double nw = static_cast<double>(std::max<std::uint64_t>(1, sum.windows));
        for (double v : dof_values) m.dof_energy.push_back(static_cast<float>(v / nw));
        for (double v : time_values) m.time_energy.push_back(static_cast<float>(total > 0 ? v / total : 0.0));
        m.build_scan();
    }
    // The stored bases are rounded: project with their exact inverses so that reconstruction is
    // exact up to the coefficients' quantization.
    const MatX dof_inverse = D > 0 ? MatX(m.dof_basis.partialPivLu().inverse()) : MatX(0, 0);
    const MatX time_inverse_t = m.time_basis.partialPivLu().inverse().transpose();

    // Pass 1: per window, the coarsest step whose decode meets the bound; context statistics.
    std::vector<WindowResult> results(window_total);
    const double E = options.max_error_cm;
    const int k_start = std::clamp(static_cast<int>(std::lround(12.0 * (std::log2(E) + 14.0))), 0, 255);
    std::vector<ThreadState> states;
    for (std::size_t t = 0; t < threads; ++t) states.emplace_back(E);
    const auto cells = static_cast<std::size_t>(D) * static_cast<std::size_t>(W);
    const std::vector<double> roundings =
        options.rounding_search ? std::vector<double>{0.5, 0.4, 0.3, 0.2} : std::vector<double>{options.rounding};
    run_parallel(
        [&](std::size_t i, ThreadState& st) {
            const Clip& clip = *clips[i];
            const detail::ClipEntry& e = m.clips[i];
            const Skeleton& decoded_skeleton = *m.skeletons[e.skeleton].skeleton;
            const MatX x = m.weighted_active(clip, m.skeletons[e.skeleton], e.canonical);
            const MatX source = joint_positions(clip);
            const auto J = static_cast<Eigen::Index>(decoded_skeleton.size());
            const auto frames = static_cast<Eigen::Index>(e.frames);
            const auto nw = static_cast<int>((frames + W - 1) / W);
            GlobalPose pose;
            FrameMatrix rows;
            detail::WindowScratch scratch;
            std::vector<std::int32_t> q(cells);
            std::vector<double> dist, best_dist;
            std::vector<int> ks(roundings.size(), k_start);
            MatX g(D, W), tmp(D, W);
            std::vector<std::uint8_t> classes;
            for (int w = 0; w < nw; ++w) {
                tmp.noalias() = dof_inverse * window_of(x, w, W);
                g.noalias() = tmp * time_inverse_t;
                const Eigen::Index f0 = static_cast<Eigen::Index>(w) * W;
                const int count = static_cast<int>(std::min<Eigen::Index>(W, frames - f0));
                // Decodes q with step index kk; true when every position is within E (dist then
                // holds every distance).
                auto check = [&](int kk) -> bool {
                    ++st.probes;
                    m.reconstruct(e, kk, q, count, scratch, rows);
                    dist.clear();
                    for (int t = 0; t < count; ++t) {
                        forward_kinematics(decoded_skeleton, rows.row(t).data(), pose);
                        for (Eigen::Index j = 0; j < J; ++j) {
                            const double d =
                                (pose.positions[static_cast<std::size_t>(j)] - source.block<3, 1>(3 * j, f0 + t))
                                    .norm();
                            if (!(d <= E)) return false;
                            dist.push_back(d);
                        }
                    }
                    return true;
                };
                // Quantizes the window with step index kk, then check.
                auto probe = [&](int kk, double rounding) -> bool {
                    const double inv = 1.0 / step_of(kk);
                    for (std::size_t s = 0; s < cells; ++s) {
                        const double c = g.data()[m.scan[s]] * inv;
                        const double a = std::abs(c);
                        if (!(a < 1e9)) return false;
                        const auto mag = static_cast<std::int32_t>(std::floor(a + rounding));
                        q[s] = c < 0 ? -mag : mag;
                    }
                    return check(kk);
                };
                int best = -1;
                std::vector<std::int32_t> best_q;
                std::size_t best_cost = 0;
                for (std::size_t c = 0; c < roundings.size(); ++c) {
                    const double rounding = roundings[c];
                    int& k = ks[c];
                    int found = -1;
                    std::vector<std::int32_t> found_q;
                    std::vector<double> found_dist;
                    auto keep = [&](int kk) {
                        found = kk;
                        found_q = q;
                        std::swap(found_dist, dist);
                    };
                    // Galloping search from the previous window's step, then bisection: ends with
                    // `lo` passing and lo + 1 failing (or 255); `found` is the last passing probe.
                    int lo = -1, hi = -1;
                    if (probe(k, rounding)) {
                        keep(k);
                        lo = k;
                        for (int stride = 1; lo < detail::kMaxStep; stride *= 2) {
                            const int cand = std::min(detail::kMaxStep, lo + stride);
                            if (!probe(cand, rounding)) {
                                hi = cand;
                                break;
                            }
                            keep(cand);
                            lo = cand;
                        }
                    } else {
                        hi = k;
                        for (int stride = 1; lo < 0 && hi > 0; stride *= 2) {
                            const int cand = std::max(0, hi - stride);
                            if (probe(cand, rounding)) {
                                keep(cand);
                                lo = cand;
                            } else {
                                hi = cand;
                            }
                        }
                    }
                    while (hi >= 0 && hi - lo > 1) {
                        const int mid = (lo + hi) / 2;
                        if (probe(mid, rounding)) {
                            keep(mid);
                            lo = mid;
                        } else {
                            hi = mid;
                        }
                    }
                    if (lo < 0) {  // even the finest step fails: this rounding has no candidate
                        k = k_start;
                        continue;
                    }
                    k = lo;
                    if (options.trim_tail > 0) {
                        // Drop the last t nonzero +-1 coefficients of the scan (they cost their zero
                        // run too) for the largest t that still passes (bisection).
                        std::vector<std::size_t> tail;
                        for (std::size_t s = found_q.size();
                             s-- > 0 && tail.size() < static_cast<std::size_t>(options.trim_tail);) {
                            if (found_q[s] == 0) continue;
                            if (std::abs(found_q[s]) > 1) continue;
                            tail.push_back(s);
                        }
                        std::size_t ok = 0, bad = tail.size() + 1;
                        while (bad - ok > 1) {
                            const std::size_t mid = (ok + bad) / 2;
                            q = found_q;
                            for (std::size_t t = 0; t < mid; ++t) q[tail[t]] = 0;
                            if (check(found)) {
                                ok = mid;
                                std::swap(found_dist, dist);
                            } else {
                                bad = mid;
                            }
                        }
                        for (std::size_t t = 0; t < ok; ++t) found_q[tail[t]] = 0;
                    }
                    std::size_t cost = 0;
                    if (roundings.size() > 1) {  // bytes with untrained contexts: a proxy to compare roundings
                        position_classes(m.levels, step_of(found), classes);
                        cost = encode_coefficients(found_q, classes, m.grid(), ContextSet()).size();
                    }
                    if (found >= 0 && (best < 0 || cost < best_cost)) {
                        best = found;
                        best_cost = cost;
                        best_q = std::move(found_q);
                        best_dist = std::move(found_dist);
                    }
                }
                WindowResult& r = results[e.first_window + static_cast<std::uint64_t>(w)];
                if (best < 0) {
                    // Escape: the window's source channel rows, stored as they are (float64). Seen
                    // only where decoded rotations cannot be projected back onto a joint's channels
                    // stably (docs/packing.md); checked like any other window.
                    r.step = detail::kRawStep;
                    const FrameMatrix raw = clip.channels.middleRows(f0, count);
                    r.raw.assign(raw.data(), raw.data() + raw.size());
                    for (int t = 0; t < count; ++t) {
                        forward_kinematics(decoded_skeleton, raw.row(t).data(), pose);
                        for (Eigen::Index j = 0; j < J; ++j) {
                            const double d =
                                (pose.positions[static_cast<std::size_t>(j)] - source.block<3, 1>(3 * j, f0 + t))
                                    .norm();
                            if (!(d <= E)) {
                                std::ostringstream message;  // %g-like: E may be far below 1e-6 cm
                                message << "pack: clip '" << clip.name << "' window " << w << " frame " << f0 + t
                                        << ": even its source rows are " << d << " cm off (joint '"
                                        << decoded_skeleton.joint(static_cast<std::size_t>(j)).name
                                        << "') with the stored (float32) skeleton, over " << E << " cm";
                                throw PackingFailed(message.str());
                            }
                            st.errors.add(d);
                        }
                    }
                    ++st.raw_windows;
                    continue;
                }
                for (double d : best_dist) st.errors.add(d);
                std::size_t length = best_q.size();
                while (length > 0 && best_q[length - 1] == 0) --length;
                best_q.resize(length);
                position_classes(m.levels, step_of(best), classes);
                count_coefficients(best_q, classes, m.grid(), st.counts);
                r.step = static_cast<std::uint8_t>(best);
                r.q = std::move(best_q);
            }
            units_done += static_cast<std::uint64_t>(nw);
            report(clip);
        },
        states);

    ErrorAccumulator errors(E);
    ContextCounts counts;
    for (const ThreadState& st : states) {
        errors.merge(st.errors);
        for (std::size_t c = 0; c < counts.n.size(); ++c) {
            counts.n[c][0] += st.counts.n[c][0];
            counts.n[c][1] += st.counts.n[c][1];
        }
        result.stats.probes += st.probes;
        result.stats.raw_windows += st.raw_windows;
    }
    m.contexts = counts.to_contexts();
    if (options.compare_zstd) measure_zstd(results, result.stats);

    // Pass 2: entropy-code every window from the trained contexts.
    std::vector<std::vector<std::uint8_t>> payloads(window_total);
    m.windows.resize(window_total);
    std::vector<std::uint8_t> classes;
    for (std::size_t w = 0; w < window_total; ++w) {
        if (results[w].step == detail::kRawStep) {
            payloads[w].resize(results[w].raw.size() * sizeof(double));
            std::memcpy(payloads[w].data(), results[w].raw.data(), payloads[w].size());
        } else {
            position_classes(m.levels, step_of(results[w].step), classes);
            payloads[w] = encode_coefficients(results[w].q, classes, m.grid(), m.contexts);
        }
        m.windows[w].step = results[w].step;
        m.windows[w].size = static_cast<std::uint32_t>(payloads[w].size());
        results[w].q = {};
        results[w].raw = {};
    }
    m.write_header(result.bytes, &result.stats.parts);
    const std::size_t before_payload = result.bytes.size();
    std::uint64_t coded_bytes = 0, raw_bytes = 0;
    for (std::size_t w = 0; w < window_total; ++w) {
        result.stats.payload_bytes += payloads[w].size();
        (m.windows[w].step == detail::kRawStep ? raw_bytes : coded_bytes) += payloads[w].size();
    }
    add_part(result.stats.parts, "payload", coded_bytes);
    add_part(result.stats.parts, "raw_windows", raw_bytes);
    result.bytes.reserve(before_payload + result.stats.payload_bytes);
    for (const auto& p : payloads) result.bytes.insert(result.bytes.end(), p.begin(), p.end());

    PackStats& st = result.stats;
    st.clips = clips.size();
    for (const Clip* c : clips) st.frames += c->frame_count();
    st.windows = window_total;
    st.channels = s0.channel_count();
    st.bytes = result.bytes.size();
    std::size_t table = 0;
    for (const auto& c : m.clips) table += 12 + (c.frames < 128 ? 1 : c.frames < 16384 ? 2 : 3) + 1;
    for (const auto& w : m.windows) table += 1 + (w.size < 128 ? 1 : w.size < 16384 ? 2 : 3);
    st.table_bytes = table;
    st.header_bytes = before_payload - table;
    st.error = errors.stats();
    st.encode_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    return result;
}

}  // namespace mocapdb::packing
