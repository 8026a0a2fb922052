#include "group_model.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numeric>
#include <string>

#include "byte_stream.hpp"
#include "lane4.hpp"
#include "mocapdb/core/float32.hpp"
#include "mocapdb/compression/dof_weights.hpp"
#include "mocapdb/core/error.hpp"

namespace mocapdb::packing::detail {

double step_of(int k) { return std::exp2(static_cast<double>(k) / 12.0 - 14.0); }

bool same_topology(const Skeleton& a, const Skeleton& b) {
    if (a.size() != b.size()) return false;
    for (std::size_t j = 0; j < a.size(); ++j) {
        const Joint& x = a.joint(j);
        const Joint& y = b.joint(j);
        if (x.name != y.name || x.parent != y.parent || x.channels != y.channels ||
            x.rotation_order != y.rotation_order || x.end_site != y.end_site)
            return false;
    }
    return a.motion_root() == b.motion_root();
}

std::vector<int> extra_position_columns(const Skeleton& s) {
    const std::vector<std::size_t>& chain = s.motion_root_chain();
    std::vector<int> out;
    for (std::size_t j = 0; j < s.size(); ++j) {
        if (std::find(chain.begin(), chain.end(), j) != chain.end()) continue;
        for (ChannelType c : s.joint(j).channels)
            if (!is_rotation(c)) out.push_back(s.channel_column(j, c));
    }
    return out;
}

void GroupModel::build_scan() {
    const auto d = dof_energy.size();
    const auto w = time_energy.size();
    sigma.assign(d * w, 0.0f);
    std::vector<float> raw(d * w);
    for (std::size_t r2 = 0; r2 < w; ++r2)
        for (std::size_t r1 = 0; r1 < d; ++r1)
            raw[r1 + d * r2] = std::sqrt(std::max(0.0f, dof_energy[r1]) * std::max(0.0f, time_energy[r2]));
    scan.resize(d * w);
    std::iota(scan.begin(), scan.end(), 0u);
    std::stable_sort(scan.begin(), scan.end(), [&](std::uint32_t i, std::uint32_t j) { return raw[i] > raw[j]; });
    for (std::size_t i = 0; i < scan.size(); ++i) sigma[i] = raw[scan[i]];
    levels = class_levels(sigma);
    scan_row.resize(scan.size());
    for (std::size_t i = 0; i < scan.size(); ++i)
        scan_row[i] = static_cast<std::uint16_t>(scan[i] % std::max<std::size_t>(1, d));
}

MatX GroupModel::dofs_of(const Clip& clip, const Canonicalization& canonical) const {
    const MatX poses = to_pose_vectors(clip, canonical);
    MatX x(dofs, poses.cols());
    x.topRows(pose_dofs) = poses;
    for (std::size_t e = 0; e < extra_columns.size(); ++e)
        x.row(pose_dofs + static_cast<Eigen::Index>(e)) = clip.channels.col(extra_columns[e]).transpose();
    return x;
}

MatX GroupModel::weighted_active(const Clip& clip, const SkeletonEntry& entry,
                                 const Canonicalization& canonical) const {
    const MatX x = dofs_of(clip, canonical);
    MatX out(static_cast<Eigen::Index>(active.size()), x.cols());
    for (std::size_t i = 0; i < active.size(); ++i)
        out.row(static_cast<Eigen::Index>(i)) = entry.weights[active[i]] * x.row(active[i]);
    return out;
}

void GroupModel::fold_constant_joints() {
    std::vector<bool> varies(static_cast<std::size_t>(dofs), false);
    for (int d : active) varies[static_cast<std::size_t>(d)] = true;
    for (SkeletonEntry& e : skeletons) {
        e.writer.fold_constants(varies, constant.data());
        e.active_weights.resize(active.size());
        for (std::size_t i = 0; i < active.size(); ++i) e.active_weights[i] = e.weights[active[i]];
    }
}

void GroupModel::prepare(WindowScratch& s) const {
    const std::size_t da = active.size();
    const std::size_t cells = da * static_cast<std::size_t>(window);
    s.q.resize(cells);
    s.level.resize(cells);
    s.nonzero.resize(cells);
    s.g.resize(cells);
    s.y.resize(da);
    s.x.resize(da);
    s.yb.resize(da * kFrameBlock);
    s.xb.resize(da * kFrameBlock);
    s.p.resize(static_cast<std::size_t>(dofs));
}

void GroupModel::dequantize(int step_index, const std::int32_t* q, std::size_t n, WindowScratch& s) const {
    const double step = step_of(step_index);
    const std::size_t da = std::max<std::size_t>(1, active.size());
    n = std::min(n, scan.size());
    const bool none = n == 0;
    while (n > 0 && q[n - 1] == 0) --n;  // the decoder's zeros after the coded length
    // Branch-free passes: whether a coefficient is zero is unpredictable (a branch per pass cost
    // more than the rest of the pass).
    std::uint32_t last = 0, last_row = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const std::uint32_t keep = q[i] != 0 ? ~0u : 0u;
        last = std::max(last, scan[i] & keep);
        last_row = std::max(last_row, static_cast<std::uint32_t>(scan_row[i]) & keep);
    }
    s.columns = none ? 0 : static_cast<int>(last / da) + 1;  // as ever (1 for an all-zero window)
    s.rows = n == 0 ? 0 : static_cast<int>(last_row) + 1;
    std::fill(s.g.begin(), s.g.begin() + static_cast<std::ptrdiff_t>(da * static_cast<std::size_t>(s.columns)), 0.0);
    // Zeros too (+0, as the clearing wrote; a zero past the cleared columns is never read).
    for (std::size_t i = 0; i < n; ++i) s.g[scan[i]] = q[i] * step;
}

