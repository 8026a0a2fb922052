// Prototype of a runtime packed format (a measurement, not a format): can a time-LOCAL transform give
// a cold random pose from the stored bytes in about a microsecond without losing format 2's bytes?
// Results and reading: benchmarks/RESULTS.md, "Runtime format prototype".
//
// Candidate: each clip's weighted active dofs in format 2's dof basis (y = U⁻¹ x; the group's
// skeletons, weights and basis are parsed from format 2's bytes), keys every W frames (shared by
// neighbouring windows), and between them a closed-loop hierarchical linear prediction: level j holds
// the frames at odd multiples of W/2^j, each predicted as the mean of its two reconstructed
// neighbours, the difference quantized (dead zone, --rounding). A frame reads 2 keys and log2(W)
// detail columns, and its error is its own column's quantization error (no accumulation). Each key
// takes the coarsest step that keeps its frame within E, made finer by --key-offsets step indices and
// checked again (the bound is not monotone in the step); each window the coarsest step that keeps its
// frames within E, by the decoder's own routine (pose_of, row_of, FK of every joint and end site
// against the source clip).
//
// Columns: rows up to the last nonzero one, coded JPEG-like ((zero run, bit length) pairs as one
// symbol, sign and lower bits raw, an end symbol), static canonical Huffman codes per (level, row/8)
// limited to --code-bits bits so that one table lookup decodes a symbol. Per window: key step, key,
// window step, a directory, the columns in tree order (frame t's path: skip left subtrees).
//   variant 1  directory = each internal node's left-subtree size in bits (per level one width);
//              a frame decodes its columns one after the other
//   variant 2  directory = the key's and every column's size; the frame's columns decode as
//              independent chains, interleaved symbol by symbol (checked equal to variant 1)
//   variant 4  keys at the END of their entries, bytes reversed (read backwards from the next entry's
//              offset), so that a frame's two keys start at known places and decode interleaved; the
//              path's columns as variant 1; decode tables of --lookups bits giving up to two (run, size)
//              symbols per lookup (same codes and bits as variant 1)
//   variant 7  variant 4 with keys at fixed widths: per clip and row a width (coded against the group's
//              largest), a center and, with --key-escapes, escapes (a value outside the width's range
//              written after the key's slots): no symbol chain for keys
//   variant 8  variant 7 with each window's level-1 column at fixed widths too (per clip and row, with
//              escapes, center 0), between the window's step byte and its directory
//   variant 9  variant 7's keys (decoded two at once by a per-clip plan); each detail column by QUADS
//              (--quads S:shift:levels:bits:1:prefetch:avx2; the 5th field is unused): four rows per symbol, a pattern when
//              all four are within [-S, S], else a width and the four values raw; codes per (level,
//              row >> shift) of at most `bits` bits, one lookup a quad; the directory holds `levels`
//              levels (a finer left subtree is skipped by scanning its codes), its widths per clip
//              where smaller; entry offsets per clip at the clip's width (counted and read so);
//              `prefetch`: the clip's key plan first; then --quads' 7th field: the combine with AVX2
// With --combos 8:4 or 16:12 the library's runtime tier (packing::encode_runtime, RuntimeDecoder: variant
// 9 with 1 or 2 directory levels) is built from the same packed groups, its local poses checked equal to
// variant 9's (first --quads config) on every frame, and timed in the same repeats ("library" row).
// Variants 4, 7, 8 and 9 are checked equal to variant 1 on every frame (so within E) and timed against
// it in the same repeats. RT_STATS=1 in the environment: per level value histograms and estimates of
// codes by groups of rows (scheme_bits). --float-dofs 1: x = U y in float32 (runtime_pose.hpp's product) in the
// encoder's bound check, the check of every frame and the timings (closed loop); variants 7 and 8 are
// also timed with y -> local pose by runtime_pose.hpp's kernels (portable and, where the CPU has it,
// AVX2), whose dofs and local poses are checked equal, bit for bit, to the library path's on every
// frame. --dof identity: no dof basis.
// With --poses N: both bitstreams are built, every frame of every clip is decoded from the bytes and
// compared with its source (FK, cm), and N cold random local poses (random clip and frame, nothing
// kept) are timed (thread CPU, best of 3) beside format 2's GroupDecoder::decode_local_pose on the
// same sequence. Bytes: entries + 3-byte offsets + code tables (5 bits per symbol) + format 2's header
// (a conservative stand-in: it also holds format 2's time basis and contexts).
// Also printed: estimates of the candidate's bytes (ideal static entropy; one bit width per window,
// level and row; per-row Huffman values) and format 2's own coefficients under the same estimator.
//
//   bench_runtime_prototype [--folders cmu-walkrun-pfnn,cmu-asfamc] [--errors 1,0.1] [--windows 16,32]
//                           [--key-offsets 0,12] [--rounding 0.4] [--code-bits 11] [--poses N] [--limit N]
//                           [--lookups 11,9,8] [--reps 3] [--float-dofs 0|1] [--key-centers 0|1] [--key-escapes 0|1]
//                           [--dof learned|identity] [--quads 1:3:2:11:1:1,...] [--combos 16:12,8:4]
#include <Eigen/LU>
#ifdef __SSE2__
#include <emmintrin.h>
#endif
#include <algorithm>
#include <cmath>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <random>
#include <map>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench_timing.hpp"
#include "shared_folder.hpp"
#include "mocapdb/motion/forward_kinematics.hpp"
#include "mocapdb/packing/group_decoder.hpp"
#include "mocapdb/packing/packed_group.hpp"
#include "mocapdb/packing/runtime_decoder.hpp"
#include "mocapdb/packing/runtime_encoder.hpp"
#include "../lib/src/packing/group_model.hpp"
#include "../lib/src/packing/runtime_pose.hpp"

using namespace mocapdb;
using namespace mocapdb::packing;

