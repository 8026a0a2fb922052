#include "mocapdb/gp/hierarchical_gp.hpp"

#include <cmath>
#include <random>
#include <thread>

#include <Eigen/Cholesky>

#include "block_low_rank.hpp"
#include "mocapdb/core/error.hpp"

namespace mocapdb::gp {

namespace {

// The two factorizations (A and C) are independent: on two threads when asked.
template <class F, class G>
void run_both(bool parallel, F& first, G& second) {
    if (parallel) {
        std::thread worker(second);
        first();
        worker.join();
    } else {
        first();
        second();
    }
}

constexpr double kLog2Pi = 1.8378770664093454836;

using Index = Eigen::Index;

/// Output-major vector of a D by T matrix: y[d·T + t] = Y(d, t).
VecX vec_output_major(const MatX& y) {
    VecX v(y.size());
    const Index t = y.cols();
    for (Index d = 0; d < y.rows(); ++d) v.segment(d * t, t) = y.row(d).transpose();
    return v;
}

MatX unvec_output_major(const VecX& v, Index d, Index t) {
    MatX y(d, t);
    for (Index i = 0; i < d; ++i) y.row(i) = v.segment(i * t, t).transpose();
    return y;
}

/// In-place Cholesky of the SPD matrix m (lower triangle); false when not positive definite.
bool factor_in_place(MatX& m, double& out_log_det) {
    Eigen::LLT<Eigen::Ref<MatX>> llt(m);
    if (llt.info() != Eigen::Success) return false;
    const auto diag = m.diagonal();
    for (Index i = 0; i < diag.size(); ++i)
        if (!(diag[i] > 0.0) || !std::isfinite(diag[i])) return false;
    out_log_det = 2.0 * diag.array().log().sum();
    return std::isfinite(out_log_det);
}

/// Replaces the Cholesky factor L held in m's lower triangle by the full symmetric inverse (L Lᵀ)⁻¹.
/// Blocked: X = L⁻¹ column block by column block (each a triangular solve restricted to the rows at and
/// below the block, ≈ n³/3 flops), written over L; then (L Lᵀ)⁻¹ = Xᵀ X one column block of its upper
/// triangle at a time (≈ n³/3 flops), also in place; finally the lower triangle is mirrored.
void invert_from_factor_in_place(MatX& m) {
    const Index n = m.rows();
    const Index bs = 96;
    MatX rhs;
    for (Index j0 = 0; j0 < n; j0 += bs) {
        const Index bb = std::min(bs, n - j0);
        const Index rows = n - j0;
        rhs.setZero(rows, bb);
        rhs.topRows(bb).setIdentity();
        m.block(j0, j0, rows, rows).triangularView<Eigen::Lower>().solveInPlace(rhs);
        m.block(j0, j0, rows, bb) = rhs;  // upper part of the diagonal block becomes 0 (exact)
    }
    // Now the lower triangle (with diagonal) of m holds X = L⁻¹ (the strict upper parts of the diagonal
    // blocks are exact zeros; the rest of the upper triangle is stale). Inverse = Xᵀ X, its upper
    // triangle one column block J = [j0, j1) at a time: Inv(0:j1, J) = X(j0:n, 0:j1)ᵀ X(j0:n, J).
    // Block J only reads rows ≥ j0 and writes rows < j1 of column block J; later blocks read rows ≥ j1
    // only, so the update is safe in place in increasing J.
    MatX tmp;
    for (Index j0 = 0; j0 < n; j0 += bs) {
        const Index bb = std::min(bs, n - j0);
        const Index j1 = j0 + bb;
        const Index rows = n - j0;
        tmp.noalias() = m.block(j0, 0, rows, j1).transpose() * m.block(j0, j0, rows, bb).triangularView<Eigen::Lower>();
        m.block(0, j0, j1, bb) = tmp;
    }
    for (Index j = 0; j < n; ++j)
        for (Index i = j + 1; i < n; ++i) m(i, j) = m(j, i);
}

MatX kron(const MatX& a, const MatX& b) {
    MatX k(a.rows() * b.rows(), a.cols() * b.cols());
    for (Index j = 0; j < a.cols(); ++j)
        for (Index i = 0; i < a.rows(); ++i) k.block(i * b.rows(), j * b.cols(), b.rows(), b.cols()) = a(i, j) * b;
    return k;
}

/// Flat indices (output-major over the shared times) of one child's observed values.
std::vector<Index> observed_indices(const HgpData& data, std::size_t child) {
    const Index t = static_cast<Index>(data.frames());
    std::vector<Index> idx;
    for (Index d = 0; d < static_cast<Index>(data.outputs()); ++d)
        for (Index f = 0; f < t; ++f)
            if (data.is_observed(child, static_cast<std::size_t>(f))) idx.push_back(d * t + f);
    return idx;
}

struct DenseLayout {
    std::vector<std::size_t> child;  ///< owning child of each observed value
    std::vector<Index> flat;         ///< its index in the child's output-major vector
    VecX y;
};

DenseLayout dense_layout(const HgpData& data) {
    DenseLayout l;
    std::vector<double> y;
    for (std::size_t r = 0; r < data.child_count(); ++r) {
        const VecX v = vec_output_major(data.children[r]);
        for (Index i : observed_indices(data, r)) {
            l.child.push_back(r);
            l.flat.push_back(i);
            y.push_back(v[i]);
        }
    }
    l.y = Eigen::Map<const VecX>(y.data(), static_cast<Index>(y.size()));
    return l;
}

/// Σ over the observed values from per-child blocks: kg for every pair, kf (+ noise diag) within a child.
MatX assemble_dense(const DenseLayout& l, const MatX* kg, const MatX* kf, const VecX* noise_flat) {
    const Index n = static_cast<Index>(l.flat.size());
    MatX s = MatX::Zero(n, n);
    for (Index j = 0; j < n; ++j)
        for (Index i = 0; i < n; ++i) {
            double v = 0.0;
            if (kg) v += (*kg)(l.flat[i], l.flat[j]);
            if (l.child[i] == l.child[j]) {
                if (kf) v += (*kf)(l.flat[i], l.flat[j]);
                if (noise_flat && i == j) v += (*noise_flat)[l.flat[i]];
            }
            s(i, j) = v;
        }
    return s;
}

/// The derivative matrices (D·T square) of an LMC term's covariance w.r.t. each of its parameters,
/// in append_parameters order.
std::vector<MatX> term_derivatives(const LmcTerm& term, const VecX& times) {
    std::vector<MatX> out;
    const Index d = static_cast<Index>(term.outputs());
    const MatX b = term.coregionalization();
    const MatX k = kernel_matrix(term.kernel, term.log_lengthscale, times, times);
    out.push_back(kron(b, kernel_matrix_dlog_lengthscale(term.kernel, term.log_lengthscale, times, times)));
    for (Index j = 0; j < term.W.cols(); ++j)
        for (Index i = 0; i < d; ++i) {
            MatX db = MatX::Zero(d, d);
            db.row(i) += term.W.col(j).transpose();
            db.col(i) += term.W.col(j);
            out.push_back(kron(db, k));
        }
    for (Index i = 0; i < d; ++i) {
        MatX db = MatX::Zero(d, d);
        db(i, i) = std::exp(term.log_kappa[i]);
        out.push_back(kron(db, k));
    }
    return out;
}

VecX flat_noise(const VecX& noise, Index t) {
    VecX v(noise.size() * t);
    for (Index d = 0; d < noise.size(); ++d) v.segment(d * t, t).setConstant(noise[d]);
    return v;
}

LikelihoodValue dense_likelihood(const HgpModel& model, const HgpData& data, bool with_gradient) {
    LikelihoodValue out;
    out.path = LikelihoodPath::Dense;
    const Index t = static_cast<Index>(data.frames());
    const DenseLayout l = dense_layout(data);
    const MatX kf = lmc_covariance(model.child, data.times, data.times);
    MatX kg;
    if (model.hierarchical) kg = lmc_covariance(model.parent, data.times, data.times);
    const VecX noise = flat_noise(model.noise_variance(), t);
    MatX sigma = assemble_dense(l, model.hierarchical ? &kg : nullptr, &kf, &noise);
    Eigen::LLT<MatX> llt(sigma);
    if (llt.info() != Eigen::Success) {
        out.message = "dense covariance is not positive definite";
        return out;
    }
    const VecX alpha = llt.solve(l.y);
    const double log_det = 2.0 * MatX(llt.matrixL()).diagonal().array().log().sum();
    const double n = static_cast<double>(l.y.size());
    out.log_likelihood = -0.5 * l.y.dot(alpha) - 0.5 * log_det - 0.5 * n * kLog2Pi;
    if (!std::isfinite(out.log_likelihood)) {
        out.message = "non-finite dense log likelihood";
        return out;
    }
    out.ok = true;
    if (!with_gradient) return out;
    // W = α αᵀ − Σ⁻¹; ∂ log p/∂θ = ½ tr(W ∂Σ/∂θ) = ½ Σ_ij W_ij ∂Σ_ij.
    MatX w = alpha * alpha.transpose() - llt.solve(MatX::Identity(sigma.rows(), sigma.cols()));
    out.gradient = VecX::Zero(static_cast<Index>(model.parameter_count()));
    Index o = 0;
    for (const auto& term : model.child.terms)
        for (const MatX& dk : term_derivatives(term, data.times))
            out.gradient[o++] = 0.5 * w.cwiseProduct(assemble_dense(l, nullptr, &dk, nullptr)).sum();
    if (model.hierarchical)
        for (const auto& term : model.parent.terms)
            for (const MatX& dk : term_derivatives(term, data.times))
                out.gradient[o++] = 0.5 * w.cwiseProduct(assemble_dense(l, &dk, nullptr, nullptr)).sum();
    for (Index d = 0; d < static_cast<Index>(model.outputs()); ++d) {
        VecX dn = VecX::Zero(noise.size());
        dn.segment(d * t, t).setConstant(std::exp(model.log_noise[d]));
        const MatX zero = MatX::Zero(noise.size(), noise.size());
        out.gradient[o++] = 0.5 * w.cwiseProduct(assemble_dense(l, nullptr, &zero, &dn)).sum();
    }
    return out;
}

/// Structured likelihood (every child complete). See the header for the decomposition.
LikelihoodValue structured_likelihood(const HgpModel& model, const HgpData& data, bool with_gradient, int threads) {
    LikelihoodValue out;
    out.path = LikelihoodPath::Structured;
    const Index t = static_cast<Index>(data.frames());
    const Index d = static_cast<Index>(data.outputs());
    const Index n = d * t;
    const Index r = static_cast<Index>(data.child_count());
    const double rd = static_cast<double>(r);
    MatX ys(n, r);
    for (Index c = 0; c < r; ++c) ys.col(c) = vec_output_major(data.children[static_cast<std::size_t>(c)]);

    MatX a = lmc_covariance(model.child, data.times, data.times);
    a.diagonal() += flat_noise(model.noise_variance(), t);
    const bool hier = model.hierarchical;

    // Hierarchical: C = A + R·B with z = √R·ȳ; A-part uses deviations E (n by R). MOA: A-part uses Y.
    MatX c;
    VecX z;
    MatX e;
    if (hier) {
        c = a;
        c.noalias() += rd * lmc_covariance(model.parent, data.times, data.times);
        const VecX mean = ys.rowwise().mean();
        z = std::sqrt(rd) * mean;
        e = ys.colwise() - mean;
    } else {
        e = ys;
    }
    const double a_count = hier ? rd - 1.0 : rd;  // number of independent N(·; 0, A) terms

    bool ok_a = false, ok_c = !hier;
    double logdet_a = 0.0, logdet_c = 0.0, quad_a = 0.0, quad_c = 0.0;
    MatX pa;   // A⁻¹ E
    VecX alpha_c;  // C⁻¹ z
    auto work_a = [&]() {
        ok_a = factor_in_place(a, logdet_a);
        if (!ok_a) return;
        pa = e;
        a.triangularView<Eigen::Lower>().solveInPlace(pa);  // L⁻¹ E
        quad_a = pa.squaredNorm();
        a.triangularView<Eigen::Lower>().transpose().solveInPlace(pa);  // A⁻¹ E
        if (with_gradient) invert_from_factor_in_place(a);
    };
    auto work_c = [&]() {
        if (!hier) return;
        ok_c = factor_in_place(c, logdet_c);
        if (!ok_c) return;
        alpha_c = z;
        c.triangularView<Eigen::Lower>().solveInPlace(alpha_c);
        quad_c = alpha_c.squaredNorm();
        c.triangularView<Eigen::Lower>().transpose().solveInPlace(alpha_c);
        if (with_gradient) invert_from_factor_in_place(c);
    };
    run_both(threads >= 2 && hier, work_a, work_c);
    if (!ok_a || !ok_c) {
        out.message = !ok_a ? "child covariance K_f + noise is not positive definite"
                            : "K_f + noise + R·K_g is not positive definite";
        return out;
    }
    out.log_likelihood = -0.5 * (quad_a + a_count * logdet_a) - 0.5 * rd * static_cast<double>(n) * kLog2Pi;
    if (hier) out.log_likelihood += -0.5 * (quad_c + logdet_c);
    if (!std::isfinite(out.log_likelihood)) {
        out.message = "non-finite structured log likelihood";
        return out;
    }
    out.ok = true;
    if (!with_gradient) return out;

    // G_f = W_C + W_A (differential through A), G_g = R·W_C (through B), with
    // W_C = α αᵀ − C⁻¹, W_A = (A⁻¹E)(A⁻¹E)ᵀ − count·A⁻¹. `a` and `c` now hold A⁻¹ and C⁻¹.
    MatX& gf = a;
    gf *= -a_count;
    gf.noalias() += pa * pa.transpose();
    if (hier) {
        gf -= c;
        gf.noalias() += alpha_c * alpha_c.transpose();
        MatX& gg = c;
        gg = -rd * c;
        gg.noalias() += rd * alpha_c * alpha_c.transpose();
    }
    out.gradient = VecX::Zero(static_cast<Index>(model.parameter_count()));
    const std::size_t parent_offset = model.child.parameter_count();
    auto grad_child = [&]() {
        std::size_t o = 0;
        for (const auto& term : model.child.terms) o = lmc_term_gradient(term, gf, data.times, o, out.gradient);
        o = parent_offset + (hier ? model.parent.parameter_count() : 0);
        for (Index i = 0; i < d; ++i)
            out.gradient[static_cast<Index>(o) + i] =
                0.5 * gf.diagonal().segment(i * t, t).sum() * std::exp(model.log_noise[i]);
    };
    auto grad_parent = [&]() {
        if (!hier) return;
        std::size_t o = parent_offset;
        for (const auto& term : model.parent.terms) o = lmc_term_gradient(term, c, data.times, o, out.gradient);
    };
    run_both(threads >= 2 && hier, grad_child, grad_parent);
    return out;
}

/// Kernel factors of every term of both layers (child terms first), computed once per evaluation.
struct LayerFactors {
    std::vector<detail::KernelFactor> child, parent;
};

LayerFactors layer_factors(const HgpModel& model, const VecX& times) {
    LayerFactors f;
    for (const auto& term : model.child.terms) f.child.push_back(detail::factor_kernel(term, times));
    if (model.hierarchical)
        for (const auto& term : model.parent.terms) f.parent.push_back(detail::factor_kernel(term, times));
    return f;
}

/// The weighted terms of A = K_f (+ noise) and of C = A + R·K_g.
std::vector<detail::WeightedTerm> terms_a(const HgpModel& model, const LayerFactors& f) {
    std::vector<detail::WeightedTerm> out;
    for (std::size_t q = 0; q < model.child.terms.size(); ++q) out.push_back({&model.child.terms[q], &f.child[q], 1.0});
    return out;
}

std::vector<detail::WeightedTerm> terms_c(const HgpModel& model, const LayerFactors& f, double r) {
    std::vector<detail::WeightedTerm> out = terms_a(model, f);
    for (std::size_t q = 0; q < model.parent.terms.size(); ++q) out.push_back({&model.parent.terms[q], &f.parent[q], r});
    return out;
}

/// Rough flop counts of one evaluation with gradient: Structured vs LowRank (for Auto).
bool low_rank_is_cheaper(const HgpModel& model, const LayerFactors& f, Index d, Index t, double r) {
    const double n = static_cast<double>(d * t), td = static_cast<double>(t), dd = static_cast<double>(d);
    const double matrices = model.hierarchical ? 2.0 : 1.0;
    const double structured = matrices * n * n * n;
    const double ma = static_cast<double>(detail::BlockLowRank::rank_of(terms_a(model, f)));
    const double mc = model.hierarchical ? static_cast<double>(detail::BlockLowRank::rank_of(terms_c(model, f, r))) : 0.0;
    auto one = [&](double m) { return 3.0 * dd * td * td * td + 2.0 * n * td * m + 2.0 * n * m * m + 2.0 * m * m * m; };
    const double terms = static_cast<double>(model.child.terms.size() + (model.hierarchical ? model.parent.terms.size() : 0));
    const double width = r + ma + 1.0 + mc;
    const double low_rank = one(ma) + (model.hierarchical ? one(mc) : 0.0) + 2.0 * n * (ma * ma + mc * mc) +
                            terms * 8.0 * n * td * width;
    return low_rank < structured;
}

/// Structured likelihood with block-diagonal-plus-low-rank layers (every child complete). See
/// block_low_rank.hpp for the algebra; the rotation of the children is the Structured path's.
LikelihoodValue low_rank_likelihood(const HgpModel& model, const HgpData& data, bool with_gradient, int threads,
                                    const LayerFactors& f) {
    LikelihoodValue out;
    out.path = LikelihoodPath::LowRank;
    const Index t = static_cast<Index>(data.frames());
    const Index d = static_cast<Index>(data.outputs());
    const Index n = d * t;
    const Index r = static_cast<Index>(data.child_count());
    const double rd = static_cast<double>(r);
    const bool hier = model.hierarchical;
    MatX e(n, r);
    for (Index c = 0; c < r; ++c) e.col(c) = vec_output_major(data.children[static_cast<std::size_t>(c)]);
    VecX z;
    if (hier) {
        const VecX mean = e.rowwise().mean();
        z = std::sqrt(rd) * mean;
        e.colwise() -= mean;
    }
    const double a_count = hier ? rd - 1.0 : rd;
    const VecX noise = model.noise_variance();

    detail::BlockLowRank fa, fc;
    bool ok_a = false, ok_c = !hier;
    std::string msg_a, msg_c;
    MatX pa;       // A⁻¹ E
    VecX alpha_c;  // C⁻¹ z
    double quad_a = 0.0, quad_c = 0.0;
    const auto ta = terms_a(model, f);
    const auto tc = hier ? terms_c(model, f, rd) : std::vector<detail::WeightedTerm>{};
    auto work_a = [&]() {
        ok_a = fa.build(ta, noise, t, msg_a);
        if (!ok_a) return;
        pa = fa.solve(e);
        quad_a = e.cwiseProduct(pa).sum();
    };
    auto work_c = [&]() {
        if (!hier) return;
        ok_c = fc.build(tc, noise, t, msg_c);
        if (!ok_c) return;
        alpha_c = fc.solve(z);
        quad_c = z.dot(alpha_c);
    };
    run_both(threads >= 2 && hier, work_a, work_c);
    if (!ok_a || !ok_c) {
        out.message = !ok_a ? "child covariance K_f + noise: " + msg_a : "K_f + noise + R·K_g: " + msg_c;
        return out;
    }
    out.log_likelihood = -0.5 * (quad_a + a_count * fa.log_det) - 0.5 * rd * static_cast<double>(n) * kLog2Pi;
    if (hier) out.log_likelihood += -0.5 * (quad_c + fc.log_det);
    if (!std::isfinite(out.log_likelihood)) {
        out.message = "non-finite low-rank log likelihood";
        return out;
    }
    out.ok = true;
    if (!with_gradient) return out;

    // W_A = (A⁻¹E)(A⁻¹E)ᵀ − count·A⁻¹ = Pa Paᵀ − count·P_A⁻¹ + count·V_A K_A⁻¹ V_Aᵀ;
    // W_C = α αᵀ − P_C⁻¹ + V_C K_C⁻¹ V_Cᵀ. G_f = W_A + W_C (child terms, noise), G_g = R·W_C (parent).
    const Index ma = fa.v.cols(), mc = hier ? fc.v.cols() : 0;
    detail::StructuredSymmetric gf, gg;
    gf.blocks.resize(static_cast<std::size_t>(d));
    const Index wf = r + ma + (hier ? 1 + mc : 0);
    gf.u.resize(n, wf);
    gf.x.resize(n, wf);
    gf.u.leftCols(r) = pa;
    gf.x.leftCols(r) = pa;
    gf.u.middleCols(r, ma) = fa.v;
    if (ma > 0) gf.x.middleCols(r, ma).noalias() = a_count * fa.v * fa.cap_inverse;
    for (Index i = 0; i < d; ++i) {
        MatX& b = gf.blocks[static_cast<std::size_t>(i)];
        b = -a_count * fa.p_inverse[static_cast<std::size_t>(i)];
        if (hier) b -= fc.p_inverse[static_cast<std::size_t>(i)];
    }
    if (hier) {
        gf.u.col(r + ma) = alpha_c;
        gf.x.col(r + ma) = alpha_c;
        gf.u.rightCols(mc) = fc.v;
        if (mc > 0) gf.x.rightCols(mc).noalias() = fc.v * fc.cap_inverse;
        // G_g / R shares W_C's columns; the factor R is applied in the contraction.
        gg.blocks.resize(static_cast<std::size_t>(d));
        for (Index i = 0; i < d; ++i) gg.blocks[static_cast<std::size_t>(i)] = -fc.p_inverse[static_cast<std::size_t>(i)];
        gg.u = gf.u.rightCols(1 + mc);
        gg.x = gf.x.rightCols(1 + mc);
    }
    out.gradient = VecX::Zero(static_cast<Index>(model.parameter_count()));
    const std::size_t parent_offset = model.child.parameter_count();
    auto grad_child = [&]() {
        std::size_t o = 0;
        for (std::size_t q = 0; q < model.child.terms.size(); ++q)
            o = detail::structured_term_gradient(model.child.terms[q], f.child[q], gf, 1.0, data.times, o, out.gradient);
        o = parent_offset + (hier ? model.parent.parameter_count() : 0);
        const VecX tr = detail::structured_block_traces(gf, d, t);
        for (Index i = 0; i < d; ++i) out.gradient[static_cast<Index>(o) + i] = 0.5 * tr[i] * std::exp(model.log_noise[i]);
    };
    auto grad_parent = [&]() {
        if (!hier) return;
        std::size_t o = parent_offset;
        for (std::size_t q = 0; q < model.parent.terms.size(); ++q)
            o = detail::structured_term_gradient(model.parent.terms[q], f.parent[q], gg, rd, data.times, o, out.gradient);
    };
    run_both(threads >= 2 && hier, grad_child, grad_parent);
    return out;
}

void check_times(const VecX& t_star) {
    if (t_star.size() == 0 || !t_star.allFinite()) throw InvalidArgument("prediction times: expected ≥ 1 finite time");
}

GaussianPrediction condition_dense(const HgpModel& model, const HgpData& data, const VecX& t_star,
                                   std::ptrdiff_t child /* −1: parent */) {
    const Index t = static_cast<Index>(data.frames());
    const Index d = static_cast<Index>(data.outputs());
    const Index ts = t_star.size();
    const DenseLayout l = dense_layout(data);
    const MatX kf = lmc_covariance(model.child, data.times, data.times);
    MatX kg;
    if (model.hierarchical) kg = lmc_covariance(model.parent, data.times, data.times);
    const VecX noise = flat_noise(model.noise_variance(), t);
    const MatX sigma = assemble_dense(l, model.hierarchical ? &kg : nullptr, &kf, &noise);
    // Cross-covariance between the query (D·T*) and every observed value.
    MatX kgs, kfs;
    if (model.hierarchical) kgs = lmc_covariance(model.parent, t_star, data.times);
    kfs = lmc_covariance(model.child, t_star, data.times);
    const Index n = static_cast<Index>(l.flat.size());
    MatX cross = MatX::Zero(d * ts, n);
    for (Index j = 0; j < n; ++j) {
        if (model.hierarchical) cross.col(j) += kgs.col(l.flat[j]);
        if (child >= 0 && l.child[j] == static_cast<std::size_t>(child)) cross.col(j) += kfs.col(l.flat[j]);
    }
    MatX prior = MatX::Zero(d * ts, d * ts);
    if (model.hierarchical) prior += lmc_covariance(model.parent, t_star, t_star);
    if (child >= 0) prior += lmc_covariance(model.child, t_star, t_star);
    Eigen::LLT<MatX> llt(sigma);
    GaussianPrediction p;
    p.noise = model.noise_variance();
    if (llt.info() != Eigen::Success) {
        p.mean = MatX::Constant(d, ts, std::nan(""));
        p.variance = p.mean;
        return p;
    }
    const VecX mean = cross * llt.solve(l.y);
    const MatX v = llt.matrixL().solve(cross.transpose());
    const VecX var = prior.diagonal() - v.colwise().squaredNorm().transpose();
    p.mean = unvec_output_major(mean, d, ts);
    p.variance = unvec_output_major(var, d, ts);
    return p;
}

/// Posterior of g at `tq` given the complete children `members` (structured): mean (D·|tq|) and covariance.
struct ParentPosterior {
    VecX mean;
    MatX cov;
    bool ok = true;
};

ParentPosterior parent_posterior_structured(const HgpModel& model, const HgpData& data,
                                            const std::vector<std::size_t>& members, const VecX& tq) {
    ParentPosterior pp;
    const Index t = static_cast<Index>(data.frames());
    const Index d = static_cast<Index>(data.outputs());
    pp.cov = lmc_covariance(model.parent, tq, tq);
    pp.mean = VecX::Zero(d * tq.size());
    if (members.empty()) return pp;
    const double rc = static_cast<double>(members.size());
    VecX mean = VecX::Zero(d * t);
    for (std::size_t m : members) mean += vec_output_major(data.children[m]);
    mean /= rc;
    MatX c = lmc_covariance(model.child, data.times, data.times);
    c.diagonal() += flat_noise(model.noise_variance(), t);
    c.noalias() += rc * lmc_covariance(model.parent, data.times, data.times);
    Eigen::LLT<MatX> llt(c);
    if (llt.info() != Eigen::Success) {
        pp.ok = false;
        return pp;
    }
    const MatX kqt = lmc_covariance(model.parent, tq, data.times);
    pp.mean = rc * kqt * llt.solve(mean);
    const MatX v = llt.matrixL().solve(kqt.transpose());
    pp.cov.noalias() -= rc * v.transpose() * v;
    return pp;
}

GaussianPrediction nan_prediction(Index d, Index ts, const VecX& noise) {
    GaussianPrediction p;
    p.mean = MatX::Constant(d, ts, std::nan(""));
    p.variance = p.mean;
    p.noise = noise;
    return p;
}

/// Child posterior at `t_star` and its full covariance (for sampling), structured; siblings complete.
struct ChildPosterior {
    VecX mean;
    MatX cov;
    bool ok = true;
};

ChildPosterior child_posterior_structured(const HgpModel& model, const HgpData& data, std::size_t child,
                                          const VecX& t_star) {
    const Index d = static_cast<Index>(data.outputs());
    std::vector<Index> obs_frames;
    for (Index f = 0; f < static_cast<Index>(data.frames()); ++f)
        if (data.is_observed(child, static_cast<std::size_t>(f))) obs_frames.push_back(f);
    const Index no = static_cast<Index>(obs_frames.size());
    const Index ts = t_star.size();
    VecX tq(no + ts);
    for (Index i = 0; i < no; ++i) tq[i] = data.times[obs_frames[static_cast<std::size_t>(i)]];
    tq.tail(ts) = t_star;
    const Index nq = tq.size();
    // Prior of f_child over tq given the siblings: μ_g, Σ_g + K_f.
    VecX mu = VecX::Zero(d * nq);
    MatX p = lmc_covariance(model.child, tq, tq);
    ChildPosterior out;
    if (model.hierarchical) {
        std::vector<std::size_t> members;
        for (std::size_t r = 0; r < data.child_count(); ++r)
            if (r != child) members.push_back(r);
        ParentPosterior pp = parent_posterior_structured(model, data, members, tq);
        if (!pp.ok) {
            out.ok = false;
            return out;
        }
        mu = pp.mean;
        p += pp.cov;
    }
    std::vector<Index> io, is;
    for (Index k = 0; k < d; ++k) {
        for (Index i = 0; i < no; ++i) io.push_back(k * nq + i);
        for (Index i = 0; i < ts; ++i) is.push_back(k * nq + no + i);
    }
    const Index m = static_cast<Index>(io.size()), ms = static_cast<Index>(is.size());
    MatX poo(m, m), pso(ms, m), pss(ms, ms);
    for (Index j = 0; j < m; ++j) {
        for (Index i = 0; i < m; ++i) poo(i, j) = p(io[i], io[j]);
        for (Index i = 0; i < ms; ++i) pso(i, j) = p(is[i], io[j]);
    }
    for (Index j = 0; j < ms; ++j)
        for (Index i = 0; i < ms; ++i) pss(i, j) = p(is[i], is[j]);
    VecX mus(ms);
    for (Index i = 0; i < ms; ++i) mus[i] = mu[is[i]];
    if (m == 0) {
        out.mean = mus;
        out.cov = pss;
        return out;
    }
    const VecX noise = model.noise_variance();
    VecX resid(m);
    const MatX& y = data.children[child];
    for (Index k = 0, j = 0; k < d; ++k)
        for (Index i = 0; i < no; ++i, ++j) {
            resid[j] = y(k, obs_frames[static_cast<std::size_t>(i)]) - mu[io[j]];
            poo(j, j) += noise[k];
        }
    Eigen::LLT<MatX> llt(poo);
    if (llt.info() != Eigen::Success) {
        out.ok = false;
        return out;
    }
    out.mean = mus + pso * llt.solve(resid);
    const MatX v = llt.matrixL().solve(pso.transpose());
    out.cov = pss - v.transpose() * v;
    return out;
}

void draw_gaussian(const VecX& mean, const MatX& cov, std::size_t count, std::mt19937_64& rng, Index d, Index ts,
                   std::vector<MatX>& out) {
    // Cholesky with a small relative jitter (sampling only; the covariance may be numerically singular).
    const double scale = std::max(cov.diagonal().cwiseAbs().maxCoeff(), 1e-300);
    MatX jittered = cov;
    Eigen::LLT<MatX> llt;
    for (double jitter = 1e-10; jitter < 1.0; jitter *= 10.0) {
        jittered = cov;
        jittered.diagonal().array() += jitter * scale;
        llt.compute(jittered);
        if (llt.info() == Eigen::Success) break;
    }
    if (llt.info() != Eigen::Success) throw InvalidArgument("sample_children: covariance cannot be factorized");
    const MatX l = llt.matrixL();
    std::normal_distribution<double> normal(0.0, 1.0);
    for (std::size_t s = 0; s < count; ++s) {
        VecX xi(mean.size());
        for (Index i = 0; i < xi.size(); ++i) xi[i] = normal(rng);
        out.push_back(unvec_output_major(mean + l * xi, d, ts));
    }
}

}  // namespace

VecX HgpModel::noise_variance() const { return (log_noise.array().exp() + noise_floor).matrix(); }

std::size_t HgpModel::parameter_count() const {
    return child.parameter_count() + (hierarchical ? parent.parameter_count() : 0) + static_cast<std::size_t>(log_noise.size());
}

VecX HgpModel::parameters() const {
    std::vector<double> p;
    for (const auto& t : child.terms) append_parameters(t, p);
    if (hierarchical)
        for (const auto& t : parent.terms) append_parameters(t, p);
    for (Index i = 0; i < log_noise.size(); ++i) p.push_back(log_noise[i]);
    return Eigen::Map<const VecX>(p.data(), static_cast<Index>(p.size()));
}

void HgpModel::set_parameters(const VecX& p) {
    if (static_cast<std::size_t>(p.size()) != parameter_count())
        throw InvalidArgument("HgpModel::set_parameters: expected " + std::to_string(parameter_count()) +
                              " values, found " + std::to_string(p.size()));
    std::size_t o = 0;
    for (auto& t : child.terms) o = read_parameters(t, p, o);
    if (hierarchical)
        for (auto& t : parent.terms) o = read_parameters(t, p, o);
    for (Index i = 0; i < log_noise.size(); ++i) log_noise[i] = p[static_cast<Index>(o) + i];
}

std::vector<std::string> HgpModel::parameter_names() const {
    std::vector<std::string> names;
    auto add = [&](const Lmc& lmc, const std::string& layer) {
        for (std::size_t q = 0; q < lmc.terms.size(); ++q) {
            const auto& t = lmc.terms[q];
            const std::string pre = layer + ".q" + std::to_string(q) + ".";
            names.push_back(pre + "log_lengthscale");
            for (Index j = 0; j < t.W.cols(); ++j)
                for (Index i = 0; i < t.W.rows(); ++i)
                    names.push_back(pre + "W[" + std::to_string(i) + "," + std::to_string(j) + "]");
            for (Index i = 0; i < t.log_kappa.size(); ++i) names.push_back(pre + "log_kappa[" + std::to_string(i) + "]");
        }
    };
    add(child, "child");
    if (hierarchical) add(parent, "parent");
    for (Index i = 0; i < log_noise.size(); ++i) names.push_back("log_noise[" + std::to_string(i) + "]");
    return names;
}

void validate(const HgpModel& model) {
    const std::size_t d = model.outputs();
    if (d == 0) throw InvalidArgument("HgpModel: no outputs (log_noise is empty)");
    if (!model.log_noise.allFinite()) throw InvalidArgument("HgpModel: non-finite log_noise");
    if (!(model.noise_floor >= 0.0) || !std::isfinite(model.noise_floor))
        throw InvalidArgument("HgpModel: noise_floor must be finite and ≥ 0");
    if (model.child.terms.empty()) throw InvalidArgument("HgpModel: the child LMC needs at least one term");
    validate(model.child, d, "child LMC");
    if (model.hierarchical) {
        if (model.parent.terms.empty()) throw InvalidArgument("HgpModel: the parent LMC needs at least one term");
        validate(model.parent, d, "parent LMC");
    }
}

bool HgpData::is_observed(std::size_t child, std::size_t frame) const {
    if (child >= observed.size() || observed[child].empty()) return true;
    return observed[child][frame];
}

bool HgpData::is_complete(std::size_t child) const {
    if (child >= observed.size()) return true;
    for (bool b : observed[child])
        if (!b) return false;
    return true;
}

bool HgpData::all_complete() const {
    for (std::size_t r = 0; r < children.size(); ++r)
        if (!is_complete(r)) return false;
    return true;
}

std::size_t HgpData::observed_value_count() const {
    std::size_t n = 0;
    for (std::size_t r = 0; r < children.size(); ++r)
        for (std::size_t f = 0; f < frames(); ++f)
            if (is_observed(r, f)) n += outputs();
    return n;
}

void validate(const HgpData& data) {
    if (data.times.size() == 0 || !data.times.allFinite()) throw InvalidArgument("HgpData: expected ≥ 1 finite sample time");
    if (data.children.empty()) throw InvalidArgument("HgpData: no children");
    const Index d = data.children.front().rows();
    if (d == 0) throw InvalidArgument("HgpData: children have no outputs");
    if (data.observed.size() > data.children.size())
        throw InvalidArgument("HgpData: more observation masks than children");
    for (std::size_t r = 0; r < data.children.size(); ++r) {
        const MatX& y = data.children[r];
        if (y.rows() != d || y.cols() != data.times.size())
            throw InvalidArgument("HgpData: child " + std::to_string(r) + " is " + std::to_string(y.rows()) + " by " +
                                  std::to_string(y.cols()) + ", expected " + std::to_string(d) + " by " +
                                  std::to_string(data.times.size()));
        if (r < data.observed.size() && !data.observed[r].empty() &&
            data.observed[r].size() != static_cast<std::size_t>(data.times.size()))
            throw InvalidArgument("HgpData: child " + std::to_string(r) + "'s mask has " +
                                  std::to_string(data.observed[r].size()) + " flags, expected " +
                                  std::to_string(data.times.size()));
        for (Index f = 0; f < y.cols(); ++f)
            if (data.is_observed(r, static_cast<std::size_t>(f)) && !y.col(f).allFinite())
                throw InvalidArgument("HgpData: child " + std::to_string(r) + " has a non-finite observed value at frame " +
                                      std::to_string(f));
    }
    if (data.observed_value_count() == 0) throw InvalidArgument("HgpData: nothing is observed");
}

LikelihoodValue log_likelihood(const HgpModel& model, const HgpData& data, bool with_gradient, LikelihoodPath path,
                               int threads) {
    validate(model);
    validate(data);
    if (model.outputs() != data.outputs())
        throw InvalidArgument("log_likelihood: model has " + std::to_string(model.outputs()) + " outputs, data " +
                              std::to_string(data.outputs()));
    if ((path == LikelihoodPath::Structured || path == LikelihoodPath::LowRank) && !data.all_complete())
        throw InvalidArgument("log_likelihood: the structured and low-rank paths need every child complete (use Dense or Auto)");
    if (path == LikelihoodPath::Dense || (path == LikelihoodPath::Auto && !data.all_complete()))
        return dense_likelihood(model, data, with_gradient);
    if (path == LikelihoodPath::Structured) return structured_likelihood(model, data, with_gradient, threads);
    const LayerFactors f = layer_factors(model, data.times);
    if (path == LikelihoodPath::LowRank) return low_rank_likelihood(model, data, with_gradient, threads, f);
    // Auto, every child complete.
    if (low_rank_is_cheaper(model, f, static_cast<Index>(data.outputs()), static_cast<Index>(data.frames()),
                            static_cast<double>(data.child_count()))) {
        LikelihoodValue v = low_rank_likelihood(model, data, with_gradient, threads, f);
        if (v.ok) return v;
        // P (the κ and noise blocks) may be singular while the full covariance is not.
    }
    return structured_likelihood(model, data, with_gradient, threads);
}

namespace {
void check_prediction_args(const HgpModel& model, const HgpData& data, const VecX& t_star) {
    validate(model);
    validate(data);
    if (model.outputs() != data.outputs()) throw InvalidArgument("prediction: model and data have different outputs");
    check_times(t_star);
}
}  // namespace

GaussianPrediction predict_parent_dense(const HgpModel& model, const HgpData& data, const VecX& t_star) {
    check_prediction_args(model, data, t_star);
    if (!model.hierarchical) throw InvalidArgument("predict_parent: the MOA baseline has no parent");
    return condition_dense(model, data, t_star, -1);
}

GaussianPrediction predict_child_dense(const HgpModel& model, const HgpData& data, std::size_t child,
                                       const VecX& t_star) {
    check_prediction_args(model, data, t_star);
    if (child >= data.child_count()) throw InvalidArgument("predict_child: no child " + std::to_string(child));
    if (!model.hierarchical) {
        // MOA: the siblings are independent of the child; condition on its own values only.
        HgpData own;
        own.times = data.times;
        own.children = {data.children[child]};
        if (child < data.observed.size()) own.observed = {data.observed[child]};
        bool any = false;
        for (std::size_t f = 0; f < own.frames(); ++f) any = any || own.is_observed(0, f);
        if (!any) {
            GaussianPrediction p;
            p.mean = MatX::Zero(static_cast<Index>(data.outputs()), t_star.size());
            p.variance = unvec_output_major(lmc_covariance(model.child, t_star, t_star).diagonal(),
                                            static_cast<Index>(data.outputs()), t_star.size());
            p.noise = model.noise_variance();
            return p;
        }
        return condition_dense(model, own, t_star, 0);
    }
    return condition_dense(model, data, t_star, static_cast<std::ptrdiff_t>(child));
}

GaussianPrediction predict_parent(const HgpModel& model, const HgpData& data, const VecX& t_star) {
    check_prediction_args(model, data, t_star);
    if (!model.hierarchical) throw InvalidArgument("predict_parent: the MOA baseline has no parent");
    if (!data.all_complete()) return condition_dense(model, data, t_star, -1);
    std::vector<std::size_t> all(data.child_count());
    for (std::size_t r = 0; r < all.size(); ++r) all[r] = r;
    const Index d = static_cast<Index>(data.outputs());
    ParentPosterior pp = parent_posterior_structured(model, data, all, t_star);
    if (!pp.ok) return nan_prediction(d, t_star.size(), model.noise_variance());
    GaussianPrediction p;
    p.mean = unvec_output_major(pp.mean, d, t_star.size());
    p.variance = unvec_output_major(pp.cov.diagonal(), d, t_star.size());
    p.noise = model.noise_variance();
    return p;
}

GaussianPrediction predict_child(const HgpModel& model, const HgpData& data, std::size_t child, const VecX& t_star) {
    check_prediction_args(model, data, t_star);
    if (child >= data.child_count()) throw InvalidArgument("predict_child: no child " + std::to_string(child));
    bool siblings_complete = true;
    for (std::size_t r = 0; r < data.child_count(); ++r)
        if (r != child && !data.is_complete(r)) siblings_complete = false;
    if (model.hierarchical && !siblings_complete) return condition_dense(model, data, t_star, static_cast<std::ptrdiff_t>(child));
    const Index d = static_cast<Index>(data.outputs());
    ChildPosterior cp = child_posterior_structured(model, data, child, t_star);
    if (!cp.ok) return nan_prediction(d, t_star.size(), model.noise_variance());
    GaussianPrediction p;
    p.mean = unvec_output_major(cp.mean, d, t_star.size());
    p.variance = unvec_output_major(cp.cov.diagonal(), d, t_star.size());
    p.noise = model.noise_variance();
    return p;
}

MatX synthesis_trend(const HgpModel& model, const HgpData& data, const VecX& t_star) {
    check_prediction_args(model, data, t_star);
    if (model.hierarchical) return predict_parent(model, data, t_star).mean;
    // MOA: every observed value of every child is a noisy observation of one function f ~ GP(0, K_f).
    const Index t = static_cast<Index>(data.frames());
    const Index d = static_cast<Index>(data.outputs());
    if (data.all_complete()) {
        // R complete replicates at the same times: their mean ȳ is sufficient, with noise N/R
        // (one (D·T)² factorization instead of (R·D·T)²).
        const double rd = static_cast<double>(data.child_count());
        VecX mean = VecX::Zero(d * t);
        for (const MatX& y : data.children) mean += vec_output_major(y);
        mean /= rd;
        MatX s = lmc_covariance(model.child, data.times, data.times);
        s.diagonal() += flat_noise(model.noise_variance(), t) / rd;
        Eigen::LLT<MatX> llt(s);
        if (llt.info() != Eigen::Success) return MatX::Constant(d, t_star.size(), std::nan(""));
        return unvec_output_major(lmc_covariance(model.child, t_star, data.times) * llt.solve(mean), d, t_star.size());
    }
    const DenseLayout l = dense_layout(data);
    const MatX kf = lmc_covariance(model.child, data.times, data.times);
    const VecX noise = flat_noise(model.noise_variance(), t);
    const Index n = static_cast<Index>(l.flat.size());
    MatX s(n, n);
    for (Index j = 0; j < n; ++j)
        for (Index i = 0; i < n; ++i) s(i, j) = kf(l.flat[i], l.flat[j]) + (i == j ? noise[l.flat[i]] : 0.0);
    const MatX ks = lmc_covariance(model.child, t_star, data.times);
    MatX cross(d * t_star.size(), n);
    for (Index j = 0; j < n; ++j) cross.col(j) = ks.col(l.flat[j]);
    Eigen::LLT<MatX> llt(s);
    if (llt.info() != Eigen::Success) return MatX::Constant(d, t_star.size(), std::nan(""));
    return unvec_output_major(cross * llt.solve(l.y), d, t_star.size());
}

std::vector<MatX> sample_children(const HgpModel& model, const HgpData& data, const VecX& t_star, std::size_t count,
                                  const SampleOptions& options) {
    check_prediction_args(model, data, t_star);
    const Index d = static_cast<Index>(data.outputs());
    const Index ts = t_star.size();
    VecX mean;
    MatX cov = lmc_covariance(model.child, t_star, t_star);
    if (model.hierarchical && options.parent_uncertainty) {
        if (!data.all_complete())
            throw InvalidArgument("sample_children: parent_uncertainty needs every child complete");
        std::vector<std::size_t> all(data.child_count());
        for (std::size_t r = 0; r < all.size(); ++r) all[r] = r;
        ParentPosterior pp = parent_posterior_structured(model, data, all, t_star);
        if (!pp.ok) throw InvalidArgument("sample_children: the parent posterior cannot be computed");
        mean = pp.mean;
        cov += pp.cov;
    } else {
        mean = vec_output_major(synthesis_trend(model, data, t_star));
    }
    if (!mean.allFinite()) throw InvalidArgument("sample_children: the trend could not be computed (covariance not positive definite)");
    if (options.add_noise) cov.diagonal() += flat_noise(model.noise_variance(), ts);
    std::mt19937_64 rng(options.seed);
    std::vector<MatX> out;
    draw_gaussian(mean, cov, count, rng, d, ts, out);
    return out;
}

}  // namespace mocapdb::gp