void GroupModel::dequantize_nonzero(int step_index, const std::int32_t* q, const std::uint32_t* nonzero,
                                    std::size_t count, WindowScratch& s) const {
    const double step = step_of(step_index);
    const std::size_t da = std::max<std::size_t>(1, active.size());
    std::uint32_t last = 0, last_row = 0;
    for (std::size_t k = 0; k < count; ++k) {
        last = std::max(last, scan[nonzero[k]]);
        last_row = std::max(last_row, static_cast<std::uint32_t>(scan_row[nonzero[k]]));
    }
    // As dequantize: one column for an all-zero window, none for an empty grid.
    s.columns = scan.empty() ? 0 : static_cast<int>(last / da) + 1;
    s.rows = count == 0 ? 0 : static_cast<int>(last_row) + 1;
    std::fill(s.g.begin(), s.g.begin() + static_cast<std::ptrdiff_t>(da * static_cast<std::size_t>(s.columns)), 0.0);
    for (std::size_t k = 0; k < count; ++k) s.g[scan[nonzero[k]]] = q[nonzero[k]] * step;
}

namespace {
// Eight AVX2 registers of accumulators: with four (16 rows) each column waited for the additions'
// latency; 32 rows make x = U y of a random ASF pose 6-9 % faster (RESULTS.md, session 20).
constexpr std::size_t kBlock = 32;

// out[i] = sum over c < columns of a[i + rows·c] · w[c·stride], i < rows. Each out[i] adds its terms
// in ascending c, starting from +0: the same bits whether this runs vectorized or not, whatever
// else is decoded (no FMA contraction: -ffp-contract=off). Blocks of kBlock rows accumulate in
// registers.
template <std::size_t N>
void block_columns(const double* a, std::size_t ld, const double* w, std::size_t stride, std::size_t columns,
                   double* out) {
    double acc[N] = {};
    for (std::size_t c = 0; c < columns; ++c) {
        const double wc = w[c * stride];
        const double* col = a + c * ld;
        for (std::size_t b = 0; b < N; ++b) acc[b] += col[b] * wc;
    }
    std::copy(acc, acc + N, out);
}

// a: `rows` rows of a column-major matrix with leading dimension ld.
// block_columns for the last `rest` (< kBlock) rows in one pass over the columns (blocks of 4 and
// single rows one after the other made up to three passes, the single rows' sums serial chains).
template <std::size_t N>
void rest_columns(std::size_t rest, const double* a, std::size_t ld, const double* w, std::size_t stride,
                  std::size_t columns, double* out) {
    if constexpr (N > 0) {
        if (rest == N) return block_columns<N>(a, ld, w, stride, columns, out);
        rest_columns<N - 1>(rest, a, ld, w, stride, columns, out);
    }
}

void multiply_columns(const double* a, std::size_t rows, std::size_t ld, const double* w, std::size_t stride,
                      std::size_t columns, double* out) {
    std::size_t i = 0;
    for (; i + kBlock <= rows; i += kBlock) block_columns<kBlock>(a + i, ld, w, stride, columns, out + i);
    rest_columns<kBlock - 1>(rows - i, a + i, ld, w, stride, columns, out + i);
}
// multiply_columns for kFrameBlock weight vectors at once: out[i + out_ld·f] = sum over c of
// a[i + ld·c] · w[c·stride + f·fstride], each element summed as multiply_columns sums it (ascending
// c from +0, no contraction), so the same bits; the columns of `a` are loaded once for all frames.
// Written with vector types (the compiler's own vectorization of this nest spilled to the stack).

template <std::size_t V>  // V lanes of 4 rows
void block_frames(const double* a, std::size_t ld, const double* w, std::size_t stride, std::size_t fstride,
                  std::size_t columns, double* out, std::size_t out_ld) {
    constexpr std::size_t B = kFrameBlock;
    Lane4 acc[B][V];
    for (std::size_t f = 0; f < B; ++f)
        for (std::size_t v = 0; v < V; ++v) acc[f][v] = Lane4{0.0, 0.0, 0.0, 0.0};
    for (std::size_t c = 0; c < columns; ++c) {
        const double* col = a + c * ld;
        Lane4 x[V];
        for (std::size_t v = 0; v < V; ++v) x[v] = load4(col + 4 * v);
        for (std::size_t f = 0; f < B; ++f) {
            const double wc = w[c * stride + f * fstride];
            const Lane4 wv{wc, wc, wc, wc};
            for (std::size_t v = 0; v < V; ++v) acc[f][v] += x[v] * wv;
        }
    }
    for (std::size_t f = 0; f < B; ++f)
        for (std::size_t v = 0; v < V; ++v) std::memcpy(out + f * out_ld + 4 * v, &acc[f][v], sizeof(Lane4));
}

// The last rows % 4 (< 4) rows: every (row, frame) sum its own chain, all advanced together.
void rest_frames(const double* a, std::size_t rest, std::size_t ld, const double* w, std::size_t stride,
                 std::size_t fstride, std::size_t columns, double* out, std::size_t out_ld) {
    constexpr std::size_t B = kFrameBlock;
    double acc[3][B] = {};
    for (std::size_t c = 0; c < columns; ++c)
        for (std::size_t f = 0; f < B; ++f) {
            const double wc = w[c * stride + f * fstride];
            for (std::size_t i = 0; i < rest; ++i) acc[i][f] += a[i + c * ld] * wc;
        }
    for (std::size_t f = 0; f < B; ++f)
        for (std::size_t i = 0; i < rest; ++i) out[i + f * out_ld] = acc[i][f];
}

void multiply_frames(const double* a, std::size_t rows, std::size_t ld, const double* w, std::size_t stride,
                     std::size_t fstride, std::size_t columns, double* out, std::size_t out_ld) {
    std::size_t i = 0;
    for (; i + 8 <= rows; i += 8) block_frames<2>(a + i, ld, w, stride, fstride, columns, out + i, out_ld);
    for (; i + 4 <= rows; i += 4) block_frames<1>(a + i, ld, w, stride, fstride, columns, out + i, out_ld);
    if (i < rows) rest_frames(a + i, rows - i, ld, w, stride, fstride, columns, out + i, out_ld);
}
}  // namespace