namespace {

std::vector<std::string> split(const std::string& s) {
    std::vector<std::string> out;
    std::stringstream in(s);
    for (std::string item; std::getline(in, item, ',');)
        if (!item.empty()) out.push_back(item);
    return out;
}

int bit_length(std::uint32_t v) {
    int n = 0;
    while (v) {
        ++n;
        v >>= 1;
    }
    return n;
}

/// Empirical static entropy of symbols per context, bits, with a table cost per used entry.
struct StaticCost {
    std::map<std::pair<int, int>, std::map<int, std::size_t>> counts;  // (context) -> symbol -> n
    double extra_bits = 0.0;                                           // escapes' uniform bits
    void add(int c1, int c2, std::int32_t q) {
        constexpr int kDirect = 40;
        int sym = q;
        if (q > kDirect || q < -kDirect) {
            sym = q > 0 ? kDirect + 1 : -kDirect - 1;
            extra_bits += 2.0 * bit_length(static_cast<std::uint32_t>(std::abs(q) - kDirect)) - 1.0;
        }
        ++counts[{c1, c2}][sym];
    }
    /// Bits of the contexts whose first key is `level` (all when level < 0), escapes excluded.
    double bits(int level = -1) const {
        double total = level < 0 ? extra_bits : 0.0;
        for (const auto& [ctx, hist] : counts) {
            if (level >= 0 && ctx.first != level) continue;
            std::size_t n = 0;
            for (const auto& [s, k] : hist) n += k;
            for (const auto& [s, k] : hist) total += static_cast<double>(k) * std::log2(static_cast<double>(n) / static_cast<double>(k));
            total += 10.0 * static_cast<double>(hist.size());
        }
        return total;
    }
};

struct HierResult {
    double static_bits = 0.0, fixed_bits = 0.0;
    /// Per clip its windows and then its end key: the key at the window's start (step index and
    /// values), the window's step index and detail columns in tree order (none for the end key).
    struct Entry {
        int key_step = 0;
        std::vector<std::int32_t> key;
        int step = -1;
        std::vector<std::vector<std::int32_t>> columns;
    };
    std::vector<Entry> entries;
    std::vector<std::size_t> clip_first;  ///< per clip, its first entry
    /// Per window: its start key (level 0), then its detail columns in tree order (level, values).
    std::vector<std::vector<std::pair<int, std::vector<std::int32_t>>>> window_columns;
    double max_error = 0.0;
    std::size_t windows = 0, keys = 0, nonzero = 0;
};

/// Coarsest step index in [0, kMaxStep] for which passes(k) holds, galloping from `start`; -1 if none.
template <class F>
int coarsest(int start, F passes) {
    int lo = -1, hi = -1;
    if (passes(start)) {
        lo = start;
        for (int stride = 1; lo < detail::kMaxStep; stride *= 2) {
            const int c = std::min(detail::kMaxStep, lo + stride);
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

std::int32_t quantize(double v, double inv_step, double rounding) {
    const double a = std::abs(v) * inv_step;
    const auto m = static_cast<std::int32_t>(std::floor(a + rounding));
    return v < 0 ? -m : m;
}

/// y -> local pose by runtime_pose.hpp's kernels: the dof basis in float32 (dp by da, zero padded),
/// and per skeleton entry of the group its weights, lanes and PoseKernel (pointing into them).
struct PosePlan {
    std::vector<float> basis;
    struct Skeleton {
        std::vector<double> inverse_weights;
        std::vector<detail::PoseLanes> lanes[3];
        detail::PoseKernel kernel;
        detail::PoseRoot root;
        bool root_projects = false;  ///< the motion root has rotation channels, but not three: scalar path
    };
    std::vector<Skeleton> skeletons;
};

std::unique_ptr<PosePlan> make_pose_plan(const detail::GroupModel& m) {
    auto plan = std::make_unique<PosePlan>();
    const int da = static_cast<int>(m.active.size()), dp = (da + 7) / 8 * 8;
    if (da > 256) throw std::runtime_error("runtime pose kernels: more than 256 active dofs");
    plan->basis.assign(static_cast<std::size_t>(dp) * static_cast<std::size_t>(da), 0.0f);
    for (int c = 0; c < da; ++c)
        for (int r = 0; r < da; ++r) plan->basis[static_cast<std::size_t>(c * dp + r)] = static_cast<float>(m.dof_basis(r, c));
    plan->skeletons.resize(m.skeletons.size());
    for (std::size_t e = 0; e < m.skeletons.size(); ++e) {
        PosePlan::Skeleton& sk = plan->skeletons[e];
        for (double w : m.skeletons[e].active_weights) sk.inverse_weights.push_back(1.0 / w);
        const auto view = m.skeletons[e].writer.local_view();
        const auto& joints = *view.joints;
        sk.root_projects = view.root_rotates && joints.front().present != 3;
        const std::size_t count[3] = {view.two_channel_joints, view.one_channel_joints,
                                      joints.size() - 1 - view.two_channel_joints - view.one_channel_joints};
        std::size_t first = 1;
        for (int kind = 0; kind < 3; ++kind) {
            for (std::size_t g = 0; 4 * g < count[kind]; ++g) {
                detail::PoseLanes lanes;
                lanes.count = static_cast<int>(std::min<std::size_t>(4, count[kind] - 4 * g));
                detail::TwoChannelLanes two;
                for (int l = 0; l < 4; ++l) {
                    const auto& j = joints[first + 4 * g + static_cast<std::size_t>(l < lanes.count ? l : 0)];
                    lanes.pose_row[l] = j.pose_row;
                    lanes.joint[l] = j.joint;
                    for (int r = 0; r < 3; ++r) {
                        for (int c = 0; c < 3; ++c) lanes.frame[3 * r + c][l] = j.euler_frame(r, c);
                        lanes.axis[r][l] = j.twist_axis[r];
                    }
                    if (kind == 0) detail::set_lane(two, l, j.euler_frame, j.missing);
                }
                for (int l = 0; l < 4; ++l) {
                    lanes.missing[l] = two.missing[l];
                    lanes.dot[l] = two.dot[l];
                    for (int r = 0; r < 3; ++r) {
                        lanes.first[r][l] = two.first[r][l];
                        lanes.second[r][l] = two.second[r][l];
                        lanes.cross[r][l] = two.cross[r][l];
                    }
                }
                sk.lanes[kind].push_back(lanes);
            }
            first += count[kind];
        }
        detail::PoseRoot& root = sk.root;
        root.joint = static_cast<int>(view.motion_root);
        root.rotates = view.root_rotates;
        root.adds = view.adds;
        std::memcpy(root.above_inverse, view.above_inverse.coeffs().data(), 4 * sizeof(double));
        for (int a = 0; a < 3; ++a) {
            root.translates[a] = view.root_translation[static_cast<std::size_t>(a)] >= 0 ? 1 : 0;
            root.above_position[a] = view.above_position[a];
            root.root_offset[a] = view.root_offset[a];
            root.offset[a] = (*view.offsets)[view.motion_root][a];
        }
        detail::PoseKernel& k = sk.kernel;
        k.root = &sk.root;
        k.da = da;
        k.dp = dp;
        k.dofs = m.dofs;
        k.basis = plan->basis.data();
        k.inverse_weights = sk.inverse_weights.data();
        k.active = m.active.data();
        k.constant = m.constant.data();
        for (int kind = 0; kind < 3; ++kind) {
            k.lanes[kind] = sk.lanes[kind].data();
            k.groups[kind] = static_cast<int>(sk.lanes[kind].size());
        }
    }
    return plan;
}

/// The plans of the groups in use (keyed by address: cleared whenever the models are rebuilt).
std::map<const detail::GroupModel*, std::unique_ptr<PosePlan>> g_pose_plans;
const detail::GroupModel* g_last_model = nullptr;
const PosePlan* g_last_plan = nullptr;
const PosePlan& pose_plan(const detail::GroupModel& m) {
    if (g_last_model != &m) {
        auto& plan = g_pose_plans[&m];
        if (!plan) plan = make_pose_plan(m);
        g_last_model = &m;
        g_last_plan = plan.get();
    }
    return *g_last_plan;
}
void clear_pose_plans() {
    g_pose_plans.clear();
    g_last_model = nullptr;
    g_last_plan = nullptr;
}

/// --float-dofs 1: x = U y in float32 (pose_dofs_portable, the same bits as pose_dofs_avx2)
/// everywhere: in the encoder's bound check, the check of every frame and the timings (closed loop:
/// the bound holds for what is decoded).
bool g_float_dofs = false;

/// How y becomes a local pose in the timings: the library's ChannelWriter::write_local after the
/// portable product, or runtime_pose.hpp's kernels (portable or AVX2 build).
enum class PosePath { library, portable, avx2 };
std::size_t g_pose_fallbacks = 0;  ///< poses the kernels left to the library's scalar path

/// y -> the frame's dofs: pose_of, or with an identity dof basis (--dof identity) the copy of y
/// instead of the product (x = y: the same values, up to the sign of a zero).
void dofs_of_y(const detail::GroupModel& m, const detail::ClipEntry& e, const double* y, detail::WindowScratch& s, double* p,
               const PosePlan* plan = nullptr) {
    static thread_local const detail::GroupModel* known = nullptr;
    static thread_local bool identity = false;
    if (known != &m) {
        known = &m;
        identity = m.dof_basis.isIdentity(0.0);
    }
    if (g_float_dofs) {
        detail::pose_dofs_portable((plan ? *plan : pose_plan(m)).skeletons[e.skeleton].kernel, y, p);
        return;
    }
    if (!identity) {
        m.pose_of(e, y, static_cast<int>(m.active.size()), s, p);
        return;
    }
    std::copy(y, y + m.active.size(), s.x.data());
    std::copy(m.constant.begin(), m.constant.end(), p);
    m.unweight(s.x.data(), m.skeletons[e.skeleton], p);
}

/// Frame y's local pose by `path` (p: the frame's dofs, written). The kernels' paths form the motion
/// root as write_local does and the other joints by the kernels; a pose they leave (see
/// pose_rotations_portable) is decoded by the library's write_local from the same dofs.
void local_pose_of_y(const detail::GroupModel& m, const detail::ClipEntry& e, const double* y, detail::WindowScratch& s,
                     double* p, LocalPose& out, PosePath path, const PosePlan* plan = nullptr) {
    if (path == PosePath::library || !g_float_dofs) {
        dofs_of_y(m, e, y, s, p, plan);
        m.local_of(e, p, out);
        return;
    }
    const PosePlan::Skeleton& sk = (plan ? *plan : pose_plan(m)).skeletons[e.skeleton];
    if (path == PosePath::avx2) detail::pose_dofs_avx2(sk.kernel, y, p);
    else detail::pose_dofs_portable(sk.kernel, y, p);
    const detail::ChannelWriter& writer = m.skeletons[e.skeleton].writer;
    const auto v = writer.local_view();  // rest transforms
    const std::size_t n = writer.size();
    out.rotations.resize(n);
    out.translations.resize(n);
    std::memcpy(static_cast<void*>(out.rotations.data()), v.rest_rotations->data(), n * sizeof(Quat));
    std::memcpy(static_cast<void*>(out.translations.data()), v.rest_translations->data(), n * sizeof(Vec3));
    static_assert(sizeof(Quat) == 4 * sizeof(double) && sizeof(Vec3) == 3 * sizeof(double), "Quat: x, y, z, w; Vec3: x, y, z");
    double placement[7];
    std::memcpy(placement, e.placement.heading.coeffs().data(), 4 * sizeof(double));
    std::memcpy(placement + 4, e.placement.translation.data(), 3 * sizeof(double));
    auto* rotations = reinterpret_cast<double*>(out.rotations.data());
    auto* translations = reinterpret_cast<double*>(out.translations.data());
    bool ok = path == PosePath::avx2 ? detail::pose_root_avx2(sk.kernel, placement, p, rotations, translations)
                                     : detail::pose_root_portable(sk.kernel, placement, p, rotations, translations);
    ok = (path == PosePath::avx2 ? detail::pose_rotations_avx2(sk.kernel, p, rotations) : detail::pose_rotations_portable(sk.kernel, p, rotations)) &&
         ok;
    if (!ok || sk.root_projects) {
        ++g_pose_fallbacks;
        m.local_of(e, p, out);
        return;
    }
    for (std::size_t c = 0; c < m.extra_columns.size(); ++c)
        writer.set_position(m.extra_columns[c], p[static_cast<std::size_t>(m.pose_dofs) + c], out);
}

/// The hierarchical candidate on one group (clips in group order, m parsed from format 2's bytes).
HierResult run_hier(const detail::GroupModel& m, const std::vector<const Clip*>& clips, double E, int W, int key_offset,
                    StaticCost& cost, StaticCost& widths, double rounding) {
    HierResult r;
    const auto Da = static_cast<Eigen::Index>(m.active.size());
    const MatX Uinv = m.dof_basis.partialPivLu().inverse();
    int levels = 0;
    while ((1 << levels) < W) ++levels;
    detail::WindowScratch s;
    m.prepare(s);
    std::vector<double> row, p(static_cast<std::size_t>(m.dofs));
    GlobalPose pose;
    int k_prev = std::clamp(static_cast<int>(std::lround(12.0 * (std::log2(E) + 14.0))), 0, 254);
    int kk_prev = k_prev;
    for (std::size_t i = 0; i < clips.size(); ++i) {
        const Clip& clip = *clips[i];
        const detail::ClipEntry& e = m.clips[i];
        const Skeleton& sk = *m.skeletons[e.skeleton].skeleton;
        row.resize(sk.channel_count());
        const MatX x = m.weighted_active(clip, m.skeletons[e.skeleton], e.canonical);
        const MatX source = joint_positions(clip);
        const auto F = x.cols();
        const auto J = static_cast<Eigen::Index>(sk.size());
        const Eigen::Index nw = (F - 1 + W - 1) / W;
        const Eigen::Index T = nw * W + 1;
        MatX y(Da, T), yh(Da, T);
        for (Eigen::Index t = 0; t < T; ++t) y.col(t) = Uinv * x.col(std::min(t, F - 1));
        // Distance check of reconstructed frame t (a real frame).
        double worst = 0.0;
        auto frame_ok = [&](Eigen::Index t, const double* yt) {
            dofs_of_y(m, e, yt, s, p.data());
            m.row_of(e, p.data(), row.data());
            forward_kinematics(sk, row.data(), pose);
            for (Eigen::Index j = 0; j < J; ++j) {
                const double d = (pose.positions[static_cast<std::size_t>(j)] - source.block<3, 1>(3 * j, t)).norm();
                if (!(d <= E)) return false;
                worst = std::max(worst, d);
            }
            return true;
        };
        // Keys.
        std::vector<std::vector<std::int32_t>> key_q(static_cast<std::size_t>(nw + 1));
        VecX tmp(Da);
        for (Eigen::Index w = 0; w <= nw; ++w) {
            const Eigen::Index t = w * W;
            const Eigen::Index real = std::min(t, F - 1);
            auto passes = [&](int k) {
                const double step = detail::step_of(k), inv = 1.0 / step;
                for (Eigen::Index d = 0; d < Da; ++d) tmp[d] = quantize(y(d, t), inv, rounding) * step;
                return frame_ok(real, tmp.data());
            };
            int k = coarsest(kk_prev, passes);
            if (k < 0) throw Error("key fails even at the finest step");
            kk_prev = k;
            // A finer step for the key (better predictions); the bound is not monotone in the step,
            // so the key is checked again and made finer until it holds.
            auto& q = key_q[static_cast<std::size_t>(w)];
            q.resize(static_cast<std::size_t>(Da));
            for (k = std::max(0, k - key_offset);; --k) {
                if (k < 0) throw Error("key fails even at the finest step");
                const double step = detail::step_of(k), inv = 1.0 / step;
                for (Eigen::Index d = 0; d < Da; ++d) {
                    q[static_cast<std::size_t>(d)] = quantize(y(d, t), inv, rounding);
                    yh(d, t) = q[static_cast<std::size_t>(d)] * step;
                }
                if (frame_ok(real, yh.col(t).data())) break;
            }
            r.max_error = std::max(r.max_error, worst);
            if (w == 0) r.clip_first.push_back(r.entries.size());
            r.entries.push_back({k, q, -1, {}});
            ++r.keys;
            r.static_bits += 8;  // step byte
            for (Eigen::Index d = 0; d < Da; ++d) cost.add(0, static_cast<int>(d), q[static_cast<std::size_t>(d)]);
        }
        // Windows.
        std::vector<std::int32_t> q(static_cast<std::size_t>(Da * W));
        for (Eigen::Index w = 0; w < nw; ++w) {
            const Eigen::Index t0 = w * W;
            auto encode = [&](int k) {
                const double step = detail::step_of(k), inv = 1.0 / step;
                for (int j = 1; j <= levels; ++j) {
                    const int h = W >> j;
                    for (int t = h; t < W; t += 2 * h) {
                        for (Eigen::Index d = 0; d < Da; ++d) {
                            const double pred = 0.5 * (yh(d, t0 + t - h) + yh(d, t0 + t + h));
                            const std::int32_t v = quantize(y(d, t0 + t) - pred, inv, rounding);
                            q[static_cast<std::size_t>(t * Da + d)] = v;
                            yh(d, t0 + t) = v ? pred + v * step : pred;  // the decoder's form: zeros add nothing
                        }
                    }
                }
            };
            auto passes = [&](int k) {
                encode(k);
                for (int t = 1; t < W && t0 + t < F; ++t)
                    if (!frame_ok(t0 + t, yh.col(t0 + t).data())) return false;
                return true;
            };
            worst = 0.0;
            const int k = coarsest(k_prev, passes);
            if (k < 0) throw Error("window fails even at the finest step");
            k_prev = k;
            worst = 0.0;
            passes(k);
            r.max_error = std::max(r.max_error, worst);
            ++r.windows;
            {
                auto& wc = r.window_columns.emplace_back();
                wc.push_back({0, key_q[static_cast<std::size_t>(w)]});
                std::vector<std::pair<int, int>> order;  // (t, level) in tree order
                auto tree = [&](auto&& self, int lo, int hi, int level) -> void {
                    if (hi - lo < 2) return;
                    const int mid = (lo + hi) / 2;
                    order.push_back({mid, level});
                    self(self, lo, mid, level + 1);
                    self(self, mid, hi, level + 1);
                };
                tree(tree, 0, W, 1);
                auto& entry = r.entries[r.clip_first.back() + static_cast<std::size_t>(w)];
                entry.step = k;
                for (const auto& [t, level] : order) {
                    wc.push_back({level, std::vector<std::int32_t>(q.begin() + t * Da, q.begin() + (t + 1) * Da)});
                    entry.columns.push_back(wc.back().second);
                }
            }
            r.static_bits += 8;
            r.fixed_bits += 8;
            for (int j = 1; j <= levels; ++j) {
                const int h = W >> j;
                const int columns = W / (2 * h);  // odd multiples of h below W
                for (Eigen::Index d = 0; d < Da; ++d) {
                    std::int32_t largest = 0;
                    for (int t = h; t < W; t += 2 * h) {
                        const std::int32_t v = q[static_cast<std::size_t>(t * Da + d)];
                        cost.add(j, static_cast<int>(d), v);
                        largest = std::max(largest, std::abs(v));
                        if (v) ++r.nonzero;
                    }
                    const int width = largest ? bit_length(static_cast<std::uint32_t>(largest)) + 1 : 0;
                    widths.add(j, static_cast<int>(d), width);
                    r.fixed_bits += static_cast<double>(width) * columns;
                }
            }
        }
        // Keys at fixed widths: one width per key and row (coded in context (0, row)).
        for (const auto& kq : key_q) {
            for (Eigen::Index d = 0; d < Da; ++d) {
                const std::int32_t v = std::abs(kq[static_cast<std::size_t>(d)]);
                const int width = v ? bit_length(static_cast<std::uint32_t>(v)) + 1 : 0;
                widths.add(0, static_cast<int>(d), width);
                r.fixed_bits += width + 8.0 / static_cast<double>(Da);
            }
        }
    }
    return r;
}

/// Huffman code lengths of a histogram (symbol -> count); plain Huffman (no length limit).
std::map<int, int> huffman_lengths(const std::map<int, std::size_t>& hist) {
    std::map<int, int> out;
    if (hist.size() == 1) {
        out[hist.begin()->first] = 1;
        return out;
    }
    // (count, node); leaves 0..n-1, internal nodes after; parent links.
    std::vector<int> symbols;
    std::vector<std::size_t> weight;
    for (const auto& [sym, n] : hist) {
        symbols.push_back(sym);
        weight.push_back(n);
    }
    const std::size_t n = symbols.size();
    std::vector<int> parent(2 * n, -1);
    using Item = std::pair<std::size_t, int>;
    std::vector<Item> heap;
    for (std::size_t i = 0; i < n; ++i) heap.push_back({weight[i], static_cast<int>(i)});
    auto cmp = [](const Item& a, const Item& b) { return a.first > b.first; };
    std::make_heap(heap.begin(), heap.end(), cmp);
    int next = static_cast<int>(n);
    while (heap.size() > 1) {
        std::pop_heap(heap.begin(), heap.end(), cmp);
        const Item a = heap.back();
        heap.pop_back();
        std::pop_heap(heap.begin(), heap.end(), cmp);
        const Item b = heap.back();
        heap.pop_back();
        parent[static_cast<std::size_t>(a.second)] = next;
        parent[static_cast<std::size_t>(b.second)] = next;
        heap.push_back({a.first + b.first, next++});
        std::push_heap(heap.begin(), heap.end(), cmp);
    }
    for (std::size_t i = 0; i < n; ++i) {
        int depth = 0;
        for (int v = static_cast<int>(i); parent[static_cast<std::size_t>(v)] >= 0; v = parent[static_cast<std::size_t>(v)]) ++depth;
        out[symbols[i]] = depth;
    }
    return out;
}

/// Realistic bytes of the hierarchical candidate with static Huffman codes: per column the number
/// of rows up to its last nonzero one (context: level), then each row's value (context: level, row;
/// |q| > 15 escapes with Elias-gamma bits); tables at 5 bits per used symbol; per window a
/// directory of the left-subtree bit sizes of the column tree (per level a 5-bit width, then each
/// size at that width), a 3-byte window offset and the step byte; each key a step byte.
struct HuffmanFigures {
    double bits = 0.0, directory_bits = 0.0, table_bits = 0.0, symbols_per_frame = 0.0;
};
/// A column as (context, symbol, extra raw bits) triples. mode 0: the row count, then each row's
/// value (|q| <= 7 itself, else its bit length as a symbol with the sign, then the bits below the top
/// one); mode 1: JPEG-like (zero run 0..15 or 16 = sixteen zeros, bit length of the value) pairs as one
/// symbol, sign and bits below the top one raw, an end symbol after the last nonzero (context: level
/// and the row bucket row/8).
struct Coded {
    int c1, c2, sym, extra;
};
void code_column(int level, const std::vector<std::int32_t>& v, int mode, std::vector<Coded>& out) {
    int n = static_cast<int>(v.size());
    while (n > 0 && v[static_cast<std::size_t>(n - 1)] == 0) --n;
    if (mode == 0) {
        out.push_back({level, -1, n, 0});
        for (int d = 0; d < n; ++d) {
            const std::int32_t q = v[static_cast<std::size_t>(d)];
            if (q >= -7 && q <= 7) {
                out.push_back({level, d, q, 0});
            } else {
                const int c = bit_length(static_cast<std::uint32_t>(std::abs(q)));
                out.push_back({level, d, q > 0 ? 100 + c : -100 - c, c - 1});
            }
        }
        return;
    }
    int run = 0;
    for (int d = 0; d < n; ++d) {
        const std::int32_t q = v[static_cast<std::size_t>(d)];
        if (q == 0) {
            ++run;
            continue;
        }
        while (run >= 16) {
            out.push_back({level, (d - run) / 8, 16 * 32, 0});
            run -= 16;
        }
        const int c = bit_length(static_cast<std::uint32_t>(std::abs(q)));
        out.push_back({level, d / 8, run * 32 + c, c});  // c - 1 magnitude bits + sign
        run = 0;
    }
    if (n < static_cast<int>(v.size())) out.push_back({level, n / 8, -1, 0});  // end of column
}

HuffmanFigures huffman_bits(const HierResult& r, int W, int mode) {
    std::map<std::pair<int, int>, std::map<int, std::size_t>> hist;
    std::vector<Coded> coded;
    for (const auto& wc : r.window_columns)
        for (const auto& [level, v] : wc) {
            coded.clear();
            code_column(level, v, mode, coded);
            for (const Coded& c : coded) ++hist[{c.c1, c.c2}][c.sym];
        }
    std::map<std::pair<int, int>, std::map<int, int>> lengths;
    HuffmanFigures f;
    for (const auto& [ctx, h] : hist) {
        lengths[ctx] = huffman_lengths(h);
        f.table_bits += 5.0 * static_cast<double>(h.size()) + 8.0;
    }
    double symbols = 0.0, frames = 0.0;
    int levels = 0;
    while ((1 << levels) < W) ++levels;
    for (const auto& wc : r.window_columns) {
        std::vector<double> column_bits;
        std::vector<double> column_symbols;
        for (const auto& [level, v] : wc) {
            coded.clear();
            code_column(level, v, mode, coded);
            double b = 0.0;
            for (const Coded& c : coded) b += lengths[{c.c1, c.c2}][c.sym] + c.extra;
            column_bits.push_back(b);
            column_symbols.push_back(static_cast<double>(coded.size()));
            f.bits += b;
        }
        // Directory: columns after the key are in tree order; a node's left subtree is the next
        // 2^(levels - level) - 1 columns.
        std::vector<double> width(static_cast<std::size_t>(levels + 1), 0.0);
        std::vector<int> count(static_cast<std::size_t>(levels + 1), 0);
        for (std::size_t i = 1; i < wc.size(); ++i) {
            const int level = wc[i].first;
            if (level >= levels) continue;  // leaves' parents have no subtree to skip
            const std::size_t span = (std::size_t{1} << (levels - level)) - 1;
            double size = 0.0;
            for (std::size_t k = i + 1; k < i + 1 + span && k < wc.size(); ++k) size += column_bits[k];
            width[static_cast<std::size_t>(level)] = std::max(width[static_cast<std::size_t>(level)],
                                                             static_cast<double>(bit_length(static_cast<std::uint32_t>(size))));
            ++count[static_cast<std::size_t>(level)];
        }
        for (int level = 1; level < levels; ++level)
            f.directory_bits += 5.0 + width[static_cast<std::size_t>(level)] * count[static_cast<std::size_t>(level)];
        f.directory_bits += 24.0 + 8.0;
        // Symbols a frame decodes, averaged over the window's frames: its two keys and its path.
        for (int t = 0; t < W; ++t) {
            // Key symbols: this window's key (next window's is about the same size).
            double s = 2.0 * column_symbols[0];
            std::size_t i = 1;
            int lo = 0, hi = W, level = 1;
            while (hi - lo >= 2 && t != lo) {
                const int mid = (lo + hi) / 2;
                s += column_symbols[i];
                if (t == mid) break;
                const std::size_t span = (std::size_t{1} << (levels - level)) - 1;
                if (t < mid) { hi = mid; i += 1; }
                else { lo = mid; i += 1 + span; }
                ++level;
            }
            symbols += s;
            frames += 1;
        }
    }
    f.bits += f.table_bits + f.directory_bits + 8.0 * static_cast<double>(r.keys);
    f.symbols_per_frame = frames > 0 ? symbols / frames : 0.0;
    return f;
}

/// Static estimate of format 2's own coefficients (window step as stored, rounding 0.4, no trim).
double format2_static_bits(const detail::GroupModel& m, const std::vector<const Clip*>& clips) {
    StaticCost cost;
    const auto Da = static_cast<Eigen::Index>(m.active.size());
    const int W = m.window;
    const MatX Uinv = m.dof_basis.partialPivLu().inverse();
    const MatX Vinv_t = m.time_basis.partialPivLu().inverse().transpose();
    double bits = 0.0;
    for (std::size_t i = 0; i < clips.size(); ++i) {
        const detail::ClipEntry& e = m.clips[i];
        const MatX x = m.weighted_active(*clips[i], m.skeletons[e.skeleton], e.canonical);
        const auto F = x.cols();
        const Eigen::Index nw = (F + W - 1) / W;
        for (Eigen::Index w = 0; w < nw; ++w) {
            const auto& we = m.windows[e.first_window + static_cast<std::uint64_t>(w)];
            bits += 8;
            if (we.step == detail::kRawStep) continue;
            MatX xw(Da, W);
            for (int t = 0; t < W; ++t) xw.col(t) = x.col(std::min<Eigen::Index>(w * W + t, F - 1));
            const MatX g = Uinv * xw * Vinv_t;
            const double inv = 1.0 / detail::step_of(we.step);
            for (Eigen::Index d = 0; d < Da; ++d)
                for (int k = 0; k < W; ++k) cost.add(k, static_cast<int>(d), quantize(g(d, k), inv, 0.4));
        }
    }
    return bits + cost.bits();
}

// ---- A real bitstream of the hierarchical candidate, to time a cold pose from the stored bytes ----

/// MSB-first bit writer.
struct BitWriter {
    std::vector<std::uint8_t> bytes;
    std::uint64_t acc = 0;
    int n = 0;
    void put(std::uint32_t value, int bits) {
        if (bits == 0) return;
        acc = (acc << bits) | (static_cast<std::uint64_t>(value) & ((std::uint64_t{1} << bits) - 1));
        n += bits;
        while (n >= 8) {
            bytes.push_back(static_cast<std::uint8_t>(acc >> (n - 8)));
            n -= 8;
        }
        acc &= (std::uint64_t{1} << n) - 1;
    }
    void align() {
        if (n > 0) put(0, 8 - n);
    }
    std::size_t bits() const { return bytes.size() * 8 + static_cast<std::size_t>(n); }
};

/// MSB-first bit reader over a buffer with at least 8 bytes of slack after the data.
struct BitReader {
    const std::uint8_t* data;
    std::size_t pos;  // bits
    std::uint64_t window() const {
        std::uint64_t v;
        std::memcpy(&v, data + (pos >> 3), 8);
        return __builtin_bswap64(v) << (pos & 7);
    }
    std::uint32_t get(int bits) {
        if (bits == 0) return 0;
        const auto v = static_cast<std::uint32_t>(window() >> (64 - bits));
        pos += static_cast<std::size_t>(bits);
        return v;
    }
};

/// The decoder's bit buffer (Giesen's branch-free refill): buf holds the next bits MSB-first, at
/// least 56 of them after refill(); the loads do not depend on the bits decoded.
struct FastBits {
    const std::uint8_t* next = nullptr;
    std::uint64_t buf = 0;
    int avail = 0;  // bits in buf
    std::size_t consumed = 0;
    FastBits() = default;
    FastBits(const std::uint8_t* data, std::size_t bit) : next(data + (bit >> 3)) {
        refill();
        drop(static_cast<int>(bit & 7));
        consumed = bit;
    }
    void refill() {
        std::uint64_t v;
        std::memcpy(&v, next, 8);
        buf |= __builtin_bswap64(v) >> avail;
        next += (63 - avail) >> 3;
        avail |= 56;
    }
    void drop(int n) {
        buf <<= n;
        avail -= n;
        consumed += static_cast<std::size_t>(n);
    }
};

constexpr int kCodeArray = 16;
/// Code lengths are limited to this, and the decode tables have 2^this entries (--code-bits).
int kMaxCode = 11;
int& kFastBits = kMaxCode;
constexpr int kEnd = -1;        // end of column
constexpr int kZeroRun = 16 * 32;  // sixteen zeros

/// A canonical Huffman code of one context: lengths limited to kMaxCode, a kFastBits lookup table
/// and the canonical tables for longer codes.
struct HuffmanCode {
    std::map<int, int> length;
    std::map<int, std::uint32_t> code;
    struct Fast {
        std::int16_t symbol = 0;
        std::uint8_t length = 0;  // 0: longer than kFastBits
    };
    std::vector<Fast> fast;
    /// The same table packed for the decoder's loop: bits 0-3 length (0: slow path), 4-8 run,
    /// 9-13 bit length of the value, 14-15 kind (0 value, 1 sixteen zeros, 2 end).
    std::vector<std::uint16_t> packed;
    std::vector<int> sorted;  // symbols in canonical order
    std::array<std::uint32_t, kCodeArray + 2> first{}, count{}, index{};

    void build(const std::map<int, std::size_t>& hist) {
        length = huffman_lengths(hist);
        // Limit lengths: clamp, then lengthen the rarest shorter codes until Kraft's sum is <= 1.
        for (auto& [s, l] : length) l = std::min(l, kMaxCode);
        auto kraft = [&] {
            double k = 0.0;
            for (const auto& [s, l] : length) k += std::ldexp(1.0, -l);
            return k;
        };
        std::vector<std::pair<std::size_t, int>> by_count;
        for (const auto& [s, n] : hist) by_count.push_back({n, s});
        std::sort(by_count.begin(), by_count.end());
        while (kraft() > 1.0 + 1e-12)
            for (const auto& [n, s] : by_count)
                if (length[s] < kMaxCode) {
                    ++length[s];
                    break;
                }
        // Canonical codes: by (length, symbol).
        std::vector<std::pair<int, int>> order;
        for (const auto& [s, l] : length) order.push_back({l, s});
        std::sort(order.begin(), order.end());
        std::uint32_t c = 0;
        int previous = order.empty() ? 0 : order.front().first;
        count.fill(0);
        for (std::size_t i = 0; i < order.size(); ++i) {
            const auto [l, s] = order[i];
            c <<= (l - previous);
            previous = l;
            code[s] = c;
            if (count[static_cast<std::size_t>(l)] == 0) {
                first[static_cast<std::size_t>(l)] = c;
                index[static_cast<std::size_t>(l)] = static_cast<std::uint32_t>(i);
            }
            ++count[static_cast<std::size_t>(l)];
            sorted.push_back(s);
            ++c;
        }
        fast.assign(std::size_t{1} << kFastBits, Fast{});
        for (const auto& [s, l] : length) {
            if (l > kFastBits) continue;
            const std::uint32_t base = code[s] << (kFastBits - l);
            for (std::uint32_t k = 0; k < (1u << (kFastBits - l)); ++k) fast[base + k] = {static_cast<std::int16_t>(s), static_cast<std::uint8_t>(l)};
        }
        packed.assign(fast.size(), 0);
        for (std::size_t i = 0; i < fast.size(); ++i) {
            const Fast f = fast[i];
            if (!f.length) continue;
            const int kind = f.symbol == kEnd ? 2 : f.symbol == kZeroRun ? 1 : 0;
            const int run = kind ? 0 : f.symbol >> 5, cat = kind ? 0 : f.symbol & 31;
            packed[i] = static_cast<std::uint16_t>(f.length | run << 4 | cat << 9 | kind << 14);
        }
    }
    void write(BitWriter& out, int symbol) const { out.put(code.at(symbol), length.at(symbol)); }
    int read(BitReader& in) const {
        const std::uint64_t w = in.window();
        const Fast& f = fast[static_cast<std::size_t>(w >> (64 - kFastBits))];
        if (f.length) {
            in.pos += f.length;
            return f.symbol;
        }
        for (int l = kFastBits + 1; l <= kMaxCode; ++l) {
            const auto v = static_cast<std::uint32_t>(w >> (64 - l));
            const std::uint32_t n = count[static_cast<std::size_t>(l)];
            if (n && v - first[static_cast<std::size_t>(l)] < n) {
                in.pos += static_cast<std::size_t>(l);
                return sorted[index[static_cast<std::size_t>(l)] + (v - first[static_cast<std::size_t>(l)])];
            }
        }
        throw Error("bad code");
    }
};

/// The runtime candidate of one group: window byte offsets, each window's bits, the codes.
struct RuntimeGroup {
    int W = 0, levels = 0, Da = 0, buckets = 0;
    std::vector<HuffmanCode> codes;      // (level, bucket) -> code; level 0 = keys
    std::vector<std::uint32_t> offsets;  // per entry, byte offset
    std::vector<std::size_t> clip_first;
    std::vector<std::uint8_t> bytes;     // entries' bits, 8 bytes of slack at the end
    std::size_t table_bits = 0, directory_bits = 0;
    bool prefetch = true;
    /// Every context's decode table, one after the other (2^kFastBits entries each): bits 0-3 the
    /// code length, 4-8 the zero run (16: sixteen zeros), 9-13 the value's bit length (0: none), 14 end.
    std::vector<std::uint16_t> flat;
    void build_flat() {
        const std::size_t n = std::size_t{1} << kFastBits;
        flat.assign(codes.size() * n, 0);
        for (std::size_t c = 0; c < codes.size(); ++c) {
            if (codes[c].fast.empty()) continue;
            for (std::size_t i = 0; i < n; ++i) {
                const auto f = codes[c].fast[i];
                if (!f.length) continue;
                const int end = f.symbol == kEnd, zeros = f.symbol == kZeroRun;
                const int run = end ? 0 : zeros ? 16 : f.symbol >> 5, cat = end || zeros ? 0 : f.symbol & 31;
                flat[c * n + i] = static_cast<std::uint16_t>(f.length | run << 4 | cat << 9 | end << 14);
            }
        }
    }

    const HuffmanCode& code(int level, int row) const { return codes[static_cast<std::size_t>(level * buckets + row / 8)]; }

    /// Column symbols (run/size with end), as code_column mode 1 but contexts by the run's start.
    void symbols(int level, const std::vector<std::int32_t>& v, std::vector<Coded>& out) const {
        int n = static_cast<int>(v.size());
        while (n > 0 && v[static_cast<std::size_t>(n - 1)] == 0) --n;
        int start = 0;
        for (int d = 0; d < n; ++d) {
            const std::int32_t q = v[static_cast<std::size_t>(d)];
            if (q == 0) continue;
            while (d - start >= 16) {
                out.push_back({level, start, kZeroRun, 0});
                start += 16;
            }
            const int c = bit_length(static_cast<std::uint32_t>(std::abs(q)));
            out.push_back({level, start, (d - start) * 32 + c, q});
            start = d + 1;
        }
        if (n < static_cast<int>(v.size())) out.push_back({level, start, kEnd, 0});
    }
    void write_column(BitWriter& out, int level, const std::vector<std::int32_t>& v) const {
        std::vector<Coded> coded;
        symbols(level, v, coded);
        for (const Coded& c : coded) {
            code(c.c1, c.c2).write(out, c.sym);
            if (c.sym == kEnd || c.sym == kZeroRun) continue;
            const int cat = c.sym & 31;
            const std::int32_t q = c.extra;
            out.put(q < 0 ? 1u : 0u, 1);
            out.put(static_cast<std::uint32_t>(std::abs(q)), cat - 1);
        }
    }
    /// y[d] = mean of a[d] and b[d] (keys: a == nullptr, 0), plus q[d] * step where q[d] is nonzero.
    void read_column(BitReader& in, int level, const double* a, const double* b, double step, double* y) const {
        if (a) {
            for (int d = 0; d < Da; ++d) y[d] = 0.5 * (a[d] + b[d]);
        } else {
            std::fill(y, y + Da, 0.0);
        }
        const int B = kFastBits;
        const std::uint16_t* table = flat.data() + (static_cast<std::size_t>(level * buckets) << B);
        FastBits bits(in.data, in.pos);
        int d = 0;
        while (d < Da) {
            bits.refill();
            const std::uint16_t e = table[(static_cast<std::size_t>(d >> 3) << B) | static_cast<std::size_t>(bits.buf >> (64 - B))];
            if (e & (1u << 14)) {
                bits.drop(e & 15);
                break;
            }
            const int len = e & 15, cat = (e >> 9) & 31;
            d += (e >> 4) & 31;
            const auto v = static_cast<std::uint32_t>(((bits.buf << len) >> 1) >> (63 - cat));
            bits.drop(len + cat);
            if (cat) {
                const auto mag = static_cast<std::int32_t>((1u << (cat - 1)) | (v & ((1u << (cat - 1)) - 1)));
                y[d] = y[d] + ((v >> (cat - 1)) ? -mag : mag) * step;
                ++d;
            }
        }
        in.pos = bits.consumed;
    }
};

/// Column levels and frames in tree order for windows of W = 2^levels frames.
void tree_order(int W, std::vector<int>& level, std::vector<int>& frame) {
    auto tree = [&](auto&& self, int lo, int hi, int l) -> void {
        if (hi - lo < 2) return;
        const int mid = (lo + hi) / 2;
        level.push_back(l);
        frame.push_back(mid);
        self(self, lo, mid, l + 1);
        self(self, mid, hi, l + 1);
    };
    tree(tree, 0, W, 1);
}

/// From the window's step byte on: the step, the directory (per level a 5-bit width, then each
/// internal node's left-subtree size in bits at that width) and the columns in tree order (levels tl).
/// Returns the directory's bits.
/// write_column(out, level, values) codes one column (variant 1: run/size codes; variant 9: quads).
/// widths: the directory's width per level given (not written: variant 9 keeps them per clip); with
/// need (per level) instead, only each level's largest width into need[l] (nothing written).
/// stored: the directory holds levels 1..stored (default: every level with a left subtree, levels - 1).
template <class WriteColumn>
std::size_t write_window_by(int levels, BitWriter& out, const HierResult::Entry& e, const std::vector<int>& tl, WriteColumn write_column,
                            const int* widths = nullptr, int* need = nullptr, int stored = -1) {
    if (stored < 0) stored = levels - 1;
    if (!need) out.put(static_cast<std::uint32_t>(e.step), 8);
    std::vector<std::size_t> size;
    for (std::size_t i = 0; i < e.columns.size(); ++i) {
        BitWriter scratch;
        write_column(scratch, tl[i], e.columns[i]);
        size.push_back(scratch.bits());
    }
    std::vector<std::vector<std::size_t>> left(static_cast<std::size_t>(levels));
    for (std::size_t i = 0; i < e.columns.size(); ++i) {
        const int l = tl[i];
        if (l >= levels) continue;
        const std::size_t span = (std::size_t{1} << (levels - l)) - 1;
        std::size_t s = 0;
        for (std::size_t k = i + 1; k <= i + span; ++k) s += size[k];
        left[static_cast<std::size_t>(l)].push_back(s);
    }
    const std::size_t before = out.bits();
    std::vector<int> width(static_cast<std::size_t>(levels), 0);
    for (int l = 1; l <= stored; ++l) {
        for (std::size_t s : left[static_cast<std::size_t>(l)])
            width[static_cast<std::size_t>(l)] = std::max(width[static_cast<std::size_t>(l)], bit_length(static_cast<std::uint32_t>(s)));
        if (need) need[l] = std::max(need[l], width[static_cast<std::size_t>(l)]);
        if (widths) width[static_cast<std::size_t>(l)] = widths[l];
        else if (!need) out.put(static_cast<std::uint32_t>(width[static_cast<std::size_t>(l)]), 5);
    }
    if (need) return 0;
    for (int l = 1; l <= stored; ++l)
        for (std::size_t s : left[static_cast<std::size_t>(l)]) out.put(static_cast<std::uint32_t>(s), width[static_cast<std::size_t>(l)]);
    const std::size_t directory = out.bits() - before;
    for (std::size_t i = 0; i < e.columns.size(); ++i) write_column(out, tl[i], e.columns[i]);
    return directory;
}

std::size_t write_window(const RuntimeGroup& g, BitWriter& out, const HierResult::Entry& e, const std::vector<int>& tl) {
    return write_window_by(g.levels, out, e, tl, [&](BitWriter& o, int level, const std::vector<std::int32_t>& v) { g.write_column(o, level, v); });
}

RuntimeGroup build_runtime(const HierResult& r, int W, int Da) {
    RuntimeGroup g;
    g.W = W;
    g.Da = Da;
    while ((1 << g.levels) < W) ++g.levels;
    g.buckets = (Da + 7) / 8;
    g.clip_first = r.clip_first;
    std::vector<int> tl, tf;
    tree_order(W, tl, tf);
    std::vector<std::map<int, std::size_t>> hist(static_cast<std::size_t>((g.levels + 1) * g.buckets));
    std::vector<Coded> coded;
    auto count = [&](int level, const std::vector<std::int32_t>& v) {
        coded.clear();
        g.symbols(level, v, coded);
        for (const Coded& c : coded) ++hist[static_cast<std::size_t>(c.c1 * g.buckets + c.c2 / 8)][c.sym];
    };
    for (const auto& e : r.entries) {
        count(0, e.key);
        for (std::size_t i = 0; i < e.columns.size(); ++i) count(tl[i], e.columns[i]);
    }
    g.codes.resize(hist.size());
    for (std::size_t c = 0; c < hist.size(); ++c) {
        if (hist[c].empty()) continue;
        g.codes[c].build(hist[c]);
        g.table_bits += 8 + 5 * hist[c].size();
    }
    BitWriter out;
    for (const auto& e : r.entries) {
        out.align();
        g.offsets.push_back(static_cast<std::uint32_t>(out.bytes.size()));
        out.put(static_cast<std::uint32_t>(e.key_step), 8);
        g.write_column(out, 0, e.key);
        if (e.step < 0) continue;
        g.directory_bits += write_window(g, out, e, tl);
    }
    out.align();
    g.build_flat();
    g.bytes = std::move(out.bytes);
    g.bytes.resize(g.bytes.size() + 8, 0);
    return g;
}

/// A window's directory at bit pos (per level a width, then the left-subtree sizes): into skip[l] the
/// size of the left subtree frame t's path skips at level l; returns the bit after the directory.
/// widths: the widths per level when the window does not hold them (variant 9: per clip).
/// stored: the directory holds levels 1..stored (default levels - 1).
std::size_t read_directory(const std::uint8_t* data, std::size_t pos, int levels, int t, std::size_t* skip, const std::uint8_t* widths = nullptr,
                           int stored = -1) {
    if (stored < 0) stored = levels - 1;
    BitReader in{data, pos};
    int width[8] = {0};
    for (int l = 1; l <= stored; ++l) width[l] = widths ? widths[l] : static_cast<int>(in.get(5));
    // Level l's sizes start after the earlier levels' (2^(l-1) each).
    std::size_t at = in.pos;
    for (int l = 1; l <= stored; ++l) {
        const std::size_t node = static_cast<std::size_t>(t) >> (levels - l + 1);
        BitReader s{data, at + node * static_cast<std::size_t>(width[l])};
        skip[l] = s.get(width[l]);
        at += (std::size_t{1} << (l - 1)) * static_cast<std::size_t>(width[l]);
    }
    return at;
}

/// A frame of a clip into y (Da values), from the bytes alone; a, b, c: Da values of scratch each.
void runtime_frame(const RuntimeGroup& g, std::size_t clip, std::size_t frame, double* y, double* a, double* b,
                   double* c) {
    const std::size_t w = frame / static_cast<std::size_t>(g.W);
    const int t = static_cast<int>(frame % static_cast<std::size_t>(g.W));
    const std::size_t entry = g.clip_first[clip] + w;
    if (g.prefetch) {
        // The window's bytes and the next key's: one pass of prefetches before the first decode, so
        // that the misses overlap instead of following one another.
        const std::size_t end = std::min<std::size_t>(g.bytes.size(), std::size_t{g.offsets[entry + 1]} + 192);
        for (std::size_t at = g.offsets[entry] & ~std::size_t{63}; at < end; at += 64) __builtin_prefetch(g.bytes.data() + at);
    }
    BitReader in{g.bytes.data(), std::size_t{g.offsets[entry]} * 8};
    const double key_step = detail::step_of(static_cast<int>(in.get(8)));
    if (t == 0) {
        g.read_column(in, 0, nullptr, nullptr, key_step, y);
        return;
    }
    g.read_column(in, 0, nullptr, nullptr, key_step, a);
    {
        BitReader next{g.bytes.data(), std::size_t{g.offsets[entry + 1]} * 8};
        const double next_step = detail::step_of(static_cast<int>(next.get(8)));
        g.read_column(next, 0, nullptr, nullptr, next_step, b);
    }
    const double step = detail::step_of(static_cast<int>(in.get(8)));
    std::size_t skip[8] = {0};
    in.pos = read_directory(g.bytes.data(), in.pos, g.levels, t, skip);
    int lo = 0, hi = g.W;
    double* lo_y = a;
    double* hi_y = b;
    for (int l = 1;; ++l) {
        const int mid = (lo + hi) / 2;
        if (mid == t) {
            g.read_column(in, l, lo_y, hi_y, step, y);
            return;
        }
        double* out = lo_y != a && hi_y != a ? a : lo_y != b && hi_y != b ? b : c;
        g.read_column(in, l, lo_y, hi_y, step, out);
        if (t < mid) {
            hi = mid;
            hi_y = out;
        } else {
            in.pos += skip[l];
            lo = mid;
            lo_y = out;
        }
    }
}


// ---- Variant 2: every column's size in the directory, so that a frame's columns (two keys and its
// path) decode as independent chains, interleaved symbol by symbol. ----

struct Chain {
    FastBits bits;
    const std::uint16_t* table = nullptr;
    int d = 0;
    std::int32_t* q = nullptr;
    bool live = false;
};

/// One symbol of a chain (the run/size code of RuntimeGroup::read_column, into q).
inline void chain_step(Chain& c, int Da, int B) {
    c.bits.refill();
    const std::uint16_t e = c.table[(static_cast<std::size_t>(c.d >> 3) << B) | static_cast<std::size_t>(c.bits.buf >> (64 - B))];
    if (e & (1u << 14)) {
        c.bits.drop(e & 15);
        c.live = false;
        return;
    }
    const int len = e & 15, cat = (e >> 9) & 31;
    c.d += (e >> 4) & 31;
    const auto v = static_cast<std::uint32_t>(((c.bits.buf << len) >> 1) >> (63 - cat));
    c.bits.drop(len + cat);
    if (cat) {
        const auto mag = static_cast<std::int32_t>((1u << (cat - 1)) | (v & ((1u << (cat - 1)) - 1)));
        c.q[c.d] = (v >> (cat - 1)) ? -mag : mag;
        ++c.d;
    }
    if (c.d >= Da) c.live = false;
}

struct RuntimeGroup2 {
    const RuntimeGroup* base = nullptr;  // codes, tables, geometry
    std::vector<std::uint32_t> offsets;
    std::vector<std::uint8_t> bytes;
    std::size_t directory_bits = 0;
    std::vector<int> tree_level, tree_frame;
};

RuntimeGroup2 build_runtime2(const RuntimeGroup& g, const HierResult& r) {
    RuntimeGroup2 g2;
    g2.base = &g;
    tree_order(g.W, g2.tree_level, g2.tree_frame);
    BitWriter out;
    auto size_of = [&](int level, const std::vector<std::int32_t>& v) {
        BitWriter scratch;
        g.write_column(scratch, level, v);
        return scratch.bits();
    };
    for (const auto& e : r.entries) {
        out.align();
        g2.offsets.push_back(static_cast<std::uint32_t>(out.bytes.size()));
        out.put(static_cast<std::uint32_t>(e.key_step), 8);
        const std::size_t key_bits = size_of(0, e.key);
        const int key_width = bit_length(static_cast<std::uint32_t>(key_bits));
        out.put(static_cast<std::uint32_t>(key_width), 5);
        out.put(static_cast<std::uint32_t>(key_bits), key_width);
        g2.directory_bits += 5 + static_cast<std::size_t>(key_width);
        g.write_column(out, 0, e.key);
        if (e.step < 0) continue;
        out.put(static_cast<std::uint32_t>(e.step), 8);
        std::vector<std::size_t> size;
        std::vector<int> width(static_cast<std::size_t>(g.levels + 1), 0);
        for (std::size_t i = 0; i < e.columns.size(); ++i) {
            size.push_back(size_of(g2.tree_level[i], e.columns[i]));
            auto& w = width[static_cast<std::size_t>(g2.tree_level[i])];
            w = std::max(w, bit_length(static_cast<std::uint32_t>(size.back())));
        }
        const std::size_t before = out.bits();
        for (int l = 1; l <= g.levels; ++l) out.put(static_cast<std::uint32_t>(width[static_cast<std::size_t>(l)]), 5);
        for (std::size_t i = 0; i < e.columns.size(); ++i)
            out.put(static_cast<std::uint32_t>(size[i]), width[static_cast<std::size_t>(g2.tree_level[i])]);
        g2.directory_bits += out.bits() - before;
        for (std::size_t i = 0; i < e.columns.size(); ++i) g.write_column(out, g2.tree_level[i], e.columns[i]);
    }
    out.align();
    g2.bytes = std::move(out.bytes);
    g2.bytes.resize(g2.bytes.size() + 8, 0);
    return g2;
}

/// Variant 2's frame: two keys and the path's columns decoded as independent chains, then the
/// predictions (the encoder's expressions, so the same bits). q: (2 + levels) * Da ints of scratch.
void runtime_frame2(const RuntimeGroup2& g2, std::size_t clip, std::size_t frame, double* y, double* a, double* b,
                    double* c, std::int32_t* q) {
    const RuntimeGroup& g = *g2.base;
    const int Da = g.Da, B = kFastBits, W = g.W;
    const std::size_t w = frame / static_cast<std::size_t>(W);
    const int t = static_cast<int>(frame % static_cast<std::size_t>(W));
    const std::size_t entry = g.clip_first[clip] + w;
    const std::uint8_t* data = g2.bytes.data();
    {
        const std::size_t end = std::min<std::size_t>(g2.bytes.size(), std::size_t{g2.offsets[entry + 1]} + 192);
        for (std::size_t at = g2.offsets[entry] & ~std::size_t{63}; at < end; at += 64) __builtin_prefetch(data + at);
    }
    const std::uint16_t* keys = g.flat.data();
    BitReader in{data, std::size_t{g2.offsets[entry]} * 8};
    const double key_step = detail::step_of(static_cast<int>(in.get(8)));
    const std::size_t key_bits = in.get(static_cast<int>(in.get(5)));
    Chain chains[12];
    int n = 0;
    std::fill(q, q + static_cast<std::ptrdiff_t>(2 + g.levels) * Da, 0);
    chains[n++] = Chain{FastBits(data, in.pos), keys, 0, q, true};
    if (t == 0) {
        while (chains[0].live) chain_step(chains[0], Da, B);
        for (int d = 0; d < Da; ++d) y[d] = q[d] ? q[d] * key_step : 0.0;
        return;
    }
    in.pos += key_bits;
    BitReader next{data, std::size_t{g2.offsets[entry + 1]} * 8};
    const double next_step = detail::step_of(static_cast<int>(next.get(8)));
    next.get(static_cast<int>(next.get(5)));
    chains[n++] = Chain{FastBits(data, next.pos), keys, 0, q + Da, true};
    const double step = detail::step_of(static_cast<int>(in.get(8)));
    int width[8] = {0};
    for (int l = 1; l <= g.levels; ++l) width[l] = static_cast<int>(in.get(5));
    // Sizes in tree order; the path's columns and their starts.
    const int columns = W - 1;
    std::size_t start[64];
    std::size_t at = 0;
    {
        std::size_t sizes_bits = 0;
        for (int i = 0; i < columns; ++i) sizes_bits += static_cast<std::size_t>(width[g2.tree_level[static_cast<std::size_t>(i)]]);
        const std::size_t base = in.pos + sizes_bits;
        for (int i = 0; i < columns; ++i) {
            start[i] = base + at;
            at += in.get(width[g2.tree_level[static_cast<std::size_t>(i)]]);
        }
    }
    int path[10], path_mid[10], levels_on_path = 0;
    {
        int lo = 0, hi = W, i = 0;
        for (int l = 1;; ++l) {
            const int mid = (lo + hi) / 2;
            path[levels_on_path] = i;
            path_mid[levels_on_path++] = mid;
            if (mid == t || levels_on_path == 10) break;
            if (t < mid) {
                hi = mid;
                i += 1;
            } else {
                lo = mid;
                i += 1 + ((1 << (g.levels - l)) - 1);
            }
        }
    }
    for (int k = 0; k < levels_on_path && n < 12; ++k)
        chains[n++] = Chain{FastBits(data, start[path[k]]), g.flat.data() + (static_cast<std::size_t>((k + 1) * g.buckets) << B), 0,
                            q + (2 + k) * Da, true};
    for (bool any = true; any;) {
        any = false;
        for (int k = 0; k < n; ++k)
            if (chains[k].live) {
                chain_step(chains[k], Da, B);
                any = true;
            }
    }
    // Predictions, as the encoder formed them.
    for (int d = 0; d < Da; ++d) {
        a[d] = q[d] ? q[d] * key_step : 0.0;
        b[d] = q[Da + d] ? q[Da + d] * next_step : 0.0;
    }
    double* lo_y = a;
    double* hi_y = b;
    for (int k = 0; k < levels_on_path; ++k) {
        const std::int32_t* qk = q + (2 + k) * Da;
        const bool last = k + 1 == levels_on_path;
        double* out = last ? y : (lo_y != a && hi_y != a ? a : lo_y != b && hi_y != b ? b : c);
        for (int d = 0; d < Da; ++d) {
            const double pred = 0.5 * (lo_y[d] + hi_y[d]);
            out[d] = qk[d] ? pred + qk[d] * step : pred;
        }
        if (last) return;
        if (t < path_mid[k]) hi_y = out;
        else lo_y = out;
    }
}


// ---- Variant 3: three independent chains and two symbols per lookup. Each entry's key is written at
// the END of its entry, its bytes in reverse order (read backwards from the next entry's offset), so
// that a frame's two keys and its window's columns start at known places and decode as three
// interleaved chains; the columns keep variant 1's directory and order. The decode tables give up to
// two (run, size) symbols per lookup when both codes fit in the lookahead and the second symbol has
// the first one's context (same row bucket). The same codes as variant 1: every frame's y is checked
// equal to variant 1's, bit for bit. ----

/// Table entry: bits 0-3 len1 (0: no code), 4-8 cat1, 9-13 adv1 (run + 1; 16: sixteen zeros),
/// 14-17 len2 (0: no second symbol), 18-22 cat2, 23-27 adv2, 28 first is end, 29 second is end.
constexpr std::uint32_t kEnd1 = 1u << 28, kEnd2 = 1u << 29;

struct RuntimeGroup3 {
    const RuntimeGroup* base = nullptr;
    std::vector<std::uint32_t> offsets;  // per entry, then one past the last (byte offsets into data)
    std::vector<std::uint8_t> bytes;     // 8 bytes of slack before and after the entries
    std::vector<std::uint32_t> table;    // per context 2^lookup entries
    int lookup = 11;                     // bits a lookup reads (<= kFastBits); longer codes: variant 1's table
    bool pairs = true;
    const std::uint8_t* data() const { return bytes.data() + 8; }
};

inline std::int32_t value_at(std::uint64_t w, int at, int cat) {
    const std::uint64_t top = w << at;
    const auto s = static_cast<std::int32_t>(top >> 63);
    const auto mag = static_cast<std::int32_t>(((top | (std::uint64_t{1} << 63)) >> (63 - cat)) >> 1);
    return (mag ^ -s) + s;
}

/// Symbol fields of a decoded code: (len, cat, adv, end) of symbol s.
inline void symbol_fields(int s, int& cat, int& adv, int& end) {
    end = s == kEnd;
    if (end) { cat = 0; adv = 0; return; }
    if (s == kZeroRun) { cat = 0; adv = 16; return; }
    cat = s & 31;
    adv = (s >> 5) + 1;
}

void build_table3(RuntimeGroup3& g3, bool pairs, int lookup) {
    const RuntimeGroup& g = *g3.base;
    const int B = lookup, shift = kFastBits - lookup;
    const std::size_t n = std::size_t{1} << B;
    g3.pairs = pairs;
    g3.lookup = lookup;
    g3.table.assign(g.codes.size() * n, 0);
    for (std::size_t c = 0; c < g.codes.size(); ++c) {
        const auto& fast = g.codes[c].fast;
        if (fast.empty()) continue;
        for (std::size_t i = 0; i < n; ++i) {
            const auto f = fast[i << shift];
            if (!f.length || f.length > B) continue;  // 0: a longer code (variant 1's table)
            int cat1, adv1, end1;
            symbol_fields(f.symbol, cat1, adv1, end1);
            std::uint32_t e = static_cast<std::uint32_t>(f.length) | static_cast<std::uint32_t>(cat1) << 4 |
                              static_cast<std::uint32_t>(adv1) << 9 | (end1 ? kEnd1 : 0u);
            const int used = f.length + cat1;
            if (pairs && !end1 && cat1 > 0 && used < B) {
                // The second code from the bits left in the lookahead (zero-padded: only if it is whole).
                const std::size_t rest = (i << used) & (n - 1);
                const auto f2 = fast[rest << shift];
                if (f2.length && used + f2.length <= B) {
                    int cat2, adv2, end2;
                    symbol_fields(f2.symbol, cat2, adv2, end2);
                    if (used + f2.length + cat2 <= 56)
                        e |= static_cast<std::uint32_t>(f2.length) << 14 | static_cast<std::uint32_t>(cat2) << 18 |
                             static_cast<std::uint32_t>(adv2) << 23 | (end2 ? kEnd2 : 0u);
                }
            }
            g3.table[c * n + i] = e;
        }
    }
}

RuntimeGroup3 build_runtime3(const RuntimeGroup& g, const HierResult& r, bool pairs, int lookup) {
    RuntimeGroup3 g3;
    g3.base = &g;
    build_table3(g3, pairs, lookup);
    std::vector<int> tl, tf;
    tree_order(g.W, tl, tf);
    BitWriter out;
    for (int k = 0; k < 8; ++k) out.put(0, 8);  // slack before the first entry (backward reads)
    for (const auto& e : r.entries) {
        out.align();
        g3.offsets.push_back(static_cast<std::uint32_t>(out.bytes.size() - 8));
        out.put(static_cast<std::uint32_t>(e.key_step), 8);
        if (e.step >= 0) write_window(g, out, e, tl);
        out.align();
        // The key, its bytes reversed: read backwards from the end of the entry.
        BitWriter key;
        g.write_column(key, 0, e.key);
        key.align();
        for (auto it = key.bytes.rbegin(); it != key.bytes.rend(); ++it) out.put(*it, 8);
    }
    out.align();
    g3.offsets.push_back(static_cast<std::uint32_t>(out.bytes.size() - 8));
    g3.bytes = std::move(out.bytes);
    g3.bytes.resize(g3.bytes.size() + 8, 0);
    return g3;
}

template <bool Rev>
inline std::uint64_t peek3(const std::uint8_t* base, std::size_t pos) {
    std::uint64_t v;
    if (Rev) {
        std::memcpy(&v, base - 8 - (pos >> 3), 8);
    } else {
        std::memcpy(&v, base + (pos >> 3), 8);
        v = __builtin_bswap64(v);
    }
    return v << (pos & 7);
}


// ---- Variant 4: variant 3's bytes and tables, lean decode. The two keys (both at entry ends) as two
// chains interleaved, then the path's columns one after the other as variant 1 decodes them (each
// into its prediction), up to two symbols per lookup; chain state in locals (registers). ----

/// A code longer than the lookup, by variant 1's table: one symbol.
struct SlowSymbol {
    int bits, adv, end;
    std::int32_t value;  // 0: no value (sixteen zeros)
};
template <bool Rev>
__attribute__((noinline)) SlowSymbol slow_symbol(const std::uint16_t* slow, int d, std::uint64_t w) {
    const int B = kFastBits;
    const std::uint16_t e = slow[(static_cast<std::size_t>(d >> 3) << B) | static_cast<std::size_t>(w >> (64 - B))];
    const int len = e & 15;
    if (e & (1u << 14)) return {len, 0, 1, 0};
    const int cat = (e >> 9) & 31, run = (e >> 4) & 31;
    if (!cat) return {len, run, 0, 0};
    return {len + cat, run + 1, 0, value_at(w, len, cat)};
}

/// One lookup of a column (one or two symbols) at bit pos with row d; out[row] = out[row] + v * step
/// for each value (keys: out zero, so v * step). Returns false when the column has ended.
template <bool Rev>
__attribute__((always_inline)) inline bool lean_step(const std::uint8_t* base, std::size_t& pos, int& d, const std::uint32_t* table,
                                                     const std::uint16_t* slow, int Da, int B, double* out, double step) {
    const std::uint64_t w = peek3<Rev>(base, pos);
    const std::uint32_t e = table[(static_cast<std::size_t>(d >> 3) << B) | static_cast<std::size_t>(w >> (64 - B))];
    if (__builtin_expect(e == 0, 0)) {
        const SlowSymbol s = slow_symbol<Rev>(slow, d, w);
        pos += static_cast<std::size_t>(s.bits);
        if (s.end) return false;
        d += s.adv;
        if (s.value) out[d - 1] = out[d - 1] + s.value * step;
        return d < Da;
    }
    const int len1 = static_cast<int>(e & 15), cat1 = static_cast<int>((e >> 4) & 31), adv1 = static_cast<int>((e >> 9) & 31);
    if (e & kEnd1) {
        pos += static_cast<std::size_t>(len1);
        return false;
    }
    const int n1 = len1 + cat1;
    const int d1 = d + adv1;
    if (__builtin_expect(cat1 != 0, 1)) out[d1 - 1] = out[d1 - 1] + value_at(w, len1, cat1) * step;
    const int len2 = static_cast<int>((e >> 14) & 15);
    if (len2 != 0 && ((d & 7) + adv1) < 8 && d1 < Da) {
        const int cat2 = static_cast<int>((e >> 18) & 31), adv2 = static_cast<int>((e >> 23) & 31);
        pos += static_cast<std::size_t>(n1 + len2 + cat2);
        if (e & kEnd2) return false;
        d = d1 + adv2;
        if (cat2) out[d - 1] = out[d - 1] + value_at(w, n1 + len2, cat2) * step;
        return d < Da;
    }
    pos += static_cast<std::size_t>(n1);
    d = d1;
    return d < Da;
}

/// From a window's step byte at `bit` (variant 1's directory and columns): frame t's path of columns,
/// each into its prediction from the keys in a and b (variant 4's decode; the same bits as variant 1).
struct FixedRows;
std::size_t read_fixed(const FixedRows& f, const std::uint8_t* data, std::size_t bit, std::size_t i, int Da, double step, double* out);

/// level1 (variant 8): the level-1 column at level1's fixed widths (clip `clip`) between the step byte
/// and the directory, predicted as the other levels (the same bits as variant 1).
void decode_path(const RuntimeGroup3& g3, const std::uint8_t* data, std::size_t bit, int t, double* y, double* a, double* b,
                 double* c, const FixedRows* level1 = nullptr, std::size_t clip = 0) {
    const RuntimeGroup& g = *g3.base;
    const int Da = g.Da, B = g3.lookup, W = g.W;
    BitReader in{data, bit};
    const double step = detail::step_of(static_cast<int>(in.get(8)));
    std::size_t skip[8] = {0};
    int lo = 0, hi = W;
    double* lo_y = a;
    double* hi_y = b;
    int l = 1;
    std::size_t pos;
    if (level1) {
        const int mid = W / 2;
        double* out = mid == t ? y : c;
        const std::size_t end = read_fixed(*level1, data, in.pos, clip, Da, step, out);
        for (int d = 0; d < Da; ++d) {
            const double p = 0.5 * (a[d] + b[d]);
            out[d] = out[d] != 0.0 ? p + out[d] : p;  // q = 0: the prediction itself (its sign of zero too)
        }
        pos = read_directory(data, end, g.levels, t, skip);
        if (mid == t) return;
        if (t < mid) {
            hi = mid;
            hi_y = out;
        } else {
            pos += skip[1];
            lo = mid;
            lo_y = out;
        }
        l = 2;
    } else {
        pos = read_directory(data, in.pos, g.levels, t, skip);
    }
    for (;; ++l) {
        const int mid = (lo + hi) / 2;
        double* out = mid == t ? y : (lo_y != a && hi_y != a ? a : lo_y != b && hi_y != b ? b : c);
        for (int d = 0; d < Da; ++d) out[d] = 0.5 * (lo_y[d] + hi_y[d]);
        const std::size_t ctx = static_cast<std::size_t>(l * g.buckets);
        const std::uint32_t* table = g3.table.data() + (ctx << B);
        const std::uint16_t* slow = g.flat.data() + (ctx << kFastBits);
        int d = 0;
        while (lean_step<false>(data, pos, d, table, slow, Da, B, out, step)) {
        }
        if (mid == t) return;
        if (t < mid) {
            hi = mid;
            hi_y = out;
        } else {
            pos += skip[l];
            lo = mid;
            lo_y = out;
        }
    }
}

/// Variant 4's frame into y (the same bits as variant 1); a, b, c: Da values of scratch each.
void runtime_frame4(const RuntimeGroup3& g3, std::size_t clip, std::size_t frame, double* y, double* a, double* b, double* c) {
    const RuntimeGroup& g = *g3.base;
    const int Da = g.Da, B = g3.lookup, W = g.W;
    const std::size_t w = frame / static_cast<std::size_t>(W);
    const int t = static_cast<int>(frame % static_cast<std::size_t>(W));
    const std::size_t entry = g.clip_first[clip] + w;
    const std::uint8_t* data = g3.data();
    const std::size_t o0 = g3.offsets[entry], o1 = g3.offsets[entry + 1];
    {
        const std::size_t end = t == 0 ? o1 + 8 : std::size_t{g3.offsets[entry + 2]} + 8;
        for (std::size_t at = o0 & ~std::size_t{63}; at < end; at += 64) __builtin_prefetch(data + at);
    }
    const std::uint32_t* keys = g3.table.data();
    const std::uint16_t* slow_keys = g.flat.data();
    const double key_step = detail::step_of(data[o0]);
    if (t == 0) {
        std::fill(y, y + Da, 0.0);
        std::size_t pos = 0;
        int d = 0;
        while (lean_step<true>(data + o1, pos, d, keys, slow_keys, Da, B, y, key_step)) {
        }
        return;
    }
    const std::size_t o2 = g3.offsets[entry + 2];
    const double next_step = detail::step_of(data[o1]);
    std::fill(a, a + Da, 0.0);
    std::fill(b, b + Da, 0.0);
    {
        // The two keys, interleaved.
        std::size_t pa = 0, pb = 0;
        int da = 0, db = 0;
        bool la = true, lb = true;
        while (la & lb) {
            la = lean_step<true>(data + o1, pa, da, keys, slow_keys, Da, B, a, key_step);
            lb = lean_step<true>(data + o2, pb, db, keys, slow_keys, Da, B, b, next_step);
        }
        while (la) la = lean_step<true>(data + o1, pa, da, keys, slow_keys, Da, B, a, key_step);
        while (lb) lb = lean_step<true>(data + o2, pb, db, keys, slow_keys, Da, B, b, next_step);
    }
    decode_path(g3, data, (o0 + 1) * 8, t, y, a, b, c);
}


// ---- Variant 7: variant 4 with keys at fixed widths: per clip and row one width (5 bits each, in the
// clip's header), each key row its two's complement value at that width; a key decodes with no
// symbol chain (every row's place is known). Columns as variant 4 (pairs, same codes). ----

/// Values of one kind (keys; variant 8 also the windows' level-1 columns) at fixed widths per clip
/// and row: each row's value minus the clip's center for the row at the clip's width for the row;
/// with escapes, a value outside the width's range is -2^(w-1) in its slot and then in full width
/// after the slots (see fixed_rows, write_fixed, fixed_key).
struct FixedRows {
    std::vector<std::uint8_t> width;   // per clip, Da widths
    std::vector<std::uint16_t> at;     // per clip, Da + 1 bit offsets of the slots (prefix sums)
    std::vector<std::int32_t> center;  // per clip, Da values every row is stored relative to (--key-centers)
    std::vector<std::uint8_t> full;    // per clip, Da widths of an escaped value (> width: the row has escapes)
    std::size_t width_bits = 0;        // the widths (and centers) as stored
};

struct RuntimeGroup7 {
    const RuntimeGroup3* v3 = nullptr;  // tables
    std::vector<std::uint32_t> offsets;  // per entry, then one past the last
    std::vector<std::uint8_t> bytes;     // 8 bytes of slack after
    FixedRows keys;
    FixedRows level1;  // variant 8: the windows' level-1 columns (center 0)
    std::size_t width_bits = 0;          // keys' and level 1's widths as stored
};

/// Two's complement bits that hold q (0 for 0).
int twos_bits(std::int64_t q) {
    if (!q) return 0;
    int b = 0;
    while (b < 40 && !(q >= -(std::int64_t{1} << b) && q < (std::int64_t{1} << b))) ++b;
    return b + 1;
}

/// Bits of a static Huffman code of `values` (table: 5 bits per symbol and 8).
std::size_t coded_bits(const std::vector<int>& values) {
    std::map<int, std::size_t> hist;
    for (int v : values) ++hist[v];
    if (hist.empty()) return 0;
    const std::map<int, int> lengths = huffman_lengths(hist);
    std::size_t bits = 8 + 5 * hist.size();
    for (const auto& [v, n] : hist) bits += n * static_cast<std::size_t>(lengths.at(v));
    return bits;
}

/// The width that codes `values` smallest when a value outside (-2^(w-1), 2^(w-1)) is stored as
/// -2^(w-1) and then at `full` bits (full: the width that holds them all); its bits into *bits.
int escape_width(const std::vector<std::int64_t>& values, int full, double* bits) {
    const auto n = static_cast<double>(values.size());
    double best = static_cast<double>(full) * n;
    int best_w = full;
    for (int x = 1; x < full; ++x) {
        double cost = static_cast<double>(x) * n;
        for (std::int64_t v : values)
            if (!(v > -(std::int64_t{1} << (x - 1)) && v < (std::int64_t{1} << (x - 1)))) cost += full;
        if (cost < best) {
            best = cost;
            best_w = x;
        }
    }
    if (bits) *bits = best;
    return best_w;
}

/// One past clip i's last entry.
std::size_t entries_end(const HierResult& r, std::size_t i) {
    return i + 1 < r.clip_first.size() ? r.clip_first[i + 1] : r.entries.size();
}

/// Per clip of r and row, the width (with escapes: the one that codes the row smallest), center and
/// escape width of the values values(e) of its entries (nullptr: an entry without such values).
template <class Values>
FixedRows fixed_rows(const HierResult& r, std::size_t Da, Values values, bool centers, bool escapes) {
    FixedRows f;
    const std::size_t clips = r.clip_first.size();
    f.width.assign(clips * Da, 0);
    f.center.assign(clips * Da, 0);
    f.full.assign(clips * Da, 0);
    f.at.assign(clips * (Da + 1), 0);
    for (std::size_t i = 0; i < clips; ++i) {
        std::vector<const std::vector<std::int32_t>*> of;
        for (std::size_t e = r.clip_first[i]; e < entries_end(r, i); ++e)
            if (const std::vector<std::int32_t>* v = values(e)) of.push_back(v);
        std::uint8_t* w = f.width.data() + i * Da;
        std::int32_t* center = f.center.data() + i * Da;
        if (centers && !of.empty())
            for (std::size_t d = 0; d < Da; ++d) {
                std::int32_t lo = (*of.front())[d], hi = lo;
                for (const auto* v : of) {
                    lo = std::min(lo, (*v)[d]);
                    hi = std::max(hi, (*v)[d]);
                }
                center[d] = static_cast<std::int32_t>((static_cast<std::int64_t>(lo) + hi) >> 1);
            }
        for (const auto* v : of)
            for (std::size_t d = 0; d < Da; ++d)
                w[d] = static_cast<std::uint8_t>(std::max<int>(w[d], twos_bits(static_cast<std::int64_t>((*v)[d]) - center[d])));
        std::uint8_t* full = f.full.data() + i * Da;
        for (std::size_t d = 0; d < Da; ++d) {
            full[d] = w[d];
            if (!escapes) continue;
            std::vector<std::int64_t> row;
            for (const auto* v : of) row.push_back(static_cast<std::int64_t>((*v)[d]) - center[d]);
            w[d] = static_cast<std::uint8_t>(escape_width(row, full[d], nullptr));
        }
        std::uint16_t* at = f.at.data() + i * (Da + 1);
        for (std::size_t d = 0; d < Da; ++d) at[d + 1] = static_cast<std::uint16_t>(at[d] + w[d]);
    }
    // The widths as stored: per row the group's largest (5 bits), then each clip's as its difference
    // from it by a static Huffman code of the group (table: 5 bits per symbol and 8).
    // With centers: each center at its own width (a Huffman-coded width, then its bits).
    std::vector<int> largest(Da, 0);
    for (std::size_t i = 0; i < clips; ++i)
        for (std::size_t d = 0; d < Da; ++d) largest[d] = std::max<int>(largest[d], f.width[i * Da + d]);
    std::vector<int> deltas, center_widths, extra;
    for (std::size_t i = 0; i < clips; ++i)
        for (std::size_t d = 0; d < Da; ++d) {
            deltas.push_back(largest[d] - f.width[i * Da + d]);
            if (escapes) extra.push_back(f.full[i * Da + d] - f.width[i * Da + d]);
            if (centers) {
                center_widths.push_back(twos_bits(f.center[i * Da + d]));
                f.width_bits += static_cast<std::size_t>(center_widths.back());
            }
        }
    f.width_bits += 5 * Da + coded_bits(deltas) + coded_bits(center_widths) + coded_bits(extra);
    return f;
}

/// Values v of clip i at f's widths: the slots, then the escaped values.
void write_fixed(BitWriter& out, const FixedRows& f, std::size_t i, std::size_t Da, const std::vector<std::int32_t>& v) {
    const std::uint8_t* w = f.width.data() + i * Da;
    const std::int32_t* center = f.center.data() + i * Da;
    const std::uint8_t* full = f.full.data() + i * Da;
    std::vector<std::pair<std::int64_t, int>> escaped;
    for (std::size_t d = 0; d < Da; ++d) {
        const std::int64_t x = static_cast<std::int64_t>(v[d]) - center[d];
        if (full[d] > w[d] && !(x > -(std::int64_t{1} << (w[d] - 1)) && x < (std::int64_t{1} << (w[d] - 1)))) {
            out.put(static_cast<std::uint32_t>(-(std::int64_t{1} << (w[d] - 1))), w[d]);
            escaped.push_back({x, full[d]});
        } else {
            out.put(static_cast<std::uint32_t>(x), w[d]);
        }
    }
    for (const auto& [x, fw] : escaped) out.put(static_cast<std::uint32_t>(x), fw);
}

/// Variant 7 (level1 false) or 8 (level1 true: each window's level-1 column at fixed widths, center
/// 0, after the window's step byte and before its directory).
RuntimeGroup7 build_runtime7(const RuntimeGroup3& g3, const HierResult& r, bool centers, bool escapes, bool level1 = false) {
    const RuntimeGroup& g = *g3.base;
    RuntimeGroup7 g7;
    g7.v3 = &g3;
    const auto Da = static_cast<std::size_t>(g.Da);
    std::vector<int> tl, tf;
    tree_order(g.W, tl, tf);
    g7.keys = fixed_rows(r, Da, [&](std::size_t e) { return &r.entries[e].key; }, centers, escapes);
    g7.width_bits = g7.keys.width_bits;
    if (level1) {
        g7.level1 = fixed_rows(r, Da, [&](std::size_t e) { return r.entries[e].step >= 0 ? &r.entries[e].columns[0] : nullptr; }, false,
                               escapes);
        g7.width_bits += g7.level1.width_bits;
    }
    std::vector<std::size_t> clip_of(r.entries.size());
    for (std::size_t i = 0; i < r.clip_first.size(); ++i)
        for (std::size_t e = r.clip_first[i]; e < entries_end(r, i); ++e) clip_of[e] = i;
    BitWriter out;
    for (std::size_t k = 0; k < r.entries.size(); ++k) {
        const auto& e = r.entries[k];
        out.align();
        g7.offsets.push_back(static_cast<std::uint32_t>(out.bytes.size()));
        out.put(static_cast<std::uint32_t>(e.key_step), 8);
        write_fixed(out, g7.keys, clip_of[k], Da, e.key);
        if (e.step < 0) continue;
        if (!level1) {
            write_window(g, out, e, tl);
            continue;
        }
        // write_window's bits with its level-1 column (tree order's first, right after the directory;
        // never in a left-subtree size) at fixed widths between the step byte and the directory.
        BitWriter window, first;
        const std::size_t directory = write_window(g, window, e, tl);
        g.write_column(first, tl[0], e.columns[0]);
        const std::size_t bits = window.bits();
        window.align();
        window.bytes.resize(window.bytes.size() + 8, 0);
        BitReader in{window.bytes.data(), 0};
        out.put(static_cast<std::uint32_t>(in.get(8)), 8);
        write_fixed(out, g7.level1, clip_of[k], Da, e.columns[0]);
        auto copy = [&](std::size_t n) {
            for (; n >= 16; n -= 16) out.put(static_cast<std::uint32_t>(in.get(16)), 16);
            if (n) out.put(static_cast<std::uint32_t>(in.get(static_cast<int>(n))), static_cast<int>(n));
        };
        copy(directory);
        in.pos += first.bits();
        copy(bits - 8 - directory - first.bits());
    }
    out.align();
    g7.offsets.push_back(static_cast<std::uint32_t>(out.bytes.size()));
    g7.bytes = std::move(out.bytes);
    g7.bytes.resize(g7.bytes.size() + 8, 0);
    return g7;
}

/// w bits at bit p as a two's complement value (0 when w is 0).
inline std::int64_t signed_bits(const std::uint8_t* data, std::size_t p, int w) {
    std::uint64_t v;
    std::memcpy(&v, data + (p >> 3), 8);
    v = __builtin_bswap64(v) << (p & 7);
    // Arithmetic shift of the top w bits (w 0: a shift by 63 and then by 1, never by 64).
    const auto q = static_cast<std::int64_t>(v) >> (63 - (w ? w - 1 : 63)) >> (w ? 0 : 1);
    return w ? q : 0;
}

/// A key's escaped values from bit `escape` on (rows escaped[0..n), in row order, each at its width
/// full[d]): out[d] = (value + center[d]) * step. Returns the bit after them.
inline std::size_t read_escapes(const std::uint8_t* data, std::size_t escape, const int* escaped, int n, const std::uint8_t* full,
                                const std::int32_t* center, double step, double* out) {
    for (int k = 0; k < n; ++k) {
        const int d = escaped[k], f = full[d];
        out[d] = static_cast<double>(signed_bits(data, escape, f) + center[d]) * step;
        escape += static_cast<std::size_t>(f);
    }
    return escape;
}

/// A fixed-width key at bit `bit`: out[d] = q * step (+0.0 where q is 0, as the encoder formed it).
/// Returns the bit after the key (its slots, then its escaped values). The rows whose slot holds the
/// escape code (-2^(w-1) in a row that has escapes) are listed in the slots' pass without branches,
/// and only those read their escaped values (in row order, as written).
inline std::size_t fixed_key(const std::uint8_t* data, std::size_t bit, const std::uint8_t* width, const std::uint16_t* at,
                             const std::int32_t* center, const std::uint8_t* full, int Da, double step, double* out) {
    int escaped[256];
    int n = 0;
    for (int d = 0; d < Da; ++d) {
        const int w = width[d];
        const std::int64_t q = signed_bits(data, bit + at[d], w);
        out[d] = static_cast<double>(q + center[d]) * step;
        const auto code = static_cast<std::int64_t>(~std::uint64_t{0} << ((w - 1) & 63));  // -2^(w-1)
        escaped[n] = d;
        n += static_cast<int>((full[d] > w) & (q == code));
    }
    return read_escapes(data, bit + at[Da], escaped, n, full, center, step, out);
}

/// Two keys of clip i (the same widths) at bits bit_a and bit_b into a and b in one pass: fixed_key's
/// values, with the rows' widths, offsets and centers loaded once. Returns the bit after key a.
inline std::size_t read_fixed_pair(const FixedRows& f, const std::uint8_t* data, std::size_t bit_a, std::size_t bit_b, std::size_t i, int Da,
                                   double step_a, double step_b, double* a, double* b) {
    const auto n = static_cast<std::size_t>(Da);
    const std::uint8_t* width = f.width.data() + i * n;
    const std::uint16_t* at = f.at.data() + i * (n + 1);
    const std::int32_t* center = f.center.data() + i * n;
    const std::uint8_t* full = f.full.data() + i * n;
    int escaped_a[256], escaped_b[256];
    int na = 0, nb = 0;
    for (int d = 0; d < Da; ++d) {
        const int w = width[d];
        const std::int64_t qa = signed_bits(data, bit_a + at[d], w), qb = signed_bits(data, bit_b + at[d], w);
        a[d] = static_cast<double>(qa + center[d]) * step_a;
        b[d] = static_cast<double>(qb + center[d]) * step_b;
        const auto code = static_cast<std::int64_t>(~std::uint64_t{0} << ((w - 1) & 63));  // -2^(w-1)
        const bool escapes = full[d] > w;
        escaped_a[na] = d;
        na += static_cast<int>(escapes & (qa == code));
        escaped_b[nb] = d;
        nb += static_cast<int>(escapes & (qb == code));
    }
    std::size_t escape_a = bit_a + at[Da], escape_b = bit_b + at[Da];
    read_escapes(data, escape_b, escaped_b, nb, full, center, step_b, b);
    return read_escapes(data, escape_a, escaped_a, na, full, center, step_a, a);
}

/// FixedRows' keys as a per-clip plan for a decoder whose keys start at a byte (variant 9): the rows
/// with a nonzero width and no escapes first, then those with escapes (each ascending), each its slot's
/// byte and shifts (value = (bswap(8 bytes at byte) << shl) >> sar, arithmetic); then the rows of
/// width 0 (value 0).
struct KeyPlan {
    struct Row {
        std::uint16_t byte;
        std::uint8_t d, shl, sar, escapes;
    };
    std::vector<Row> rows;               // per clip Da rows: nonzero width without escapes, with escapes, width 0
    std::vector<std::uint16_t> plain;    // per clip, its rows of nonzero width without escapes
    std::vector<std::uint16_t> nonzero;  // per clip, its rows of nonzero width
    std::size_t bytes() const { return rows.size() * sizeof(Row) + 2 * nonzero.size() * sizeof(std::uint16_t); }
};

KeyPlan key_plan(const FixedRows& f, std::size_t clips, int Da) {
    KeyPlan plan;
    const auto n = static_cast<std::size_t>(Da);
    for (std::size_t i = 0; i < clips; ++i) {
        std::uint16_t count[3] = {0, 0, 0};
        for (int pass = 0; pass < 3; ++pass)
            for (std::size_t d = 0; d < n; ++d) {
                const int w = f.width[i * n + d];
                const bool escapes = f.full[i * n + d] > w;
                if ((w == 0 ? 2 : escapes ? 1 : 0) != pass) continue;
                const std::uint16_t at = f.at[i * (n + 1) + d];
                plan.rows.push_back({static_cast<std::uint16_t>(at >> 3), static_cast<std::uint8_t>(d), static_cast<std::uint8_t>(at & 7),
                                     static_cast<std::uint8_t>(64 - w), static_cast<std::uint8_t>(escapes)});
                ++count[pass];
            }
        plan.plain.push_back(count[0]);
        plan.nonzero.push_back(static_cast<std::uint16_t>(count[0] + count[1]));
    }
    return plan;
}

/// Row r of two keys whose slots start at pa and pb: its stored values into qa and qb, and a[r.d],
/// b[r.d] as fixed_key forms them (value + center, times the key's step).
inline void plan_row(const KeyPlan::Row r, const std::uint8_t* pa, const std::uint8_t* pb, const std::int32_t* center, double step_a,
                     double step_b, double* a, double* b, std::int64_t& qa, std::int64_t& qb) {
    std::uint64_t va, vb;
    std::memcpy(&va, pa + r.byte, 8);
    std::memcpy(&vb, pb + r.byte, 8);
    qa = static_cast<std::int64_t>(__builtin_bswap64(va) << r.shl) >> r.sar;
    qb = static_cast<std::int64_t>(__builtin_bswap64(vb) << r.shl) >> r.sar;
    a[r.d] = static_cast<double>(qa + center[r.d]) * step_a;
    b[r.d] = static_cast<double>(qb + center[r.d]) * step_b;
}

/// Two keys of clip i, starting at bytes at_a and at_b, by the plan into a and b (fixed_key's values).
/// Returns the bit after key a.
inline std::size_t read_plan_pair(const KeyPlan& plan, const FixedRows& f, const std::uint8_t* data, std::size_t at_a, std::size_t at_b,
                                  std::size_t i, int Da, double step_a, double step_b, double* a, double* b) {
    const auto n = static_cast<std::size_t>(Da);
    const KeyPlan::Row* rows = plan.rows.data() + i * n;
    const int plain = plan.plain[i], nonzero = plan.nonzero[i];
    const std::int32_t* center = f.center.data() + i * n;
    const std::uint8_t* pa = data + at_a;
    const std::uint8_t* pb = data + at_b;
    std::int64_t qa, qb;
    for (int k = 0; k < plain; ++k) plan_row(rows[k], pa, pb, center, step_a, step_b, a, b, qa, qb);
    // Rows with escapes (ascending, as the escaped values are written): the escape code -2^(w-1) in a
    // slot lists the row for its escaped value.
    int escaped_a[256], escaped_b[256];
    int na = 0, nb = 0;
    for (int k = plain; k < nonzero; ++k) {
        const KeyPlan::Row r = rows[k];
        plan_row(r, pa, pb, center, step_a, step_b, a, b, qa, qb);
        const std::int64_t code = std::numeric_limits<std::int64_t>::min() >> r.sar;  // -2^(w-1)
        escaped_a[na] = r.d;
        na += static_cast<int>(qa == code);
        escaped_b[nb] = r.d;
        nb += static_cast<int>(qb == code);
    }
    for (int k = nonzero; k < Da; ++k) {
        const int d = rows[k].d;
        a[d] = static_cast<double>(std::int64_t{0} + center[d]) * step_a;
        b[d] = static_cast<double>(std::int64_t{0} + center[d]) * step_b;
    }
    const std::uint8_t* full = f.full.data() + i * n;
    const std::size_t slots = f.at[i * (n + 1) + n];
    std::size_t escape_a = at_a * 8 + slots, escape_b = at_b * 8 + slots;
    read_escapes(data, escape_b, escaped_b, nb, full, center, step_b, b);
    return read_escapes(data, escape_a, escaped_a, na, full, center, step_a, a);
}

/// Clip i's values of f at bit `bit` into out (out[d] = value * step); returns the bit after them.
std::size_t read_fixed(const FixedRows& f, const std::uint8_t* data, std::size_t bit, std::size_t i, int Da, double step,
                              double* out) {
    const auto n = static_cast<std::size_t>(Da);
    return fixed_key(data, bit, f.width.data() + i * n, f.at.data() + i * (n + 1), f.center.data() + i * n, f.full.data() + i * n, Da,
                     step, out);
}

/// A frame into y from entries that start with a step byte and a key at `keys`' fixed widths: the
/// frame's key (t = 0), or its window's two keys into a and b and then path(key_end, t) for the rest.
/// pair: the two keys in one pass (read_fixed_pair, or by `plan` when given).
/// offsets(clip, window, o0, o1): the byte offsets of the window's entry and the next.
template <class Offsets, class Path>
void frame_with_fixed_keys(const RuntimeGroup& g, const FixedRows& keys, Offsets offsets, const std::uint8_t* data,
                           std::size_t clip, std::size_t frame, double* y, double* a, double* b, Path path, bool pair = false,
                           const KeyPlan* plan = nullptr) {
    const int Da = g.Da, W = g.W;
    const std::size_t w = frame / static_cast<std::size_t>(W);
    const int t = static_cast<int>(frame % static_cast<std::size_t>(W));
    std::size_t o0, o1;
    offsets(clip, w, o0, o1);
    {
        const std::size_t key_bits = keys.at[clip * static_cast<std::size_t>(Da + 1) + static_cast<std::size_t>(Da)];
        const std::size_t end = (t == 0 ? o0 : o1) + key_bits / 8 + 9;
        for (std::size_t x = o0 & ~std::size_t{63}; x < end; x += 64) __builtin_prefetch(data + x);
    }
    const double key_step = detail::step_of(data[o0]);
    if (t == 0) {
        read_fixed(keys, data, o0 * 8 + 8, clip, Da, key_step, y);
        return;
    }
    if (plan) {
        path(read_plan_pair(*plan, keys, data, o0 + 1, o1 + 1, clip, Da, key_step, detail::step_of(data[o1]), a, b), t);
        return;
    }
    if (pair) {
        path(read_fixed_pair(keys, data, o0 * 8 + 8, o1 * 8 + 8, clip, Da, key_step, detail::step_of(data[o1]), a, b), t);
        return;
    }
    const std::size_t key_end = read_fixed(keys, data, o0 * 8 + 8, clip, Da, key_step, a);
    read_fixed(keys, data, o1 * 8 + 8, clip, Da, detail::step_of(data[o1]), b);
    path(key_end, t);
}

/// Variant 7's frame into y (variant 8's when g7 has level-1 widths); the same bits as variant 1.
void runtime_frame7(const RuntimeGroup7& g7, std::size_t clip, std::size_t frame, double* y, double* a, double* b, double* c) {
    const RuntimeGroup3& g3 = *g7.v3;
    const std::uint8_t* data = g7.bytes.data();
    const RuntimeGroup& g = *g3.base;
    auto offsets = [&](std::size_t i, std::size_t w, std::size_t& o0, std::size_t& o1) {
        o0 = g7.offsets[g.clip_first[i] + w];
        o1 = g7.offsets[g.clip_first[i] + w + 1];
    };
    frame_with_fixed_keys(g, g7.keys, offsets, data, clip, frame, y, a, b, [&](std::size_t key_end, int t) {
        decode_path(g3, data, key_end, t, y, a, b, c, g7.level1.width.empty() ? nullptr : &g7.level1, clip);
    });
}


// ---- Variant 9: variant 7's keys; each detail column by QUADS, four rows per symbol. A quad whose
// values are all within [-S, S] is one symbol (its pattern); else a width symbol (the two's complement
// width of its largest value, 2-32) followed by its four values at that width; an end symbol after
// the column's last nonzero quad (none when that quad reaches the last row). Static canonical Huffman
// codes per (level, row >> shift), at most kMaxCode bits, so one lookup decodes a quad. The same
// quantized values as variant 1: every frame's y is checked equal to variant 1's, bit for bit. ----

constexpr int kQuadWide = 1000;  // symbol kQuadWide + w: a quad at width w

struct QuadCode {
    int S = 1, shift = 3, per_level = 0, levels = 0, bits = 11;  // bits: code lengths at most, lookup width
    std::vector<HuffmanCode> codes;       // (level - 1) * per_level + (row >> shift)
    std::vector<std::uint16_t> table;     // per code 2^kMaxCode entries: bits 0-3 length, 4-13 pattern or
                                          // width, 14 wide, 15 end (0: no code)
    std::vector<std::int32_t> patterns;   // four values per pattern
    std::size_t table_bits = 0;           // the codes as stored
    std::size_t code(int level, int row) const { return static_cast<std::size_t>((level - 1) * per_level + (row >> shift)); }
    int symbol(const std::int32_t* v, int Da, int d, int* width) const {
        int mx = 0, pattern = 0, w = 0;
        for (int k = d; k < d + 4; ++k) {
            const std::int32_t q = k < Da ? v[k] : 0;
            mx = std::max(mx, std::abs(q));
            w = std::max(w, twos_bits(q));
            pattern = pattern * (2 * S + 1) + (std::clamp(q, -S, S) + S);
        }
        *width = w;
        return mx <= S ? pattern : kQuadWide + w;
    }
    /// Calls fn(code index, symbol, width) for each symbol of column v.
    template <class Fn>
    void each_symbol(int level, const std::vector<std::int32_t>& v, Fn fn) const {
        const int Da = static_cast<int>(v.size());
        int n = Da;
        while (n > 0 && v[static_cast<std::size_t>(n - 1)] == 0) --n;
        int d = 0;
        for (; d < n; d += 4) {
            int w = 0;
            const int s = symbol(v.data(), Da, d, &w);
            fn(code(level, d), s, s >= kQuadWide ? w : 0, d);
        }
        if (d < Da) fn(code(level, d), kEnd, 0, d);
    }
    void write_column(BitWriter& out, int level, const std::vector<std::int32_t>& v) const {
        const int Da = static_cast<int>(v.size());
        each_symbol(level, v, [&](std::size_t c, int s, int w, int d) {
            codes[c].write(out, s);
            for (int k = d; w && k < d + 4; ++k) out.put(static_cast<std::uint32_t>(k < Da ? v[static_cast<std::size_t>(k)] : 0), w);
        });
    }
};

QuadCode build_quads(const HierResult& r, int W, int Da, int S, int shift, int bits) {
    QuadCode qc;
    qc.S = S;
    qc.shift = shift;
    qc.bits = bits;
    struct Restore {  // HuffmanCode::build limits lengths to kMaxCode: the quads' own limit meanwhile
        int saved = kMaxCode;
        ~Restore() { kMaxCode = saved; }
    } restore;
    kMaxCode = bits;
    while ((1 << qc.levels) < W) ++qc.levels;
    qc.per_level = ((Da + 3) >> shift) + 1;
    std::vector<int> tl, tf;
    tree_order(W, tl, tf);
    std::vector<std::map<int, std::size_t>> hist(static_cast<std::size_t>(qc.levels * qc.per_level));
    for (const auto& e : r.entries)
        for (std::size_t i = 0; i < e.columns.size(); ++i)
            qc.each_symbol(tl[i], e.columns[i], [&](std::size_t c, int s, int, int) { ++hist[c][s]; });
    const int patterns = (2 * S + 1) * (2 * S + 1) * (2 * S + 1) * (2 * S + 1);
    if (patterns > 1024 || bits > 15) throw std::runtime_error("quads: S or the code length too large for the 16-bit table");
    // The codes as stored: per code the smaller of a length per symbol of the alphabet (4 bits each)
    // and a list of the used symbols (symbol index and length), and 8 bits.
    const double alphabet = patterns + 32 + 1;
    const std::size_t n = std::size_t{1} << bits;
    qc.codes.resize(hist.size());
    qc.table.assign(hist.size() * n, 0);
    for (std::size_t c = 0; c < hist.size(); ++c) {
        if (hist[c].empty()) continue;
        qc.codes[c].build(hist[c]);
        const auto used = static_cast<double>(hist[c].size());
        qc.table_bits += 8 + static_cast<std::size_t>(std::min(4.0 * alphabet, (std::ceil(std::log2(alphabet)) + 4.0) * used));
        for (std::size_t i = 0; i < n; ++i) {
            const auto f = qc.codes[c].fast[i];
            if (!f.length) continue;
            std::uint32_t e = f.length;
            if (f.symbol == kEnd) e |= 1u << 15;
            else if (f.symbol >= kQuadWide) e |= static_cast<std::uint32_t>(f.symbol - kQuadWide) << 4 | 1u << 14;
            else e |= static_cast<std::uint32_t>(f.symbol) << 4;
            qc.table[c * n + i] = static_cast<std::uint16_t>(e);
        }
    }
    qc.patterns.assign(static_cast<std::size_t>(4 * patterns), 0);
    for (int p = 0; p < patterns; ++p)
        for (int k = 3, x = p; k >= 0; --k, x /= 2 * S + 1) qc.patterns[static_cast<std::size_t>(4 * p + k)] = x % (2 * S + 1) - S;
    return qc;
}

/// Entry offsets as stored (variant 9): per clip its first entry's byte offset, the bit at which its
/// later entries' offsets start and their width (4 + 4 + 1 bytes), then each later entry's byte
/// offset from the clip's first at that width (`bits`).
struct PackedOffsets {
    struct Clip {
        std::uint32_t base = 0, at = 0;
        std::uint8_t width = 0;
    };
    std::vector<Clip> clips;
    std::vector<std::uint8_t> bits;  // 8 bytes of slack after
    std::size_t bit_count = 0;
    std::size_t stored_bytes() const { return 9 * clips.size() + (bit_count + 7) / 8; }
    static std::size_t read(const std::uint8_t* data, std::size_t p, int w) {
        std::uint64_t v;
        std::memcpy(&v, data + (p >> 3), 8);
        return static_cast<std::size_t>((__builtin_bswap64(v) << (p & 7)) >> (64 - w));
    }
    /// Byte offsets of clip i's entries k and k + 1.
    void pair(std::size_t i, std::size_t k, std::size_t& o0, std::size_t& o1) const {
        const Clip& c = clips[i];
        const std::size_t p = c.at + k * c.width;  // entry k + 1's slot (entry 0 has none)
        o0 = c.base + (k ? read(bits.data(), p - c.width, c.width) : 0);
        o1 = c.base + read(bits.data(), p, c.width);
    }
};

PackedOffsets pack_offsets(const HierResult& r, const std::vector<std::uint32_t>& offsets) {
    PackedOffsets p;
    BitWriter out;
    for (std::size_t i = 0; i < r.clip_first.size(); ++i) {
        const std::size_t first = r.clip_first[i], last = entries_end(r, i);  // entries first..last-1
        PackedOffsets::Clip c;
        c.base = offsets[first];
        c.at = static_cast<std::uint32_t>(out.bits());
        c.width = static_cast<std::uint8_t>(bit_length(offsets[last - 1] - c.base));
        for (std::size_t k = first + 1; k < last; ++k) out.put(offsets[k] - c.base, c.width);
        p.clips.push_back(c);
    }
    p.bit_count = out.bits();
    out.align();
    p.bits = std::move(out.bytes);
    p.bits.resize(p.bits.size() + 8, 0);
    return p;
}

struct RuntimeGroup9 {
    const RuntimeGroup* base = nullptr;
    QuadCode quads;
    FixedRows keys;
    KeyPlan plan;
    PackedOffsets packed;                // the offsets as stored and read
    std::vector<std::uint8_t> directory_widths;  // per clip 8: the directory's width per level, or 0: in each window
    std::size_t directory_bits = 0;              // the clip table's flags and widths as stored
    int stored = 0;                              // the directory's levels (finer left subtrees are skipped by scanning)
    bool prefetch_clip = false;                  // prefetch the clip's key plan first
    bool avx2_combine = false;                   // combine_avx2 (where the CPU has it; the same bits)
    std::vector<std::uint32_t> offsets;  // per entry, then one past the last
    std::vector<std::uint8_t> bytes;     // 16 bytes of slack after
};

RuntimeGroup9 build_runtime9(const RuntimeGroup& g, const HierResult& r, const FixedRows& keys, int S, int shift, int stored, int bits) {
    RuntimeGroup9 g9;
    g9.base = &g;
    g9.stored = std::min(stored, g.levels - 1);
    g9.quads = build_quads(r, g.W, g.Da, S, shift, bits);
    g9.keys = keys;
    g9.plan = key_plan(keys, r.clip_first.size(), g.Da);
    const auto Da = static_cast<std::size_t>(g.Da);
    std::vector<int> tl, tf;
    tree_order(g.W, tl, tf);
    BitWriter out;
    auto quads = [&](BitWriter& o, int level, const std::vector<std::int32_t>& v) { g9.quads.write_column(o, level, v); };
    for (std::size_t i = 0; i < r.clip_first.size(); ++i) {
        // The directory's widths per clip (in the clip table) or per window (in each window), whichever
        // gives the clip's entries fewer bytes (a clip with per-window widths has width 0 in the table).
        int widths[8] = {0};
        for (std::size_t k = r.clip_first[i]; k < entries_end(r, i); ++k)
            if (r.entries[k].step >= 0) write_window_by(g.levels, out, r.entries[k], tl, quads, nullptr, widths, g9.stored);
        auto entry = [&](BitWriter& o, std::size_t k, const int* w) {
            const auto& e = r.entries[k];
            o.put(static_cast<std::uint32_t>(e.key_step), 8);
            write_fixed(o, keys, i, Da, e.key);
            if (e.step >= 0) write_window_by(g.levels, o, e, tl, quads, w, nullptr, g9.stored);
            o.align();
        };
        std::size_t per_clip = 0, per_window = 0;
        for (std::size_t k = r.clip_first[i]; k < entries_end(r, i); ++k) {
            BitWriter a, b;
            entry(a, k, widths);
            entry(b, k, nullptr);
            per_clip += a.bytes.size();
            per_window += b.bytes.size();
        }
        const bool clip_widths = 8 * per_clip + 5 * static_cast<std::size_t>(g9.stored) < 8 * per_window;
        g9.directory_bits += 1 + (clip_widths ? 5 * static_cast<std::size_t>(g9.stored) : 0);
        for (int l = 0; l < 8; ++l) g9.directory_widths.push_back(static_cast<std::uint8_t>(clip_widths ? widths[l] : 0));
        for (std::size_t k = r.clip_first[i]; k < entries_end(r, i); ++k) {
            out.align();
            g9.offsets.push_back(static_cast<std::uint32_t>(out.bytes.size()));
            entry(out, k, clip_widths ? widths : nullptr);
        }
    }
    out.align();
    g9.offsets.push_back(static_cast<std::uint32_t>(out.bytes.size()));
    g9.bytes = std::move(out.bytes);
    g9.bytes.resize(g9.bytes.size() + 16, 0);
    g9.packed = pack_offsets(r, g9.offsets);
    return g9;
}

/// out[d] = p + q[d] * step where q[d] is nonzero, else p, with p = 0.5 * (lo[d] + hi[d]): the
/// encoder's expressions (SSE2 two rows at a time: the same operations, a select instead of a branch).
inline void combine(double* out, const double* lo, const double* hi, const std::int32_t* q, double step, int Da) {
    int d = 0;
#ifdef __SSE2__
    const __m128d half = _mm_set1_pd(0.5), s = _mm_set1_pd(step), zero = _mm_setzero_pd();
    for (; d + 2 <= Da; d += 2) {
        const __m128d p = _mm_mul_pd(half, _mm_add_pd(_mm_loadu_pd(lo + d), _mm_loadu_pd(hi + d)));
        const __m128d v = _mm_cvtepi32_pd(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(q + d)));
        const __m128d nonzero = _mm_cmpneq_pd(v, zero);
        const __m128d sum = _mm_add_pd(p, _mm_mul_pd(v, s));
        _mm_storeu_pd(out + d, _mm_or_pd(_mm_and_pd(nonzero, sum), _mm_andnot_pd(nonzero, p)));
    }
#endif
    for (; d < Da; ++d) {
        const double p = 0.5 * (lo[d] + hi[d]);
        out[d] = q[d] ? p + q[d] * step : p;
    }
}

/// One column of quads at bit pos into q (rows past the last decoded quad zero, up to Da rounded up to
/// 4); returns the bit after the column. The bits are held in a register (FastBits: a branch-free
/// refill whose load does not wait for the symbol being decoded), so that a quad's lookup waits only
/// for the previous one's length (reading 8 bytes at each quad's bit instead: hot poses 9 % slower).
inline std::size_t read_quads(const QuadCode& qc, const std::uint8_t* data, std::size_t pos, int level, int Da, std::int32_t* q) {
    const int B = qc.bits, shift = qc.shift;
    const std::uint16_t* table = qc.table.data() + (qc.code(level, 0) << B);
    const std::int32_t* patterns = qc.patterns.data();
    FastBits bits(data, pos);
    int d = 0;
    while (d < Da) {
        bits.refill();
        const std::uint32_t e = table[(static_cast<std::size_t>(d >> shift) << B) | static_cast<std::size_t>(bits.buf >> (64 - B))];
        bits.drop(static_cast<int>(e & 15));
        if (__builtin_expect((e & 0xC000u) == 0, 1)) {
            std::memcpy(q + d, patterns + 4 * ((e >> 4) & 1023), 4 * sizeof(std::int32_t));
            d += 4;
            continue;
        }
        if (e & (1u << 15)) break;
        const int wd = static_cast<int>((e >> 4) & 1023);
        if (wd <= 14) {
            bits.refill();
            const std::uint64_t x = bits.buf;
            for (int k = 0; k < 4; ++k) q[d + k] = static_cast<std::int32_t>(static_cast<std::int64_t>(x << (k * wd)) >> (64 - wd));
            bits.drop(4 * wd);
        } else {
            for (int k = 0; k < 4; ++k) {
                bits.refill();
                q[d + k] = static_cast<std::int32_t>(static_cast<std::int64_t>(bits.buf) >> (64 - wd));
                bits.drop(wd);
            }
        }
        d += 4;
    }
    for (; d < Da; ++d) q[d] = 0;
    return bits.consumed;
}

/// The bit after the column of quads at bit pos (its codes and raw bits summed, nothing decoded).
inline std::size_t skip_quads(const QuadCode& qc, const std::uint8_t* data, std::size_t pos, int level, int Da) {
    const int B = qc.bits, shift = qc.shift;
    const std::uint16_t* table = qc.table.data() + (qc.code(level, 0) << B);
    for (int d = 0; d < Da; d += 4) {
        const std::uint64_t w = peek3<false>(data, pos);
        const std::uint32_t e = table[(static_cast<std::size_t>(d >> shift) << B) | static_cast<std::size_t>(w >> (64 - B))];
        pos += (e & 15) + ((e >> 14) & 1) * 4 * ((e >> 4) & 1023);
        if (e & (1u << 15)) break;
    }
    return pos;
}

/// The bit after the subtree of columns (tree order) whose root column, at bit pos, is at `level`.
inline std::size_t skip_subtree(const QuadCode& qc, const std::uint8_t* data, std::size_t pos, int level, int Da) {
    pos = skip_quads(qc, data, pos, level, Da);
    if (level < qc.levels) {
        pos = skip_subtree(qc, data, pos, level + 1, Da);
        pos = skip_subtree(qc, data, pos, level + 1, Da);
    }
    return pos;
}

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
/// combine with AVX2 (four rows at a time; the same operations per row, no FMA: the same bits), for
/// CPUs that have it (variant 9's `avx2_combine`).
__attribute__((target("avx2"))) void combine_avx2(double* out, const double* lo, const double* hi, const std::int32_t* q, double step, int Da) {
    typedef double V4d __attribute__((vector_size(32)));
    typedef std::int32_t V4i __attribute__((vector_size(16)));
    typedef std::int64_t V4l __attribute__((vector_size(32)));
    const V4d half = {0.5, 0.5, 0.5, 0.5}, s = {step, step, step, step}, zero = {0.0, 0.0, 0.0, 0.0};
    int d = 0;
    for (; d + 4 <= Da; d += 4) {
        V4d l, h;
        V4i qi;
        std::memcpy(&l, lo + d, sizeof l);
        std::memcpy(&h, hi + d, sizeof h);
        std::memcpy(&qi, q + d, sizeof qi);
        const V4d p = half * (l + h);
        const V4d v = __builtin_convertvector(qi, V4d);
        const V4l nonzero = v != zero;
        const V4d sum = p + v * s;
        const V4d r = nonzero ? sum : p;
        std::memcpy(out + d, &r, sizeof r);
    }
    for (; d < Da; ++d) {
        const double p = 0.5 * (lo[d] + hi[d]);
        out[d] = q[d] ? p + q[d] * step : p;
    }
}
bool cpu_has_avx2() { return __builtin_cpu_supports("avx2"); }
#else
void combine_avx2(double* out, const double* lo, const double* hi, const std::int32_t* q, double step, int Da) { combine(out, lo, hi, q, step, Da); }
bool cpu_has_avx2() { return false; }
#endif

/// Variant 9's path from the window's step byte at `bit`: each column's quads into q, then
/// out = prediction (+ q * step where q is nonzero), the encoder's expressions.
void decode_path9(const RuntimeGroup9& g9, const std::uint8_t* data, std::size_t bit, int t, double* y, double* a, double* b, double* c,
                  std::size_t clip) {
    const RuntimeGroup& g = *g9.base;
    const int Da = g.Da, W = g.W;
    alignas(16) std::int32_t q[260];
    BitReader in{data, bit};
    const double step = detail::step_of(static_cast<int>(in.get(8)));
    std::size_t skip[8] = {0};
    const std::uint8_t* widths = g9.directory_widths.data() + 8 * clip;
    std::size_t pos = read_directory(data, in.pos, g.levels, t, skip, widths[1] ? widths : nullptr, g9.stored);
    int lo = 0, hi = W;
    double* lo_y = a;
    double* hi_y = b;
    for (int l = 1;; ++l) {
        const int mid = (lo + hi) / 2;
        double* out = mid == t ? y : (lo_y != a && hi_y != a ? a : lo_y != b && hi_y != b ? b : c);
        pos = read_quads(g9.quads, data, pos, l, Da, q);
        if (g9.avx2_combine) combine_avx2(out, lo_y, hi_y, q, step, Da);
        else combine(out, lo_y, hi_y, q, step, Da);
        if (mid == t) return;
        if (t < mid) {
            hi = mid;
            hi_y = out;
        } else {
            pos = l <= g9.stored ? pos + skip[l] : skip_subtree(g9.quads, data, pos, l + 1, Da);
            lo = mid;
            lo_y = out;
        }
    }
}

/// Variant 9's frame into y; the same bits as variant 1.
/// keys: 2 by the key plan, 1 paired (read_fixed_pair), 0 one after the other; keys_only: no path
/// (timing of the keys alone: y is not complete).
void runtime_frame9(const RuntimeGroup9& g9, std::size_t clip, std::size_t frame, double* y, double* a, double* b, double* c, int keys = 2,
                    bool keys_only = false) {
    const std::uint8_t* data = g9.bytes.data();
    if (g9.prefetch_clip) {
        // The clip's key plan, centers and escape widths: known before the entry's offset is.
        const auto n = static_cast<std::size_t>(g9.base->Da);
        const auto* rows = reinterpret_cast<const char*>(g9.plan.rows.data() + clip * n);
        for (std::size_t x = 0; x < n * sizeof(KeyPlan::Row); x += 64) __builtin_prefetch(rows + x);
        const auto* center = reinterpret_cast<const char*>(g9.keys.center.data() + clip * n);
        for (std::size_t x = 0; x < n * sizeof(std::int32_t); x += 64) __builtin_prefetch(center + x);
        __builtin_prefetch(g9.keys.full.data() + clip * n);
    }
    auto offsets = [&](std::size_t i, std::size_t w, std::size_t& o0, std::size_t& o1) { g9.packed.pair(i, w, o0, o1); };
    frame_with_fixed_keys(*g9.base, g9.keys, offsets, data, clip, frame, y, a, b,
                          [&](std::size_t key_end, int t) {
                              if (!keys_only) decode_path9(g9, data, key_end, t, y, a, b, c, clip);
                          }, keys > 0, keys == 2 ? &g9.plan : nullptr);
}

/// Estimate (RT_STATS): bits per level of a column code by groups of G rows: a group whose values are
/// all within [-S, S] is one joint symbol (its pattern), else a width symbol (two's complement width
/// of its largest) and the G values raw at that width; an end symbol after the last nonzero group.
/// Context: (level, row/8). scheme 0: today's run/size symbols (RuntimeGroup::symbols) for comparison.
struct SchemeBits {
    double bits[6] = {}, symbols[6] = {}, columns[6] = {}, tables = 0.0;
};
SchemeBits scheme_bits(const HierResult& r, int W, int scheme, int G, int S, int cdiv = 8) {
    std::vector<int> tl, tf;
    tree_order(W, tl, tf);
    std::map<std::pair<int, int>, std::map<int, std::size_t>> hist;
    struct Sym { int level, ctx, sym; double extra; };
    std::vector<Sym> all;
    auto column = [&](int level, const std::vector<std::int32_t>& v) {
        const int Da = static_cast<int>(v.size());
        int n = Da;
        while (n > 0 && v[static_cast<std::size_t>(n - 1)] == 0) --n;
        if (scheme == 0) {
            int start = 0;
            for (int d = 0; d < n; ++d) {
                const std::int32_t q = v[static_cast<std::size_t>(d)];
                if (q == 0) continue;
                while (d - start >= 16) { all.push_back({level, start / 8, kZeroRun, 0}); start += 16; }
                const int c = bit_length(static_cast<std::uint32_t>(std::abs(q)));
                all.push_back({level, start / 8, (d - start) * 32 + c, static_cast<double>(c)});
                start = d + 1;
            }
            if (n < Da) all.push_back({level, start / 8, kEnd, 0});
            return;
        }
        int d = 0;
        for (; d < n; d += G) {
            int mx = 0, pattern = 0;
            for (int k = d; k < d + G; ++k) {
                const int q = k < Da ? v[static_cast<std::size_t>(k)] : 0;
                mx = std::max(mx, std::abs(q));
                pattern = pattern * (2 * S + 1) + (std::clamp(q, -S, S) + S);
            }
            if (mx <= S) all.push_back({level, d / cdiv, pattern, 0});
            else if (scheme == 2) {  // two widths: rows d, d + 1 and rows d + 2, d + 3
                int w1 = 0, w2 = 0;
                for (int k = d; k < d + 2 && k < Da; ++k) w1 = std::max(w1, twos_bits(v[static_cast<std::size_t>(k)]));
                for (int k = d + 2; k < d + 4 && k < Da; ++k) w2 = std::max(w2, twos_bits(v[static_cast<std::size_t>(k)]));
                all.push_back({level, d / cdiv, 100000 + 64 * w1 + w2, 2.0 * (w1 + w2)});
            } else {
                int w = 0;
                for (int k = d; k < d + G && k < Da; ++k) w = std::max(w, twos_bits(v[static_cast<std::size_t>(k)]));
                all.push_back({level, d / cdiv, 100000 + w, static_cast<double>(G * w)});
            }
        }
        if (d < Da) all.push_back({level, d / cdiv, -1, 0});
    };
    SchemeBits out;
    for (const auto& e : r.entries) {
        for (std::size_t i = 0; i < e.columns.size(); ++i) {
            column(tl[i], e.columns[i]);
            out.columns[tl[i]] += 1;
        }
    }
    for (const Sym& x : all) ++hist[{x.level, x.ctx}][x.sym];
    std::map<std::pair<int, int>, std::map<int, int>> lengths;
    const double alphabet = scheme == 0 ? 16 * 20 + 2 : std::pow(2 * S + 1, G) + 22;
    for (const auto& [ctx, h] : hist) {
        lengths[ctx] = huffman_lengths(h);
        const auto used = static_cast<double>(h.size());
        out.tables += 8.0 + std::min(4.0 * alphabet, (std::ceil(std::log2(alphabet)) + 4.0) * used);
    }
    for (const Sym& x : all) {
        out.bits[x.level] += lengths[{x.level, x.ctx}][x.sym] + x.extra;
        out.symbols[x.level] += 1;
    }
    return out;
}

}  // namespace

int main(int argc, char** argv) {
    std::vector<std::string> folders{"cmu-walkrun-pfnn", "cmu-asfamc"};
    std::vector<double> errors{1.0, 0.1};
    std::vector<int> windows{16, 32};
    std::vector<int> key_offsets{0, 12};
    double rounding = 0.4;
    std::size_t limit = 0;
    std::vector<int> lookups{11, 9, 8};  // variant 4's lookup widths (the first also without pairs)
    int reps = 3;                        // repeats of the variant 4 and 7 timings (best of)
    bool identity_dofs = false;          // --dof identity: no dof basis (y = x, no product at decode)
    bool key_centers = true;             // --key-centers 0: variant 7's keys without per-clip centers
    bool key_escapes = true;             // --key-escapes 0: variant 7's keys without escapes
    std::size_t poses = 0;  // > 0: build the bitstream, verify every frame, time this many cold poses
    std::vector<std::pair<int, int>> combos;  // --combos 16:12,8:4: (W, key offset) pairs instead of every W with every offset
    std::vector<std::array<int, 7>> quad_configs;  // variant 9: S, context shift, directory levels, code bits, (unused), prefetch of the clip's key plan, AVX2 combine (--quads 1:3:2:11:1:1:1)
    for (int a = 1; a + 1 < argc; a += 2) {
        const std::string k = argv[a], v = argv[a + 1];
        if (k == "--folders") folders = split(v);
        else if (k == "--errors") { errors.clear(); for (auto& s : split(v)) errors.push_back(std::stod(s)); }
        else if (k == "--windows") { windows.clear(); for (auto& s : split(v)) windows.push_back(std::stoi(s)); }
        else if (k == "--key-offsets") { key_offsets.clear(); for (auto& s : split(v)) key_offsets.push_back(std::stoi(s)); }
        else if (k == "--rounding") rounding = std::stod(v);
        else if (k == "--limit") limit = std::stoul(v);
        else if (k == "--poses") poses = std::stoul(v);
        else if (k == "--code-bits") kMaxCode = std::stoi(v);
        else if (k == "--reps") reps = std::stoi(v);
        else if (k == "--dof") identity_dofs = v == "identity";
        else if (k == "--key-centers") key_centers = v == "1";
        else if (k == "--key-escapes") key_escapes = v == "1";
        else if (k == "--float-dofs") g_float_dofs = v == "1";
        else if (k == "--lookups") { lookups.clear(); for (auto& x : split(v)) lookups.push_back(std::stoi(x)); }
        else if (k == "--combos") {
            for (auto& x : split(v)) combos.push_back({std::stoi(x.substr(0, x.find(':'))), std::stoi(x.substr(x.find(':') + 1))});
        }
        else if (k == "--quads") {
            quad_configs.clear();
            for (auto& x : split(v)) {
                std::array<int, 7> c{1, 3, 9, 11, 0, 0, 0};
                std::stringstream in(x);
                std::string part;
                for (int n = 0; n < 7 && std::getline(in, part, ':'); ++n) c[static_cast<std::size_t>(n)] = std::stoi(part);
                quad_configs.push_back(c);
            }
        }
    }
    std::printf("folder,E,format2_bytes,format2_payload,format2_static,W,key_offset,hier_static,hier_fixed,hier_max,"
                "windows,keys,nonzero,seconds\n");
    for (const auto& folder : folders) {
        const std::vector<Clip> clips = bench::read_shared_folder(folder, limit);
        std::vector<const Clip*> all;
        for (const Clip& c : clips) all.push_back(&c);
        const auto groups = group_clips(all);
        for (double E : errors) {
            PackOptions o;
            o.max_error_cm = E;
            o.time_basis = TimeBasis::Learned;
            o.dof_basis = identity_dofs ? DofBasis::Identity : DofBasis::Learned;
            clear_pose_plans();
            std::vector<detail::GroupModel> models(groups.size());
            std::vector<std::vector<const Clip*>> members(groups.size());
            std::size_t f2_bytes = 0, f2_payload = 0, f2_header = 0;
            std::vector<std::vector<std::uint8_t>> f2(groups.size());
            double f2_static = 0.0;
            for (std::size_t g = 0; g < groups.size(); ++g) {
                for (std::size_t i : groups[g]) members[g].push_back(all[i]);
                const PackedGroup pg = pack_group(members[g], o);
                f2_bytes += pg.stats.bytes;
                f2_payload += pg.stats.payload_bytes + pg.stats.table_bytes;
                f2_header += pg.stats.header_bytes;
                f2[g] = pg.bytes;
                models[g].read_header(pg.bytes.data(), pg.bytes.size());
                f2_static += format2_static_bits(models[g], members[g]);
            }
            std::vector<std::pair<int, int>> runs = combos;  // (W, key offset)
            if (runs.empty())
                for (int W : windows)
                    for (int ko : key_offsets) runs.push_back({W, ko});
            for (const auto& run : runs) {
                {
                    const int W = run.first, ko = run.second;
                    const auto t0 = bench::Clock::now();
                    HierResult total;
                    double static_bits = 0.0, fixed_bits = 0.0;
                    std::vector<RuntimeGroup> runtime;
                    std::vector<HierResult> hier_results;
                    std::vector<double> by_level(10, 0.0);
                    HuffmanFigures huff, rle;
                    for (std::size_t g = 0; g < groups.size(); ++g) {
                        StaticCost cost, widths;
                        const HierResult r = run_hier(models[g], members[g], E, W, ko, cost, widths, rounding);
                        if (std::getenv("RT_STATS")) {
                            std::vector<int> tl, tf;
                            tree_order(W, tl, tf);
                            // per level: histogram of |v| buckets 0,1,2,3,4-7,8-15,16+; columns; rows up to last nonzero
                            double h[6][8] = {}, cols[6] = {}, used[6] = {}, quads_small[6] = {}, quads[6] = {};
                            for (const auto& e : r.entries) {
                                auto add = [&](int l, const std::vector<std::int32_t>& v) {
                                    cols[l] += 1;
                                    int n = static_cast<int>(v.size());
                                    while (n > 0 && v[static_cast<std::size_t>(n - 1)] == 0) --n;
                                    used[l] += n;
                                    for (int d = 0; d < n; ++d) {
                                        const int a = std::abs(v[static_cast<std::size_t>(d)]);
                                        h[l][a == 0 ? 0 : a == 1 ? 1 : a == 2 ? 2 : a == 3 ? 3 : a < 8 ? 4 : a < 16 ? 5 : 6] += 1;
                                    }
                                    for (int d = 0; d < n; d += 4) {
                                        int mx = 0;
                                        for (int k = d; k < d + 4 && k < static_cast<int>(v.size()); ++k) mx = std::max(mx, std::abs(v[static_cast<std::size_t>(k)]));
                                        quads[l] += 1;
                                        if (mx <= 1) quads_small[l] += 1;
                                    }
                                };
                                add(0, e.key);
                                for (std::size_t i = 0; i < e.columns.size(); ++i) add(tl[i], e.columns[i]);
                            }
                            for (int l = 0; l < 5; ++l) {
                                std::printf("#STATS g%zu level %d: columns %.0f, rows used %.1f/col;", g, l, cols[l], used[l] / std::max(1.0, cols[l]));
                                for (int b = 0; b < 7; ++b) std::printf(" %.3f", h[l][b] / std::max(1.0, used[l]));
                                std::printf("; quads/col %.1f, all |v|<=1 %.3f\n", quads[l] / std::max(1.0, cols[l]), quads_small[l] / std::max(1.0, quads[l]));
                            }
                        }
                        for (int j = 0; j < 10; ++j) by_level[static_cast<std::size_t>(j)] += cost.bits(j) / 8;
                        static_bits += r.static_bits + cost.bits();
                        if (poses > 0) {
                            runtime.push_back(build_runtime(r, W, static_cast<int>(models[g].active.size())));
                            hier_results.push_back(r);
                        }
                        const HuffmanFigures h = huffman_bits(r, W, 0);
                        const HuffmanFigures h1 = huffman_bits(r, W, 1);
                        if (std::getenv("RT_STATS")) {
                            const int cfg[][4] = {{0, 1, 0, 8}, {1, 4, 1, 8}, {2, 4, 1, 8}, {2, 4, 0, 8}, {2, 4, 2, 8}};
                            for (const auto& c : cfg) {
                                const SchemeBits b = scheme_bits(r, W, c[0], c[1], c[2], c[3]);
                                double tot = 0;
                                std::printf("#SCHEME g%zu %s G=%d S=%d ctx=row/%d:", g, c[0] ? "groups" : "run/size", c[1], c[2], c[3]);
                                for (int l = 1; l < 5; ++l) {
                                    tot += b.bits[l];
                                    std::printf(" L%d %.0f B (%.1f sym/col)", l, b.bits[l] / 8, b.symbols[l] / std::max(1.0, b.columns[l]));
                                }
                                std::printf(" total %.0f B, tables %.0f B\n", tot / 8, b.tables / 8);
                            }
                        }
                        rle.bits += h1.bits;
                        rle.symbols_per_frame += h1.symbols_per_frame * static_cast<double>(r.windows);
                        huff.bits += h.bits;
                        huff.directory_bits += h.directory_bits;
                        huff.table_bits += h.table_bits;
                        huff.symbols_per_frame += h.symbols_per_frame * static_cast<double>(r.windows);
                        fixed_bits += r.fixed_bits + widths.bits();
                        total.max_error = std::max(total.max_error, r.max_error);
                        total.windows += r.windows;
                        total.keys += r.keys;
                        total.nonzero += r.nonzero;
                    }
                    std::printf("%s,%g,%zu,%zu,%.0f,%d,%d,%.0f,%.0f,%.7f,%zu,%zu,%zu,%.1f\n", folder.c_str(), E, f2_bytes,
                                f2_payload, f2_static / 8, W, ko, static_bits / 8, fixed_bits / 8, total.max_error,
                                total.windows, total.keys, total.nonzero, bench::seconds_since(t0));
                    std::printf("#  huffman %.0f (directory %.0f, tables %.0f), symbols per frame %.1f\n", huff.bits / 8,
                                huff.directory_bits / 8, huff.table_bits / 8,
                                huff.symbols_per_frame / static_cast<double>(std::max<std::size_t>(1, total.windows)));
                    std::printf("#  huffman run/size %.0f, symbols per frame %.1f\n", rle.bits / 8,
                                rle.symbols_per_frame / static_cast<double>(std::max<std::size_t>(1, total.windows)));
                    if (poses > 0) {
                        // Bytes: entries, a 3-byte offset per entry, the code tables, format 2's header as a
                        // stand-in for the shared header (skeletons, dof basis, constants, clip table).
                        double bits = 0.0, directory = 0.0, tables = 0.0;
                        std::size_t entries = 0;
                        for (const RuntimeGroup& rg : runtime) {
                            bits += 8.0 * static_cast<double>(rg.bytes.size() - 8);
                            directory += static_cast<double>(rg.directory_bits);
                            tables += static_cast<double>(rg.table_bits);
                            entries += rg.offsets.size();
                        }
                        const double bytes = bits / 8 + 3.0 * static_cast<double>(entries) + tables / 8 + static_cast<double>(f2_header);
                        // Every frame decoded from the bytes, FK against the source clip.
                        double worst = 0.0;
                        GlobalPose pose;
                        for (std::size_t g = 0; g < groups.size(); ++g) {
                            const auto& m = models[g];
                            const auto Da = m.active.size();
                            std::vector<double> y(Da), a(Da), b(Da), c(Da), p(static_cast<std::size_t>(m.dofs)), row;
                            detail::WindowScratch s;
                            m.prepare(s);
                            for (std::size_t i = 0; i < members[g].size(); ++i) {
                                const Clip& clip = *members[g][i];
                                const auto& e = m.clips[i];
                                const Skeleton& sk = *m.skeletons[e.skeleton].skeleton;
                                row.resize(sk.channel_count());
                                const MatX source = joint_positions(clip);
                                for (std::size_t f = 0; f < clip.frame_count(); ++f) {
                                    runtime_frame(runtime[g], i, f, y.data(), a.data(), b.data(), c.data());
                                    dofs_of_y(m, e, y.data(), s, p.data());
                                    m.row_of(e, p.data(), row.data());
                                    forward_kinematics(sk, row.data(), pose);
                                    for (std::size_t j = 0; j < sk.size(); ++j)
                                        worst = std::max(worst, (pose.positions[j] - source.block<3, 1>(3 * static_cast<Eigen::Index>(j),
                                                                                                          static_cast<Eigen::Index>(f))).norm());
                                }
                            }
                        }
                        // Cold random local poses: the same sequence for both formats.
                        std::mt19937_64 rng(7);
                        std::vector<std::array<std::size_t, 3>> seq;
                        std::size_t frames_total = 0;
                        for (const auto& mem : members)
                            for (const Clip* c : mem) frames_total += c->frame_count();
                        for (std::size_t n = 0; n < poses; ++n) {
                            std::size_t u = std::uniform_int_distribution<std::size_t>(0, frames_total - 1)(rng);
                            for (std::size_t g = 0; g < members.size(); ++g)
                                for (std::size_t i = 0; i < members[g].size(); ++i) {
                                    const std::size_t fc = members[g][i]->frame_count();
                                    if (u < fc) {
                                        seq.push_back({g, i, u});
                                        u = ~std::size_t{0} >> 1;
                                        g = members.size() - 1;
                                        break;
                                    }
                                    u -= fc;
                                }
                        }
                        std::vector<GroupDecoder> decoders;
                        for (const auto& bytes_g : f2) decoders.emplace_back(bytes_g);
                        LocalPose out;
                        double ours = 1e300, theirs = 1e300;
                        std::vector<std::vector<double>> scratch(groups.size());
                        std::vector<detail::WindowScratch> ws(groups.size());
                        for (std::size_t g = 0; g < groups.size(); ++g) {
                            scratch[g].assign(4 * models[g].active.size() + static_cast<std::size_t>(models[g].dofs), 0.0);
                            models[g].prepare(ws[g]);
                        }
                        for (int rep = 0; rep < 3; ++rep) {
                            double c0 = bench::thread_cpu_seconds();
                            for (const auto& [g, i, f] : seq) {
                                const auto& m = models[g];
                                const std::size_t Da = m.active.size();
                                double* base = scratch[g].data();
                                runtime_frame(runtime[g], i, f, base, base + Da, base + 2 * Da, base + 3 * Da);
                                dofs_of_y(m, m.clips[i], base, ws[g], base + 4 * Da);
                                m.local_of(m.clips[i], base + 4 * Da, out);
                            }
                            ours = std::min(ours, (bench::thread_cpu_seconds() - c0) / static_cast<double>(seq.size()) * 1e6);
                            c0 = bench::thread_cpu_seconds();
                            for (const auto& [g, i, f] : seq) decoders[g].decode_local_pose(i, f, out);
                            theirs = std::min(theirs, (bench::thread_cpu_seconds() - c0) / static_cast<double>(seq.size()) * 1e6);
                        }
                        // Stages: the frame's y from the bytes alone, and y -> local pose alone (on stored y).
                        double decode_only = 1e300, pose_only = 1e300;
                        for (int rep = 0; rep < 3; ++rep) {
                            double c0 = bench::thread_cpu_seconds();
                            for (const auto& [g, i, f] : seq) {
                                const std::size_t Da = models[g].active.size();
                                double* base = scratch[g].data();
                                runtime_frame(runtime[g], i, f, base, base + Da, base + 2 * Da, base + 3 * Da);
                            }
                            decode_only = std::min(decode_only, (bench::thread_cpu_seconds() - c0) / static_cast<double>(seq.size()) * 1e6);
                            c0 = bench::thread_cpu_seconds();
                            for (const auto& [g, i, f] : seq) {
                                const auto& m = models[g];
                                const std::size_t Da = m.active.size();
                                double* base = scratch[g].data();
                                dofs_of_y(m, m.clips[i], base, ws[g], base + 4 * Da);
                                m.local_of(m.clips[i], base + 4 * Da, out);
                            }
                            pose_only = std::min(pose_only, (bench::thread_cpu_seconds() - c0) / static_cast<double>(seq.size()) * 1e6);
                        }

                        double no_prefetch = 1e300;
                        for (auto& rg : runtime) rg.prefetch = false;
                        for (int rep = 0; rep < 3; ++rep) {
                            const double c0 = bench::thread_cpu_seconds();
                            for (const auto& [g, i, f] : seq) {
                                const std::size_t Da = models[g].active.size();
                                double* base = scratch[g].data();
                                runtime_frame(runtime[g], i, f, base, base + Da, base + 2 * Da, base + 3 * Da);
                            }
                            no_prefetch = std::min(no_prefetch, (bench::thread_cpu_seconds() - c0) / static_cast<double>(seq.size()) * 1e6);
                        }
                        for (auto& rg : runtime) rg.prefetch = true;
                        double hot = 1e300;  // 32 poses over and over: their bytes stay in L1/L2
                        for (int rep = 0; rep < 3; ++rep) {
                            const double c0 = bench::thread_cpu_seconds();
                            for (int again = 0; again < 200; ++again)
                                for (std::size_t n = 0; n < 32; ++n) {
                                    const auto& [g, i, f] = seq[n];
                                    const std::size_t Da = models[g].active.size();
                                    double* base = scratch[g].data();
                                    runtime_frame(runtime[g], i, f, base, base + Da, base + 2 * Da, base + 3 * Da);
                                }
                            hot = std::min(hot, (bench::thread_cpu_seconds() - c0) / 6400.0 * 1e6);
                        }
                        std::printf("#  hot (32 poses repeated): y from bytes %.3f us\n", hot);
                        // Variant 2: sizes of every column, interleaved chains.
                        std::vector<RuntimeGroup2> runtime2;
                        double directory2 = 0.0, bits2 = 0.0, worst2 = 0.0;
                        {
                            std::size_t gi = 0;
                            for (std::size_t g = 0; g < groups.size(); ++g) {
                                runtime2.push_back(build_runtime2(runtime[g], hier_results[g]));
                                directory2 += static_cast<double>(runtime2.back().directory_bits);
                                bits2 += 8.0 * static_cast<double>(runtime2.back().bytes.size() - 8);
                                ++gi;
                            }
                            // Every frame equal to variant 1's y, bit for bit.
                            for (std::size_t g = 0; g < groups.size(); ++g) {
                                const std::size_t Da = models[g].active.size();
                                std::vector<double> y1(Da), y2(Da), sa(Da), sb(Da), sc(Da);
                                std::vector<std::int32_t> qs(static_cast<std::size_t>(2 + runtime[g].levels) * Da);
                                for (std::size_t i = 0; i < members[g].size(); ++i)
                                    for (std::size_t f = 0; f < members[g][i]->frame_count(); ++f) {
                                        runtime_frame(runtime[g], i, f, y1.data(), sa.data(), sb.data(), sc.data());
                                        runtime_frame2(runtime2[g], i, f, y2.data(), sa.data(), sb.data(), sc.data(), qs.data());
                                        for (std::size_t d = 0; d < Da; ++d)
                                            if (std::memcmp(&y1[d], &y2[d], sizeof(double)) != 0) worst2 = 1e9;
                                    }
                            }
                        }
                        std::vector<std::vector<std::int32_t>> qscratch(groups.size());
                        for (std::size_t g = 0; g < groups.size(); ++g)
                            qscratch[g].assign(static_cast<std::size_t>(2 + runtime[g].levels) * models[g].active.size(), 0);
                        double decode2 = 1e300, cold2 = 1e300;
                        for (int rep = 0; rep < 3; ++rep) {
                            double c0 = bench::thread_cpu_seconds();
                            for (const auto& [g, i, f] : seq) {
                                const std::size_t Da = models[g].active.size();
                                double* base = scratch[g].data();
                                runtime_frame2(runtime2[g], i, f, base, base + Da, base + 2 * Da, base + 3 * Da, qscratch[g].data());
                            }
                            decode2 = std::min(decode2, (bench::thread_cpu_seconds() - c0) / static_cast<double>(seq.size()) * 1e6);
                            c0 = bench::thread_cpu_seconds();
                            for (const auto& [g, i, f] : seq) {
                                const auto& m = models[g];
                                const std::size_t Da = m.active.size();
                                double* base = scratch[g].data();
                                runtime_frame2(runtime2[g], i, f, base, base + Da, base + 2 * Da, base + 3 * Da, qscratch[g].data());
                                dofs_of_y(m, m.clips[i], base, ws[g], base + 4 * Da);
                                m.local_of(m.clips[i], base + 4 * Da, out);
                            }
                            cold2 = std::min(cold2, (bench::thread_cpu_seconds() - c0) / static_cast<double>(seq.size()) * 1e6);
                        }
                        std::size_t entries2 = 0;
                        for (const auto& rg : runtime2) entries2 += rg.offsets.size();
                        std::printf("#  VARIANT 2 (interleaved): bytes %.0f (entries %.0f, directory %.0f); %s; y from bytes %.3f us, "
                                    "cold local pose %.3f us\n",
                                    bits2 / 8 + 3.0 * static_cast<double>(entries2) + tables / 8 + static_cast<double>(f2_header), bits2 / 8,
                                    directory2 / 8, worst2 > 0 ? "MISMATCH with variant 1" : "every frame equal to variant 1", decode2, cold2);
                        // Per clip of every group: fn(group, its entries, Da, the clip's first entry, one past its last).
                        auto each_clip = [&](auto&& fn) {
                            for (std::size_t g = 0; g < groups.size(); ++g)
                                for (std::size_t i = 0; i < hier_results[g].clip_first.size(); ++i)
                                    fn(g, hier_results[g], models[g].active.size(), hier_results[g].clip_first[i], entries_end(hier_results[g], i));
                        };
                        // Detail levels 1-2 coded like variant 7's keys (estimate): per clip and row of a level's
                        // columns the width (with escapes, center 0) that codes smallest, a 5-bit width and a 5-bit
                        // escape width per clip and row, against the columns' Huffman bits.
                        {
                            std::vector<int> tl, tf;
                            tree_order(W, tl, tf);
                            for (int level = 1; level <= 2; ++level) {
                                double column_bits = 0.0, fixed = 0.0;
                                each_clip([&](std::size_t g, const HierResult& hr, std::size_t Da, std::size_t first, std::size_t last) {
                                        std::vector<const std::vector<std::int32_t>*> cols;
                                        for (std::size_t e = first; e < last; ++e)
                                            for (std::size_t k = 0; k < hr.entries[e].columns.size(); ++k)
                                                if (tl[k] == level) {
                                                    cols.push_back(&hr.entries[e].columns[k]);
                                                    BitWriter bw;
                                                    runtime[g].write_column(bw, level, hr.entries[e].columns[k]);
                                                    column_bits += static_cast<double>(bw.bits());
                                                }
                                        for (std::size_t d = 0; d < Da; ++d) {
                                            int full = 0;
                                            std::vector<std::int64_t> values;
                                            for (const auto* c : cols) {
                                                full = std::max(full, twos_bits((*c)[d]));
                                                values.push_back((*c)[d]);
                                            }
                                            double best = 0.0;
                                            escape_width(values, full, &best);
                                            fixed += 10.0 + best;
                                        }
                                });
                                std::printf("#  level %d columns: huffman %.0f bytes, fixed widths per clip and row with escapes %.0f\n", level,
                                            column_bits / 8, fixed / 8);
                            }
                        }
                        // Keys: Huffman bits against fixed widths per clip and row (5 bits a width per clip
                        // and row), and against fixed widths per clip and row of the key minus the previous key.
                        {
                            double huff_bits = 0.0, width_bits = 0.0, delta_bits = 0.0;
                            each_clip([&](std::size_t g, const HierResult& hr, std::size_t Da, std::size_t first, std::size_t last) {
                                    std::vector<int> width(Da, 0), dwidth(Da, 0);
                                    for (std::size_t e = first; e < last; ++e) {
                                        BitWriter bw;
                                        runtime[g].write_column(bw, 0, hr.entries[e].key);
                                        huff_bits += static_cast<double>(bw.bits());
                                        for (std::size_t d = 0; d < Da; ++d) {
                                            const std::int32_t q = hr.entries[e].key[d];
                                            width[d] = std::max(width[d], q ? bit_length(static_cast<std::uint32_t>(std::abs(q))) + 1 : 0);
                                            if (e > first) {
                                                const std::int32_t dq = q - hr.entries[e - 1].key[d] * (1 << 0);
                                                dwidth[d] = std::max(dwidth[d], dq ? bit_length(static_cast<std::uint32_t>(std::abs(dq))) + 1 : 0);
                                            }
                                        }
                                    }
                                    for (std::size_t d = 0; d < Da; ++d) {
                                        width_bits += 5.0 + static_cast<double>(width[d]) * static_cast<double>(last - first);
                                        delta_bits += 5.0 + static_cast<double>(dwidth[d]) * static_cast<double>(last - first);
                                    }
                            });
                            std::printf("#  keys: huffman %.0f bytes, fixed width per clip and row %.0f, previous-key delta at fixed widths %.0f "
                                        "(steps differ between keys: indicative only)\n",
                                        huff_bits / 8, width_bits / 8, delta_bits / 8);
                        }
                        // Variants 4 (per lookup width, with and without two symbols per lookup) and 7 (keys at
                        // fixed widths, with and without escapes), timed A/B against variant 1 in the same reps.
                        {
                            struct Config {
                                int lookup;
                                bool pairs;
                            };
                            std::vector<Config> configs;
                            for (int b : lookups) configs.push_back({b, true});
                            configs.push_back({lookups.front(), false});
                            std::vector<std::vector<RuntimeGroup3>> r4(configs.size());
                            for (std::size_t v = 0; v < configs.size(); ++v)
                                for (std::size_t g = 0; g < groups.size(); ++g)
                                    r4[v].push_back(build_runtime3(runtime[g], hier_results[g], configs[v].pairs, configs[v].lookup));
                            double bytes4 = tables / 8 + static_cast<double>(f2_header);
                            for (const auto& rg : r4[0])
                                bytes4 += static_cast<double>(rg.bytes.size() - 16) + 3.0 * static_cast<double>(rg.offsets.size());
                            // Variant 7: bytes without the keys' (level 0) code tables, with the clips' key widths.
                            // [0] with escapes (--key-escapes), [1] without, [2] variant 8: [0] with the windows' level-1
                            // columns at fixed widths too (without their code tables).
                            std::vector<RuntimeGroup7> r7[3];
                            double bytes7[3];
                            for (int k = 0; k < 3; ++k) bytes7[k] = tables / 8 + static_cast<double>(f2_header);
                            for (std::size_t g = 0; g < groups.size(); ++g)
                                for (int k = 0; k < 3; ++k) {
                                    r7[k].push_back(build_runtime7(r4[0][g], hier_results[g], key_centers, k != 1 && key_escapes, k == 2));
                                    const RuntimeGroup7& b7 = r7[k].back();
                                    bytes7[k] += static_cast<double>(b7.bytes.size() - 8) + 3.0 * static_cast<double>(b7.offsets.size()) +
                                                 static_cast<double>(b7.width_bits) / 8;
                                    for (int c = 0; c < (k == 2 ? 2 : 1) * runtime[g].buckets; ++c) {
                                        const auto& code = runtime[g].codes[static_cast<std::size_t>(c)];
                                        if (!code.length.empty()) bytes7[k] -= (8.0 + 5.0 * static_cast<double>(code.length.size())) / 8;
                                    }
                                }
                            // Variant 9 per --quads config: v7's keys (with escapes), the columns by quads.
                            std::vector<std::vector<RuntimeGroup9>> r9(quad_configs.size());
                            std::vector<double> bytes9(quad_configs.size(), static_cast<double>(f2_header)), tables9_5bit(quad_configs.size(), 0.0),
                                offsets9(quad_configs.size(), 0.0), offsets9_3byte(quad_configs.size(), 0.0);
                            for (std::size_t v = 0; v < quad_configs.size(); ++v)
                                for (std::size_t g = 0; g < groups.size(); ++g) {
                                    r9[v].push_back(build_runtime9(runtime[g], hier_results[g], r7[0][g].keys, quad_configs[v][0], quad_configs[v][1], quad_configs[v][2], quad_configs[v][3]));
                                    r9[v].back().prefetch_clip = quad_configs[v][5] != 0;
                                    r9[v].back().avx2_combine = quad_configs[v][6] != 0 && cpu_has_avx2();
                                    const RuntimeGroup9& b9 = r9[v].back();
                                    bytes9[v] += static_cast<double>(b9.bytes.size() - 16) + static_cast<double>(b9.packed.stored_bytes()) +
                                                 std::ceil(static_cast<double>(b9.directory_bits) / 8) +
                                                 static_cast<double>(r7[0][g].width_bits + b9.quads.table_bits) / 8;
                                    offsets9_3byte[v] += 3.0 * static_cast<double>(b9.offsets.size() - 1);
                                    offsets9[v] += static_cast<double>(b9.packed.stored_bytes());
                                    for (const auto& code : b9.quads.codes)
                                        if (!code.length.empty()) tables9_5bit[v] += (8.0 + 5.0 * static_cast<double>(code.length.size())) / 8;
                                }
                            // Every frame of every variant equal to variant 1's, bit for bit (so within E: the max above).
                            bool equal = true;
                            for (std::size_t g = 0; g < groups.size(); ++g) {
                                const std::size_t Da = models[g].active.size();
                                std::vector<double> y1(Da), yv(Da), sa(Da), sb(Da), sc(Da);
                                auto same = [&] { equal = equal && std::memcmp(y1.data(), yv.data(), Da * sizeof(double)) == 0; };
                                for (std::size_t i = 0; i < members[g].size(); ++i)
                                    for (std::size_t f = 0; f < members[g][i]->frame_count(); ++f) {
                                        runtime_frame(runtime[g], i, f, y1.data(), sa.data(), sb.data(), sc.data());
                                        for (const auto& rv : r4) {
                                            runtime_frame4(rv[g], i, f, yv.data(), sa.data(), sb.data(), sc.data());
                                            same();
                                        }
                                        for (const auto& rv : r7) {
                                            runtime_frame7(rv[g], i, f, yv.data(), sa.data(), sb.data(), sc.data());
                                            same();
                                        }
                                        for (const auto& rv : r9) {
                                            runtime_frame9(rv[g], i, f, yv.data(), sa.data(), sb.data(), sc.data());
                                            same();
                                        }
                                    }
                            }
                            // Cold local pose, y alone, and hot y (32 poses over and over: bytes, tables and branches learnt).
                            struct Times {
                                double cold = 1e300, y = 1e300, hot = 1e300;
                            };
                            std::vector<const PosePlan*> plans;  // per group (no lookup in the timed loops)
                            for (const auto& m : models) plans.push_back(g_float_dofs ? &pose_plan(m) : nullptr);
                            auto time = [&](auto&& frame_fn, Times& t, bool float64_product = false, PosePath path = PosePath::library) {
                                for (int with_pose = 1; with_pose >= 0; --with_pose) {
                                    const double c0 = bench::thread_cpu_seconds();
                                    for (const auto& [g, i, f] : seq) {
                                        const auto& m = models[g];
                                        const std::size_t Da = m.active.size();
                                        double* base = scratch[g].data();
                                        frame_fn(g, i, f, base, Da);
                                        if (with_pose) {
                                            if (float64_product) {
                                                m.pose_of(m.clips[i], base, static_cast<int>(Da), ws[g], base + 4 * Da);
                                                m.local_of(m.clips[i], base + 4 * Da, out);
                                            } else {
                                                local_pose_of_y(m, m.clips[i], base, ws[g], base + 4 * Da, out, path, plans[g]);
                                            }
                                        }
                                    }
                                    double& slot = with_pose ? t.cold : t.y;
                                    slot = std::min(slot, (bench::thread_cpu_seconds() - c0) / static_cast<double>(seq.size()) * 1e6);
                                }
                                const double c0 = bench::thread_cpu_seconds();
                                for (int again = 0; again < 200; ++again)
                                    for (std::size_t n = 0; n < 32; ++n) {
                                        const auto& [g, i, f] = seq[n];
                                        frame_fn(g, i, f, scratch[g].data(), models[g].active.size());
                                    }
                                t.hot = std::min(t.hot, (bench::thread_cpu_seconds() - c0) / 6400.0 * 1e6);
                            };
                            // The kernels' local poses against the library's on every frame (v1's y): the dofs
                            // of both builds equal to dofs_of_y's, the poses equal bit for bit (else the max
                            // difference of a component).
                            const bool avx2 = detail::pose_avx2_available();
                            std::size_t pose_frames = 0, pose_differ = 0;
                            double pose_diff = 0.0;
                            bool dofs_equal = true;
                            g_pose_fallbacks = 0;
                            if (g_float_dofs) {
                                LocalPose ref, got;
                                for (std::size_t g = 0; g < groups.size(); ++g) {
                                    const auto& m = models[g];
                                    const std::size_t Da = m.active.size(), D = static_cast<std::size_t>(m.dofs);
                                    std::vector<double> yv(Da), sa(Da), sb(Da), sc(Da), p0(D), p1(D);
                                    for (std::size_t i = 0; i < members[g].size(); ++i)
                                        for (std::size_t f = 0; f < members[g][i]->frame_count(); ++f) {
                                            runtime_frame(runtime[g], i, f, yv.data(), sa.data(), sb.data(), sc.data());
                                            local_pose_of_y(m, m.clips[i], yv.data(), ws[g], p0.data(), ref, PosePath::library);
                                            for (PosePath path : {PosePath::portable, PosePath::avx2}) {
                                                if (path == PosePath::avx2 && !avx2) continue;
                                                local_pose_of_y(m, m.clips[i], yv.data(), ws[g], p1.data(), got, path);
                                                dofs_equal = dofs_equal && std::memcmp(p0.data(), p1.data(), D * sizeof(double)) == 0;
                                                ++pose_frames;
                                                bool same_pose = true;
                                                for (std::size_t j = 0; j < ref.rotations.size(); ++j) {
                                                    same_pose = same_pose && std::memcmp(&ref.rotations[j], &got.rotations[j], sizeof(Quat)) == 0 &&
                                                                std::memcmp(&ref.translations[j], &got.translations[j], sizeof(Vec3)) == 0;
                                                    pose_diff = std::max({pose_diff, (ref.rotations[j].coeffs() - got.rotations[j].coeffs()).cwiseAbs().maxCoeff(),
                                                                          (ref.translations[j] - got.translations[j]).cwiseAbs().maxCoeff()});
                                                }
                                                if (!same_pose) ++pose_differ;
                                            }
                                        }
                                }
                                std::printf("#  pose kernels (%s): %zu frame decodes, dofs %s, local poses %zu differ from the library's (max %.3g), %zu left "
                                            "to the library\n",
                                            avx2 ? "portable and AVX2" : "portable; no AVX2", pose_frames,
                                            dofs_equal ? "equal to the library path's" : "DIFFER", pose_differ, pose_diff, g_pose_fallbacks);
                            }
                            // The library's runtime tier (packing::encode_runtime, RuntimeDecoder) on the same packed
                            // groups at this W (its key offset and directory levels: W 8 -> 4 and 1, W 16 -> 8 and 2, as
                            // the --combos 8:4 / 16:8 and --quads 1:3:1 / 1:3:2 runs): its bytes (bodies + the same header
                            // stand-in as v9), every frame's local pose against v9's (the first --quads config; since the
                            // library's format 2, a step per level and three predictors, its frames differ from v9's), and
                            // its cold local pose timed in the same repeats.
                            const bool library_tier = (W == 8 && ko == 4) || (W == 16 && ko == 8);
                            std::vector<RuntimeBody> lib_bodies;
                            std::vector<RuntimeDecoder> lib_decoders;
                            double lib_bytes = static_cast<double>(f2_header);
                            std::size_t lib_resident = 0, lib_differ = 0, lib_frames = 0;
                            if (library_tier) {
                                for (std::size_t g = 0; g < groups.size(); ++g) {
                                    RuntimeOptions ro;
                                    ro.max_error_cm = E;
                                    ro.window = W;
                                    lib_bodies.push_back(encode_runtime(f2[g], members[g], ro));
                                    lib_bytes += static_cast<double>(lib_bodies.back().bytes.size());
                                }
                                for (std::size_t g = 0; g < groups.size(); ++g) {
                                    lib_decoders.emplace_back(f2[g].data(), f2[g].size(), lib_bodies[g].bytes.data(), lib_bodies[g].bytes.size());
                                    lib_resident += lib_decoders.back().resident_bytes();
                                }
                                if (!r9.empty() && g_float_dofs)
                                    for (std::size_t g = 0; g < groups.size(); ++g) {
                                        const auto& m = models[g];
                                        const std::size_t Da = m.active.size();
                                        std::vector<double> buf(4 * Da + static_cast<std::size_t>(m.dofs));
                                        LocalPose ref, got;
                                        for (std::size_t i = 0; i < members[g].size(); ++i)
                                            for (std::size_t f = 0; f < members[g][i]->frame_count(); ++f, ++lib_frames) {
                                                runtime_frame9(r9[0][g], i, f, buf.data(), buf.data() + Da, buf.data() + 2 * Da, buf.data() + 3 * Da);
                                                local_pose_of_y(m, m.clips[i], buf.data(), ws[g], buf.data() + 4 * Da, ref,
                                                                avx2 ? PosePath::avx2 : PosePath::portable, plans[g]);
                                                lib_decoders[g].decode_local_pose(i, f, got);
                                                const bool same = ref.rotations.size() == got.rotations.size() &&
                                                                  std::memcmp(ref.rotations.data(), got.rotations.data(), ref.rotations.size() * sizeof(Quat)) == 0 &&
                                                                  std::memcmp(ref.translations.data(), got.translations.data(), ref.translations.size() * sizeof(Vec3)) == 0;
                                                if (!same) ++lib_differ;
                                            }
                                    }
                            }
                            double lib_cold = 1e300;
                            Times t1, t1d, t7[3], t7k[3][2];  // t7k: with the pose kernels, portable and AVX2
                            std::vector<Times> t4(configs.size()), t9(quad_configs.size()), t9s(quad_configs.size()), t9k(quad_configs.size());
                            const PosePath fastest = !g_float_dofs ? PosePath::library : avx2 ? PosePath::avx2 : PosePath::portable;
                            for (int rep = 0; rep < reps; ++rep) {
                                if (library_tier) {
                                    const double c0 = bench::thread_cpu_seconds();
                                    for (const auto& [g, i, f] : seq) lib_decoders[g].decode_local_pose(i, f, out);
                                    lib_cold = std::min(lib_cold, (bench::thread_cpu_seconds() - c0) / static_cast<double>(seq.size()) * 1e6);
                                }
                                for (std::size_t v = 0; v < quad_configs.size(); ++v) {
                                    time([&](std::size_t g, std::size_t i, std::size_t f, double* base, std::size_t Da) {
                                        runtime_frame9(r9[v][g], i, f, base, base + Da, base + 2 * Da, base + 3 * Da);
                                    }, t9[v], false, fastest);
                                    time([&](std::size_t g, std::size_t i, std::size_t f, double* base, std::size_t Da) {
                                        runtime_frame9(r9[v][g], i, f, base, base + Da, base + 2 * Da, base + 3 * Da, 1);
                                    }, t9s[v], false, fastest);
                                    time([&](std::size_t g, std::size_t i, std::size_t f, double* base, std::size_t Da) {
                                        runtime_frame9(r9[v][g], i, f, base, base + Da, base + 2 * Da, base + 3 * Da, 2, true);
                                    }, t9k[v], false, fastest);
                                }
                                time([&](std::size_t g, std::size_t i, std::size_t f, double* base, std::size_t Da) {
                                    runtime_frame(runtime[g], i, f, base, base + Da, base + 2 * Da, base + 3 * Da);
                                }, t1);
                                time([&](std::size_t g, std::size_t i, std::size_t f, double* base, std::size_t Da) {
                                    runtime_frame(runtime[g], i, f, base, base + Da, base + 2 * Da, base + 3 * Da);
                                }, t1d, true);
                                for (int k = 0; k < 3; ++k) {
                                    time([&](std::size_t g, std::size_t i, std::size_t f, double* base, std::size_t Da) {
                                        runtime_frame7(r7[k][g], i, f, base, base + Da, base + 2 * Da, base + 3 * Da);
                                    }, t7[k]);
                                    if (!g_float_dofs) continue;
                                    for (int a = 0; a < (avx2 ? 2 : 1); ++a)
                                        time([&](std::size_t g, std::size_t i, std::size_t f, double* base, std::size_t Da) {
                                            runtime_frame7(r7[k][g], i, f, base, base + Da, base + 2 * Da, base + 3 * Da);
                                        }, t7k[k][a], false, a ? PosePath::avx2 : PosePath::portable);
                                }
                                for (std::size_t v = 0; v < configs.size(); ++v)
                                    time([&](std::size_t g, std::size_t i, std::size_t f, double* base, std::size_t Da) {
                                        runtime_frame4(r4[v][g], i, f, base, base + Da, base + 2 * Da, base + 3 * Da);
                                    }, t4[v]);
                            }
                            std::printf("#  A/B (%s): v1 cold local pose %.3f us, y %.3f us (hot %.3f); v1 with the float64 product "
                                        "(pose_of, as before): cold local pose %.3f us\n",
                                        equal ? "every frame of every variant equal to variant 1" : "MISMATCH with variant 1", t1.cold, t1.y, t1.hot,
                                        t1d.cold);
                            for (std::size_t v = 0; v < configs.size(); ++v)
                                std::printf("#    v4 lookup %d bits%s (table %zu kB): bytes %.0f, cold local pose %.3f us, y %.3f us (hot %.3f)\n",
                                            configs[v].lookup, configs[v].pairs ? ", pairs" : ", no pairs", r4[v][0].table.size() * 4 / 1024, bytes4,
                                            t4[v].cold, t4[v].y, t4[v].hot);
                            for (int k = 0; k < 3; ++k) {
                                std::printf("#    %s keys at fixed widths%s%s, lookup %d: bytes %.0f, cold local pose %.3f us, y %.3f us (hot %.3f)\n",
                                            k == 2 ? "v8 level-1 columns and" : "v7", key_centers ? ", centered" : "",
                                            k != 1 && key_escapes ? ", escapes" : "", configs[0].lookup, bytes7[k],
                                            t7[k].cold, t7[k].y, t7[k].hot);
                                if (g_float_dofs)
                                    std::printf("#      with the pose kernels: cold local pose %.3f us portable, %.3f us AVX2\n", t7k[k][0].cold,
                                                avx2 ? t7k[k][1].cold : 0.0);
                            }
                            for (std::size_t v = 0; v < quad_configs.size(); ++v)
                                std::printf("#    v9 quads S=%d, contexts row>>%d, directory levels %d, codes <= %d bits%s%s (table %zu kB): bytes %.0f (offsets %.0f, at 3 bytes an entry %.0f; code tables %.0f; at 5 bits a used symbol %.0f), "
                                            "cold local pose %.3f us (%s), y %.3f us (hot %.3f)\n",
                                            quad_configs[v][0], quad_configs[v][1], r9[v][0].stored, r9[v][0].quads.bits, r9[v][0].prefetch_clip ? ", clip prefetch" : "", r9[v][0].avx2_combine ? ", AVX2 combine" : "", r9[v][0].quads.table.size() * 2 / 1024, bytes9[v], offsets9[v], offsets9_3byte[v],
                                            [&] { double tb = 0; for (const auto& rg : r9[v]) tb += static_cast<double>(rg.quads.table_bits) / 8; return tb; }(),
                                            tables9_5bit[v], t9[v].cold, !g_float_dofs ? "library pose" : avx2 ? "AVX2 kernels" : "portable kernels", t9[v].y, t9[v].hot);
                            if (library_tier)
                                std::printf("#    library RuntimeDecoder (W %d, %s kernels): bytes %.0f, resident %zu; %zu of %zu frames' local poses differ from v9's; "
                                            "cold local pose %.3f us (v9 above: %.3f us, the same repeats)\n",
                                            W, lib_decoders.front().uses_avx2() ? "AVX2" : "portable", lib_bytes, lib_resident, lib_differ, lib_frames,
                                            lib_cold, r9.empty() ? 0.0 : t9[0].cold);
                            for (std::size_t v = 0; v < quad_configs.size(); ++v)
                                std::printf("#      v9 S=%d row>>%d: keys paired without the plan: cold %.3f us, y %.3f (hot %.3f); keys alone (plan): y %.3f (hot %.3f)\n",
                                            quad_configs[v][0], quad_configs[v][1], t9s[v].cold, t9s[v].y, t9s[v].hot, t9k[v].y, t9k[v].hot);
                            // y -> local pose alone (each group's last y, over and over), by each path.
                            if (g_float_dofs) {
                                double stage[3] = {1e300, 1e300, 1e300};
                                for (int rep = 0; rep < reps; ++rep)
                                    for (int a = 0; a < (avx2 ? 3 : 2); ++a) {
                                        const double c0 = bench::thread_cpu_seconds();
                                        for (const auto& [g, i, f] : seq) {
                                            const auto& m = models[g];
                                            double* base = scratch[g].data();
                                            local_pose_of_y(m, m.clips[i], base, ws[g], base + 4 * m.active.size(), out, static_cast<PosePath>(a),
                                                            plans[g]);
                                        }
                                        stage[a] = std::min(stage[a], (bench::thread_cpu_seconds() - c0) / static_cast<double>(seq.size()) * 1e6);
                                    }
                                // The AVX2 kernels' parts alone: the dofs, then the rotations.
                                double part[2] = {1e300, 1e300};
                                for (int rep = 0; rep < reps && avx2; ++rep)
                                    for (int a = 0; a < 2; ++a) {
                                        const double c0 = bench::thread_cpu_seconds();
                                        for (const auto& [g, i, f] : seq) {
                                            const auto& m = models[g];
                                            const auto& k = plans[g]->skeletons[m.clips[i].skeleton].kernel;
                                            double* base = scratch[g].data();
                                            if (a == 0) detail::pose_dofs_avx2(k, base, base + 4 * m.active.size());
                                            else detail::pose_rotations_avx2(k, base + 4 * m.active.size(), reinterpret_cast<double*>(out.rotations.data()));
                                        }
                                        part[a] = std::min(part[a], (bench::thread_cpu_seconds() - c0) / static_cast<double>(seq.size()) * 1e6);
                                    }
                                const auto& k0 = pose_plan(models[0]).skeletons[0].kernel;
                                // What the kernels hold beyond the stored bytes (the float basis, per skeleton its lanes,
                                // inverse weights and root).
                                std::size_t kernel_bytes = 0, skeletons = 0;
                                for (const PosePlan* plan : plans) {
                                    kernel_bytes += plan->basis.size() * sizeof(float);
                                    for (const auto& sk : plan->skeletons) {
                                        ++skeletons;
                                        kernel_bytes += sk.inverse_weights.size() * sizeof(double) + sizeof(detail::PoseRoot) + sizeof(detail::PoseKernel);
                                        for (const auto& lanes : sk.lanes) kernel_bytes += lanes.size() * sizeof(detail::PoseLanes);
                                    }
                                }
                                std::printf("#    pose kernels' resident bytes: %zu (%zu skeletons)\n", kernel_bytes, skeletons);
                                std::printf("#    y -> local pose alone: library %.3f us, kernels portable %.3f us, AVX2 %.3f us (its dofs %.3f, rotations %.3f; "
                                            "%zu groups; group 0: %d active dofs, lane groups %d / %d / %d of joints with 2 / 1 / 3 channels)\n",
                                            stage[0], stage[1], avx2 ? stage[2] : 0.0, part[0], part[1], groups.size(), k0.da, k0.groups[0], k0.groups[1], k0.groups[2]);
                                // Sequential playback: every frame of every clip in order, each decoded as a cold pose
                                // (variant 7 with escapes and variant 9's first --quads config, the fastest pose path;
                                // nothing kept between frames).
                                for (int variant = 0; variant < (r9.empty() ? 1 : 2); ++variant) {
                                double sequential = 1e300;
                                std::size_t frames = 0;
                                for (int rep = 0; rep < reps; ++rep) {
                                    frames = 0;
                                    const double c0 = bench::thread_cpu_seconds();
                                    for (std::size_t g = 0; g < groups.size(); ++g) {
                                        const auto& m = models[g];
                                        const std::size_t Da = m.active.size();
                                        double* base = scratch[g].data();
                                        for (std::size_t i = 0; i < members[g].size(); ++i)
                                            for (std::size_t f = 0; f < members[g][i]->frame_count(); ++f, ++frames) {
                                                if (variant) runtime_frame9(r9[0][g], i, f, base, base + Da, base + 2 * Da, base + 3 * Da);
                                                else runtime_frame7(r7[0][g], i, f, base, base + Da, base + 2 * Da, base + 3 * Da);
                                                local_pose_of_y(m, m.clips[i], base, ws[g], base + 4 * Da, out,
                                                                avx2 ? PosePath::avx2 : PosePath::portable, plans[g]);
                                            }
                                    }
                                    sequential = std::min(sequential, bench::thread_cpu_seconds() - c0);
                                }
                                std::printf("#    sequential playback (every frame in order, each a cold pose, %s, %s kernels): %.3f us a pose, "
                                            "%.2f M poses/s\n",
                                            variant ? "v9" : "v7 with escapes", avx2 ? "AVX2" : "portable", sequential / static_cast<double>(frames) * 1e6,
                                            static_cast<double>(frames) / sequential * 1e-6);
                                }
                            }
                        }
                        std::printf("#  stages: y from bytes %.3f us (without prefetch %.3f), y -> local pose %.3f us\n", decode_only,
                                    no_prefetch, pose_only);
                        std::printf("#  RUNTIME bytes %.0f (entries %.0f, directory %.0f, offsets %zu, tables %.0f, header %zu); "
                                    "max %.7f cm over every frame; cold local pose %.3f us (format 2: %.3f us)\n",
                                    bytes, bits / 8, directory / 8, 3 * entries, tables / 8, f2_header, worst, ours, theirs);
                    }
                    std::printf("#  static bytes by level (0 = keys):");
                    for (double b : by_level)
                        if (b > 0) std::printf(" %.0f", b);
                    std::printf("\n");
                    std::fflush(stdout);
                }
            }
        }
    }
    return 0;
}
