#include "block_low_rank.hpp"

#include <cmath>
#include <limits>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

namespace mocapdb::gp::detail {

KernelFactor factor_kernel(const LmcTerm& term, const VecX& times) {
    KernelFactor f;
    f.k = kernel_matrix(term.kernel, term.log_lengthscale, times, times);
    const Eigen::Index t = f.k.rows();
    Eigen::SelfAdjointEigenSolver<MatX> es(f.k);
    const VecX& lambda = es.eigenvalues();  // ascending
    const double lmax = std::max(lambda[t - 1], 0.0);
    // Eigenvalues below the eigensolver's own precision are zero to working accuracy.
    const double threshold = static_cast<double>(t) * std::numeric_limits<double>::epsilon() * lmax;
    Eigen::Index first = 0;
    while (first < t && !(lambda[first] > threshold)) ++first;
    const Eigen::Index m = t - first;
    f.s = es.eigenvectors().rightCols(m) * lambda.tail(m).cwiseSqrt().asDiagonal();
    return f;
}

KernelFactor extended_factor(const LmcTerm& term, const KernelFactor& base, const VecX& times, const VecX& a,
                             bool a_rank1) {
    const Eigen::Index k = a.size(), t = base.k.rows(), m = base.s.cols();
    const MatX amat = a_rank1 ? MatX(a * a.transpose()) : MatX(a.asDiagonal());
    const MatX dk = kernel_matrix_dlog_lengthscale(term.kernel, term.log_lengthscale, times, times);
    KernelFactor f;
    f.k.resize(k * t, k * t);
    f.dk.resize(k * t, k * t);
    for (Eigen::Index j = 0; j < k; ++j)
        for (Eigen::Index i = 0; i < k; ++i) {
            f.k.block(i * t, j * t, t, t) = amat(i, j) * base.k;
            f.dk.block(i * t, j * t, t, t) = amat(i, j) * dk;
        }
    if (a_rank1) {
        f.s.resize(k * t, m);
        for (Eigen::Index i = 0; i < k; ++i) f.s.middleRows(i * t, t) = a[i] * base.s;
    } else {
        f.s = MatX::Zero(k * t, k * m);
        for (Eigen::Index i = 0; i < k; ++i) f.s.block(i * t, i * m, t, m) = std::sqrt(a[i]) * base.s;
    }
    return f;
}

Eigen::Index BlockLowRank::rank_of(const std::vector<WeightedTerm>& terms) {
    Eigen::Index m = 0;
    for (const auto& wt : terms) m += wt.term->W.cols() * wt.factor->s.cols();
    return m;
}

bool BlockLowRank::build(const std::vector<WeightedTerm>& terms, const VecX& noise, Eigen::Index t,
                         std::string& message) {
    const Eigen::Index d = noise.size();
    const Eigen::Index n = d * t;
    outputs = d;
    frames = t;
    log_det = 0.0;
    const Eigen::Index m = rank_of(terms);
    p_inverse.assign(static_cast<std::size_t>(d), MatX());
    MatX l = MatX::Zero(n, m);
    v.setZero(n, m);
    const MatX eye = MatX::Identity(t, t);
    MatX pd(t, t), tmp;
    for (Eigen::Index i = 0; i < d; ++i) {
        pd = noise[i] * eye;
        for (const auto& wt : terms) pd.noalias() += (wt.weight * std::exp(wt.term->log_kappa[i])) * wt.factor->k;
        Eigen::LLT<MatX> llt(pd);
        if (llt.info() != Eigen::Success) {
            message = "block " + std::to_string(i) + " of the block-diagonal part is not positive definite";
            return false;
        }
        const auto diag = llt.matrixLLT().diagonal();
        for (Eigen::Index j = 0; j < t; ++j)
            if (!(diag[j] > 0.0) || !std::isfinite(diag[j])) {
                message = "block " + std::to_string(i) + " of the block-diagonal part is not positive definite";
                return false;
            }
        log_det += 2.0 * diag.array().log().sum();
        MatX& pinv = p_inverse[static_cast<std::size_t>(i)];
        pinv = llt.solve(eye);
        pinv = 0.5 * (pinv + pinv.transpose()).eval();
        Eigen::Index off = 0;
        for (const auto& wt : terms) {
            const MatX& s = wt.factor->s;
            const Eigen::Index mq = s.cols();
            tmp.noalias() = pinv * s;
            const double c = std::sqrt(wt.weight);
            for (Eigen::Index j = 0; j < wt.term->W.cols(); ++j) {
                const double w = c * wt.term->W(i, j);
                l.block(i * t, off, t, mq) = w * s;
                v.block(i * t, off, t, mq) = w * tmp;
                off += mq;
            }
        }
    }
    if (m > 0) {
        MatX cap = MatX::Identity(m, m);
        cap.noalias() += l.transpose() * v;
        cap = 0.5 * (cap + cap.transpose()).eval();
        Eigen::LLT<MatX> llt(cap);
        if (llt.info() != Eigen::Success) {
            message = "the Woodbury capacitance matrix is not positive definite";
            return false;
        }
        const auto diag = llt.matrixLLT().diagonal();
        for (Eigen::Index j = 0; j < m; ++j)
            if (!(diag[j] > 0.0) || !std::isfinite(diag[j])) {
                message = "the Woodbury capacitance matrix is not positive definite";
                return false;
            }
        log_det += 2.0 * diag.array().log().sum();
        cap_inverse = llt.solve(MatX::Identity(m, m));
        cap_inverse = 0.5 * (cap_inverse + cap_inverse.transpose()).eval();
    } else {
        cap_inverse.resize(0, 0);
    }
    if (!std::isfinite(log_det)) {
        message = "non-finite log determinant";
        return false;
    }
    return true;
}

MatX BlockLowRank::apply_p_inverse(const MatX& z) const {
    MatX y(z.rows(), z.cols());
    for (Eigen::Index i = 0; i < outputs; ++i)
        y.middleRows(i * frames, frames).noalias() =
            p_inverse[static_cast<std::size_t>(i)] * z.middleRows(i * frames, frames);
    return y;
}

MatX BlockLowRank::solve(const MatX& z) const {
    MatX y = apply_p_inverse(z);
    if (v.cols() > 0) {
        const MatX small = cap_inverse * (v.transpose() * z);
        y.noalias() -= v * small;
    }
    return y;
}

namespace {

/// Σ_a Map(a_col, T, D)ᵀ b.col(a): for n×m `a` and T×m `b`, the D-vector ⟨A_d, b⟩ (A_d = rows of output d).
VecX block_inner(const MatX& a, const MatX& b, Eigen::Index d, Eigen::Index t) {
    VecX out = VecX::Zero(d);
    for (Eigen::Index c = 0; c < a.cols(); ++c) {
        Eigen::Map<const MatX> ac(a.col(c).data(), t, d);
        out.noalias() += ac.transpose() * b.col(c);
    }
    return out;
}

/// (wᵀ ⊗ I_T) a for n×m `a`: Σ_d w_d A_d (T×m).
MatX weighted_block_sum(const MatX& a, const VecX& w, Eigen::Index d, Eigen::Index t) {
    MatX out(t, a.cols());
    for (Eigen::Index c = 0; c < a.cols(); ++c) {
        Eigen::Map<const MatX> ac(a.col(c).data(), t, d);
        out.col(c).noalias() = ac * w;
    }
    return out;
}

}  // namespace

std::size_t structured_term_gradient(const LmcTerm& term, const KernelFactor& factor, const StructuredSymmetric& g,
                                     double scale, const VecX& times, std::size_t offset, VecX& out_gradient) {
    const Eigen::Index d = static_cast<Eigen::Index>(term.outputs());
    const Eigen::Index t = factor.k.rows();
    const Eigen::Index m = g.u.cols();
    const MatX& k = factor.k;
    const MatX dk = factor.dk.size() > 0
                        ? factor.dk
                        : kernel_matrix_dlog_lengthscale(term.kernel, term.log_lengthscale, times, times);
    const VecX kappa = term.log_kappa.array().exp().matrix();
    const MatX& w = term.W;
    // Block-diagonal part.
    VecX trgk(d);
    MatX nmat = MatX::Zero(t, t);
    for (Eigen::Index i = 0; i < d; ++i) {
        const MatX& gb = g.blocks[static_cast<std::size_t>(i)];
        trgk[i] = gb.cwiseProduct(k).sum();
        nmat.noalias() += (w.row(i).squaredNorm() + kappa[i]) * gb;
    }
    VecX mdiag = trgk;
    MatX mw = trgk.asDiagonal() * w;
    // Low-rank part X Uᵀ.
    if (m > 0) {
        Eigen::Map<const MatX> ut(g.u.data(), t, d * m), xt(g.x.data(), t, d * m);
        const MatX ku = k * ut;  // columns a·D + i: k U_i(:, a)
        const VecX colsum = xt.cwiseProduct(ku).colwise().sum().transpose();
        mdiag += Eigen::Map<const MatX>(colsum.data(), d, m).rowwise().sum();
        MatX xk = xt;
        for (Eigen::Index c = 0; c < d * m; ++c) xk.col(c) *= kappa[c % d];
        nmat.noalias() += xk * ut.transpose();
        for (Eigen::Index j = 0; j < w.cols(); ++j) {
            const MatX ubar = weighted_block_sum(g.u, w.col(j), d, t);
            const MatX xbar = weighted_block_sum(g.x, w.col(j), d, t);
            nmat.noalias() += xbar * ubar.transpose();
            const MatX kubar = k * ubar;
            mw.col(j) += block_inner(g.x, kubar, d, t);
        }
    }
    Eigen::Index o = static_cast<Eigen::Index>(offset);
    out_gradient[o++] = scale * 0.5 * nmat.cwiseProduct(dk).sum();
    for (Eigen::Index i = 0; i < mw.size(); ++i) out_gradient[o++] = scale * mw.data()[i];
    for (Eigen::Index i = 0; i < d; ++i) out_gradient[o++] = scale * 0.5 * mdiag[i] * kappa[i];
    return static_cast<std::size_t>(o);
}

VecX structured_block_traces(const StructuredSymmetric& g, Eigen::Index d, Eigen::Index t) {
    VecX tr(d);
    for (Eigen::Index i = 0; i < d; ++i) tr[i] = g.blocks[static_cast<std::size_t>(i)].trace();
    if (g.u.cols() > 0) {
        Eigen::Map<const MatX> ut(g.u.data(), t, d * g.u.cols()), xt(g.x.data(), t, d * g.u.cols());
        const VecX colsum = xt.cwiseProduct(ut).colwise().sum().transpose();
        tr += Eigen::Map<const MatX>(colsum.data(), d, g.u.cols()).rowwise().sum();
    }
    return tr;
}

}  // namespace mocapdb::gp::detail