void GroupModel::unweight(double* x, const SkeletonEntry& entry, double* p) const {
    const std::size_t da = active.size();
    const double* w = entry.active_weights.data();
    for (std::size_t i = 0; i < da; ++i) x[i] = x[i] / w[i];  // contiguous: vector divisions, same bits
    for (std::size_t i = 0; i < da; ++i) p[active[i]] = x[i];
}

void GroupModel::frames_pose(const ClipEntry& clip, const double* g, int columns, int rows, int t0, WindowScratch& s,
                             double* p) const {
    const std::size_t da = active.size();
    const auto W = static_cast<std::size_t>(window);
    const auto r = static_cast<std::size_t>(rows);
    // As frame_pose, for frames t0.. at once: Y = G [v_t0 ...] (rows r of each y; the rest are
    // zero and unused), then X = U Y.
    multiply_frames(g, r, da, time_basis.data() + t0, W, 1, static_cast<std::size_t>(columns), s.yb.data(), da);
    multiply_frames(dof_basis.data(), da, da, s.yb.data(), 1, da, r, s.xb.data(), da);
    const SkeletonEntry& entry = skeletons[clip.skeleton];
    const auto D = static_cast<std::size_t>(dofs);
    for (std::size_t f = 0; f < static_cast<std::size_t>(kFrameBlock); ++f) {
        double* pf = p + f * D;
        double* x = s.xb.data() + f * da;
        std::copy(constant.begin(), constant.end(), pf);
        unweight(x, entry, pf);
    }
}

void GroupModel::frame_row(const ClipEntry& clip, const double* g, int columns, int rows, int t, WindowScratch& s,
                           double* row) const {
    frame_pose(clip, g, columns, rows, t, s, s.p.data());
    row_of(clip, s.p.data(), row);
}

void GroupModel::row_of(const ClipEntry& clip, const double* p, double* row) const {
    const SkeletonEntry& entry = skeletons[clip.skeleton];
    entry.writer.write(p, clip.placement, row);
    for (std::size_t e = 0; e < extra_columns.size(); ++e)
        row[extra_columns[e]] = p[static_cast<std::size_t>(pose_dofs) + e];
}

void GroupModel::local_of(const ClipEntry& clip, const double* p, LocalPose& out) const {
    const SkeletonEntry& entry = skeletons[clip.skeleton];
    out.rotations.resize(entry.writer.size());
    out.translations.resize(entry.writer.size());
    entry.writer.write_local(p, clip.placement, out);
    for (std::size_t e = 0; e < extra_columns.size(); ++e)
        entry.writer.set_position(extra_columns[e], p[static_cast<std::size_t>(pose_dofs) + e], out);
}

void GroupModel::local_of_row(const ClipEntry& clip, const double* row, LocalPose& out) const {
    const Skeleton& k = *skeletons[clip.skeleton].skeleton;
    out.rotations.resize(k.size());
    out.translations.resize(k.size());
    for (std::size_t j = 0; j < k.size(); ++j) {
        out.rotations[j] = k.local_rotation(j, row);
        out.translations[j] = k.local_translation(j, row);
    }
}

void GroupModel::frame_pose(const ClipEntry& clip, const double* g, int columns, int rows, int t, WindowScratch& s,
                            double* p) const {
    const std::size_t da = active.size();
    const auto W = static_cast<std::size_t>(window);
    double* y = s.y.data();
    // y = G v_t (v_t = row t of the time basis), then x = U y. Each output element sums its terms in
    // ascending column order, in blocks of kBlock elements held in registers; the result does not
    // depend on vectorization or on what else is decoded (no FMA contraction: -ffp-contract=off).
    const double* v = time_basis.data() + t;
    // Rows of g past `rows` are zero: so are those elements of y, and their terms in x are skipped.
    const auto r = static_cast<std::size_t>(rows);
    multiply_columns(g, r, da, v, W, static_cast<std::size_t>(columns), y);
    pose_of(clip, y, rows, s, p);
}

void GroupModel::pose_of(const ClipEntry& clip, const double* y, int rows, WindowScratch& s, double* p) const {
    const std::size_t da = active.size();
    double* x = s.x.data();
    multiply_columns(dof_basis.data(), da, da, y, 1, static_cast<std::size_t>(rows), x);
    std::copy(constant.begin(), constant.end(), p);
    unweight(x, skeletons[clip.skeleton], p);
}

WindowScratch& thread_scratch() {
    thread_local WindowScratch scratch;
    return scratch;
}

void GroupModel::reconstruct(const ClipEntry& clip, int step_index, const std::vector<std::int32_t>& q, int count,
                             WindowScratch& s, FrameMatrix& out_rows) const {
    prepare(s);
    dequantize(step_index, q.data(), q.size(), s);
    out_rows.resize(count, static_cast<Eigen::Index>(skeletons[clip.skeleton].skeleton->channel_count()));
    for (int t = 0; t < count; ++t) frame_row(clip, s.g.data(), s.columns, s.rows, t, s, out_rows.row(t).data());
}

namespace {
VecX weights_of(const Skeleton& s, int pose_dofs, std::size_t extra) {
    const VecX w = compression::position_error_weights(s);
    VecX out(pose_dofs + static_cast<Eigen::Index>(extra));
    // Rotations: the bound's levers (dof_weights.hpp), relative to the root translation's weight.
    // Translations (root, and non-root position channels): kTranslationWeight. A translation error
    // moves every joint below by the same vector, where rotation errors along a chain partly cancel;
    // the bound treats both alike. Measured on both shared folders (docs/packing.md): 3 gives 7-10%
    // fewer bytes than 1 at the same guaranteed max error; 2-5 are within 1% of it.
    out.head(pose_dofs) = w / w[0];
    out.head(3).setConstant(kTranslationWeight);
    out.tail(static_cast<Eigen::Index>(extra)).setConstant(kTranslationWeight);
    return out;
}
}  // namespace

std::vector<std::uint8_t> encode_basis(const MatX& basis) {
    std::vector<std::int32_t> q(static_cast<std::size_t>(basis.size()));
    for (Eigen::Index i = 0; i < basis.size(); ++i)
        q[static_cast<std::size_t>(i)] = static_cast<std::int32_t>(std::lround(basis.data()[i] / kBasisStep));
    const std::vector<std::uint8_t> classes(q.size(), std::uint8_t(kClassBias + 12));
    const std::vector<std::uint32_t> scan = identity_scan(q.size());
    return encode_coefficients(q, classes, ScanGrid{&scan, static_cast<int>(basis.rows())}, ContextSet());
}

MatX decode_basis(const std::uint8_t* data, std::size_t size, Eigen::Index n) {
    const std::vector<std::uint8_t> classes(static_cast<std::size_t>(n * n), std::uint8_t(kClassBias + 12));
    std::vector<std::int32_t> q;
    const std::vector<std::uint32_t> scan = identity_scan(classes.size());
    decode_coefficients(data, size, classes, ScanGrid{&scan, static_cast<int>(n)}, ContextSet(), q);
    MatX out(n, n);
    for (Eigen::Index i = 0; i < out.size(); ++i) out.data()[i] = q[static_cast<std::size_t>(i)] * kBasisStep;
    return out;
}

SkeletonEntry make_entry(const Skeleton& source, int pose_dofs, std::size_t extra) {
    std::vector<Joint> joints = source.joints();
    std::vector<std::array<float, 4>> axes(joints.size());
    for (std::size_t k = 0; k < joints.size(); ++k) {
        round_entries_to_float32(joints[k].offset);  // not .cast<float>(): see core/float32.hpp
        for (int a = 0; a < 4; ++a) axes[k][static_cast<std::size_t>(a)] = to_float32(joints[k].axis.coeffs()[a]);
    }
    SourceUnits units = source.source_units();
    units.cm_per_unit = float32_value(units.cm_per_unit);
    std::array<float, 3> forward{};
    for (int a = 0; a < 3; ++a) forward[static_cast<std::size_t>(a)] = to_float32(source.forward()[a]);
    return stored_entry(std::move(joints), units, forward, axes, source.position_channels(), source.motion_root(),
                        pose_dofs, extra);
}

SkeletonEntry stored_entry(std::vector<Joint> joints, const SourceUnits& units, const std::array<float, 3>& forward,
                           const std::vector<std::array<float, 4>>& axes, PositionChannels positions,
                           std::size_t motion_root, int pose_dofs, std::size_t extra) {
    for (std::size_t k = 0; k < joints.size(); ++k) {
        for (int a = 0; a < 4; ++a) joints[k].axis.coeffs()[a] = axes[k][static_cast<std::size_t>(a)];
        joints[k].axis.normalize();
    }
    SkeletonEntry e;
    e.skeleton = std::make_shared<const Skeleton>(std::move(joints), units, Vec3(forward[0], forward[1], forward[2]),
                                                  positions, motion_root);
    e.weights = weights_of(*e.skeleton, pose_dofs, extra);
    e.writer = ChannelWriter(*e.skeleton);
    e.stored_axes = axes;
    e.stored_forward = forward;
    return e;
}

void GroupModel::write_clip_table(ByteWriter& w) const {
    for (const ClipEntry& c : clips) {
        w.varint(c.skeleton);
        w.varint(c.frames);
        w.f32(c.canonical.translation.x());
        w.f32(c.canonical.translation.z());
        w.f32(c.canonical.yaw);
    }
}

void GroupModel::write_header(std::vector<std::uint8_t>& out, ByteParts* parts) const {
    ByteWriter w(out);
    // Each section's bytes, named as PackStats::parts reports them.
    std::size_t section_start = out.size();
    auto section = [&](const char* name) {
        if (parts) add_part(*parts, name, out.size() - section_start);
        section_start = out.size();
    };
    w.raw<std::uint32_t>(0x5042444Du);  // "MDBP"
    w.u8(runtime ? kRuntimeFormatVersion : kFormatVersion);
    w.varint(clips.size());
    if (clips.empty()) return section("header");
    w.raw<double>(frame_rate);
    if (!runtime) w.varint(static_cast<std::uint64_t>(window));
    section("header");
    // Topology (from the first skeleton).
    const Skeleton& s = *skeletons.front().skeleton;
    w.varint(s.size());
    for (const Joint& j : s.joints()) {
        w.text(j.name);
        w.varint(static_cast<std::uint64_t>(j.parent + 1));
        w.u8(static_cast<std::uint8_t>(j.channels.size() | (j.end_site ? 0x80 : 0)));
        for (ChannelType c : j.channels) w.u8(static_cast<std::uint8_t>(c));
        w.u8(static_cast<std::uint8_t>(j.rotation_order));
    }
    w.varint(s.motion_root());
    section("topology");
    w.varint(skeletons.size());
    for (const SkeletonEntry& e : skeletons) {
        const Skeleton& k = *e.skeleton;
        w.f32(k.source_units().cm_per_unit);
        // Bit 0: angles in degrees; bit 1: position channels replace OFFSET (else they add to it).
        const bool replaces = k.position_channels() == PositionChannels::replace_offset;
        w.u8(static_cast<std::uint8_t>((k.source_units().degrees ? 1 : 0) | (replaces ? 2 : 0)));
        for (float c : e.stored_forward) w.f32(c);
        const std::array<float, 4> identity{0.0f, 0.0f, 0.0f, 1.0f};  // x, y, z, w
        bool any_axis = false;
        for (const auto& a : e.stored_axes) any_axis = any_axis || a != identity;
        w.u8(any_axis ? 1 : 0);
        for (std::size_t j = 0; j < k.size(); ++j) {
            for (int a = 0; a < 3; ++a) w.f32(k.joint(j).offset[a]);
            if (any_axis)
                for (float c : e.stored_axes[j]) w.f32(c);
        }
    }
    section("skeletons");
    std::vector<std::uint8_t> mask((static_cast<std::size_t>(dofs) + 7) / 8, 0);
    for (int d : active) mask[static_cast<std::size_t>(d) / 8] |= static_cast<std::uint8_t>(1u << (d % 8));
    w.bytes(mask);
    std::size_t next = 0;
    for (int d = 0; d < dofs; ++d) {
        if (next < active.size() && active[next] == d) {
            ++next;
            continue;
        }
        w.raw<double>(constant[static_cast<std::size_t>(d)]);
    }
    section("constant_dofs");
    for (const MatX* basis : {&dof_basis, &time_basis}) {
        if (runtime && basis == &time_basis) continue;
        const std::vector<std::uint8_t> coded = encode_basis(*basis);
        w.varint(coded.size());
        w.bytes(coded);
    }
    if (runtime) {
        section("bases");
        write_clip_table(w);
        section("clip_table");
        w.raw<std::uint32_t>(body_crc);
        return section("checksum");
    }
    for (float v : dof_energy) w.raw<float>(v);
    for (float v : time_energy) w.raw<float>(v);
    section("bases");
    // Trained contexts: a bit mask of those used, then 8 bits each (to_contexts' precision).
    std::vector<std::uint8_t> used((contexts.p.size() + 7) / 8, 0);
    for (std::size_t i = 0; i < contexts.p.size(); ++i)
        if (contexts.p[i] != kProbabilityHalf) used[i / 8] |= static_cast<std::uint8_t>(1u << (i % 8));
    w.bytes(used);
    for (BitContext c : contexts.p)
        if (c != kProbabilityHalf) w.u8(static_cast<std::uint8_t>(c >> (kProbabilityBits - 8)));
    section("contexts");
    write_clip_table(w);
    section("clip_table");
    for (const WindowEntry& e : windows) {
        w.u8(e.step);
        w.varint(e.size);
    }
    section("window_table");
}

std::uint64_t GroupModel::read_clip_table(ByteReader& r, std::uint64_t clip_count) {
    clips.assign(clip_count, ClipEntry{});
    std::uint64_t window_total = 0;
    for (ClipEntry& c : clips) {
        c.skeleton = static_cast<std::uint32_t>(r.varint());
        if (c.skeleton >= skeletons.size()) throw Error("packed group: bad skeleton index");
        c.frames = r.varint();
        if (c.frames == 0) throw Error("packed group: clip without frames");
        const double tx = r.f32();  // one read per statement: argument order is unspecified
        const double tz = r.f32();
        Canonicalization canonical;
        canonical.translation = Vec3(tx, 0.0, tz);
        canonical.yaw = r.f32();
        c.set_canonical(canonical);
        c.first_window = window_total;
        if (window > 0)
            window_total += (c.frames + static_cast<std::uint64_t>(window) - 1) / static_cast<std::uint64_t>(window);
    }
    return window_total;
}

std::size_t GroupModel::read_header(const std::uint8_t* data, std::size_t size) {
    ByteReader r(data, size);
    if (r.raw<std::uint32_t>() != 0x5042444Du) throw Error("packed group: bad magic");
    const auto version = r.u8();
    if (version < kOldestFormatVersion || version > kRuntimeFormatVersion)
        throw Error("packed group: version " + std::to_string(version) + ", this build reads " +
                    std::to_string(kOldestFormatVersion) + " to " + std::to_string(kRuntimeFormatVersion));
    runtime = version == kRuntimeFormatVersion;
    const auto clip_count = r.varint();
    if (clip_count == 0) return r.position();
    frame_rate = r.raw<double>();
    if (!(frame_rate > 0.0) || !std::isfinite(frame_rate)) throw Error("packed group: bad frame rate");
    window = runtime ? 0 : static_cast<int>(r.varint());
    if (!runtime && (window < 2 || window > 256)) throw Error("packed group: bad window length");
    const auto joint_count = r.varint();
    if (joint_count == 0 || joint_count > 100000) throw Error("packed group: bad joint count");
    std::vector<Joint> topology(joint_count);
    for (Joint& j : topology) {
        j.name = r.text();
        j.parent = static_cast<int>(r.varint()) - 1;
        const auto flags = r.u8();
        j.end_site = (flags & 0x80) != 0;
        for (int c = 0; c < (flags & 0x7F); ++c) {
            const auto t = r.u8();
            if (t > 5) throw Error("packed group: bad channel type");
            j.channels.push_back(static_cast<ChannelType>(t));
        }
        j.rotation_order = static_cast<EulerOrder>(r.u8());
    }
    const std::uint64_t motion_root = version >= 3 ? r.varint() : 0;
    if (motion_root >= joint_count) throw Error("packed group: bad motion root");
    // The layout (pose dofs, extra position channels) depends on the topology alone.
    std::shared_ptr<const Skeleton> layout;
    try {
        layout =
            std::make_shared<const Skeleton>(topology, SourceUnits{}, Vec3::UnitZ(), PositionChannels::add_to_offset,
                                             static_cast<std::size_t>(motion_root));
    } catch (const InvalidArgument& e) {
        throw Error(std::string("packed group: bad topology: ") + e.what());
    }
    pose_dofs = static_cast<int>(PoseLayout(*layout).dof_count());
    extra_columns = extra_position_columns(*layout);
    const std::size_t extra = extra_columns.size();
    const auto skeleton_count = r.varint();
    if (skeleton_count == 0 || skeleton_count > clip_count) throw Error("packed group: bad skeleton count");
    skeletons.clear();
    for (std::uint64_t k = 0; k < skeleton_count; ++k) {
        SourceUnits units;
        units.cm_per_unit = r.f32();
        const auto unit_flags = r.u8();
        if (version >= 3 && unit_flags > 3) throw Error("packed group: bad skeleton flags");
        units.degrees = (version >= 3 ? unit_flags & 1 : unit_flags) != 0;
        const PositionChannels positions =
            version >= 3 && (unit_flags & 2) != 0 ? PositionChannels::replace_offset : PositionChannels::add_to_offset;
        std::array<float, 3> forward{};
        for (float& c : forward) c = static_cast<float>(r.f32());  // exact: read as float32
        const bool any_axis = r.u8() != 0;
        std::vector<Joint> joints = topology;
        std::vector<std::array<float, 4>> axes(joints.size(), {0.0f, 0.0f, 0.0f, 1.0f});
        for (std::size_t j = 0; j < joints.size(); ++j) {
            for (int a = 0; a < 3; ++a) joints[j].offset[a] = r.f32();
            if (any_axis)
                for (float& c : axes[j]) c = static_cast<float>(r.f32());  // exact: read as float32
        }
        // The values the encoder's skeleton was built from: the same skeleton, to the bit.
        skeletons.push_back(stored_entry(std::move(joints), units, forward, axes, positions,
                                         static_cast<std::size_t>(motion_root), pose_dofs, extra));
    }
    dofs = pose_dofs + static_cast<int>(extra);
    active.clear();
    constant.assign(static_cast<std::size_t>(dofs), 0.0);
    std::vector<std::uint8_t> mask((static_cast<std::size_t>(dofs) + 7) / 8);
    for (auto& b : mask) b = r.u8();
    for (int d = 0; d < dofs; ++d) {
        if (mask[static_cast<std::size_t>(d) / 8] & (1u << (d % 8))) active.push_back(d);
        else constant[static_cast<std::size_t>(d)] = r.raw<double>();
    }
    fold_constant_joints();
    const auto da = static_cast<Eigen::Index>(active.size());
    time_basis.resize(0, 0);
    for (MatX* basis : {&dof_basis, &time_basis}) {
        if (runtime && basis == &time_basis) continue;
        const Eigen::Index n = basis == &dof_basis ? da : window;
        const auto coded = r.varint();
        if (coded > r.size() - r.position()) throw Error("packed group: truncated basis");
        *basis = decode_basis(data + r.position(), coded, n);
        for (std::uint64_t i = 0; i < coded; ++i) r.u8();
    }
    if (runtime) {
        dof_energy = {};
        time_energy = {};
        scan = {};
        scan_row = {};
        sigma = {};
        levels = {};
        contexts = ContextSet{};
        read_clip_table(r, clip_count);
        windows = {};
        body_crc = r.raw<std::uint32_t>();
        return r.position();
    }
    dof_energy.resize(active.size());
    for (float& v : dof_energy) v = r.raw<float>();
    time_energy.resize(static_cast<std::size_t>(window));
    for (float& v : time_energy) v = r.raw<float>();
    {
        std::vector<std::uint8_t> used((contexts.p.size() + 7) / 8);
        for (auto& b : used) b = r.u8();
        for (std::size_t i = 0; i < contexts.p.size(); ++i)
            contexts.p[i] = (used[i / 8] & (1u << (i % 8)))
                                ? static_cast<BitContext>(static_cast<unsigned>(r.u8()) << (kProbabilityBits - 8))
                                : kProbabilityHalf;
    }
    build_scan();
    const std::uint64_t window_total = read_clip_table(r, clip_count);
    windows.assign(window_total, WindowEntry{});
    std::uint64_t offset = 0;
    for (WindowEntry& e : windows) {
        e.step = r.u8();
        e.size = static_cast<std::uint32_t>(r.varint());
        e.offset = offset;
        offset += e.size;
    }
    if (offset != size - r.position()) throw Error("packed group: payload size does not match its table");
    return r.position();
}

}  // namespace mocapdb::packing::detail
