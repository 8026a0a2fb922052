// The dense path of the hierarchical GP (hgp_posteriors.hpp): the covariance of every observed value,
// its likelihood and gradient, and conditioning on it.
#include <cmath>

#include <Eigen/Cholesky>

#include "mocapdb/core/error.hpp"
#include "gp_internal.hpp"
#include "hgp_posteriors.hpp"

namespace mocapdb::gp::detail {
namespace {

MatX kron(const MatX& a, const MatX& b) {
    MatX k(a.rows() * b.rows(), a.cols() * b.cols());
    for (Eigen::Index j = 0; j < a.cols(); ++j)
        for (Eigen::Index i = 0; i < a.rows(); ++i)
            k.block(i * b.rows(), j * b.cols(), b.rows(), b.cols()) = a(i, j) * b;
    return k;
}

/// Flat indices (output-major over the shared times) of one child's observed values.
std::vector<Eigen::Index> observed_indices(const HgpData& data, std::size_t child) {
    const Eigen::Index t = static_cast<Eigen::Index>(data.frames());
    std::vector<Eigen::Index> idx;
    for (Eigen::Index d = 0; d < static_cast<Eigen::Index>(data.outputs()); ++d)
        for (Eigen::Index f = 0; f < t; ++f)
            if (data.is_observed(child, static_cast<std::size_t>(f))) idx.push_back(d * t + f);
    return idx;
}

/// The group of a child for the covariance (without groups: every child its own).
std::size_t group_of(const HgpData& data, std::size_t child) {
    return data.groups.empty() ? child : data.groups[child];
}

}  // namespace

DenseLayout dense_layout(const HgpData& data) {
    DenseLayout l;
    std::vector<double> y;
    for (std::size_t r = 0; r < data.child_count(); ++r) {
        const VecX v = vec_output_major(data.children[r]);
        for (Eigen::Index i : observed_indices(data, r)) {
            l.child.push_back(r);
            l.group.push_back(group_of(data, r));
            l.flat.push_back(i);
            y.push_back(v[i]);
        }
    }
    l.y = Eigen::Map<const VecX>(y.data(), static_cast<Eigen::Index>(y.size()));
    return l;
}

namespace {

/// Σ over the observed values from per-child blocks: kg for every pair, kh within a group, kf (+ noise
/// diag) within a child.
MatX assemble_dense(const DenseLayout& l, const MatX* kg, const MatX* kh, const MatX* kf, const VecX* noise_flat) {
    const Eigen::Index n = static_cast<Eigen::Index>(l.flat.size());
    MatX s = MatX::Zero(n, n);
    for (Eigen::Index j = 0; j < n; ++j)
        for (Eigen::Index i = 0; i < n; ++i) {
            double v = 0.0;
            if (kg) v += (*kg)(l.flat[i], l.flat[j]);
            if (kh && l.group[i] == l.group[j]) v += (*kh)(l.flat[i], l.flat[j]);
            if (l.child[i] == l.child[j]) {
                if (kf) v += (*kf)(l.flat[i], l.flat[j]);
                if (noise_flat && i == j) v += (*noise_flat)[l.flat[i]];
            }
            s(i, j) = v;
        }
    return s;
}

/// The covariance of every observed value under the model.
MatX dense_covariance(const HgpModel& model, const HgpData& data, const DenseLayout& l) {
    const MatX kf = lmc_covariance(model.child, data.times, data.times);
    MatX kg, kh;
    if (model.hierarchical) kg = lmc_covariance(model.parent, data.times, data.times);
    if (model.grouped) kh = lmc_covariance(model.group, data.times, data.times);
    const VecX noise = flat_noise(model.noise_variance(), static_cast<Eigen::Index>(data.frames()));
    return assemble_dense(l, model.hierarchical ? &kg : nullptr, model.grouped ? &kh : nullptr, &kf, &noise);
}

/// The derivative matrices (D·T square) of an LMC term's covariance w.r.t. each of its parameters,
/// in append_parameters order.
std::vector<MatX> term_derivatives(const LmcTerm& term, const VecX& times) {
    std::vector<MatX> out;
    const Eigen::Index d = static_cast<Eigen::Index>(term.outputs());
    const MatX b = term.coregionalization();
    const MatX k = kernel_matrix(term.kernel, term.log_lengthscale, times, times);
    out.push_back(kron(b, kernel_matrix_dlog_lengthscale(term.kernel, term.log_lengthscale, times, times)));
    for (Eigen::Index j = 0; j < term.W.cols(); ++j)
        for (Eigen::Index i = 0; i < d; ++i) {
            MatX db = MatX::Zero(d, d);
            db.row(i) += term.W.col(j).transpose();
            db.col(i) += term.W.col(j);
            out.push_back(kron(db, k));
        }
    for (Eigen::Index i = 0; i < d; ++i) {
        MatX db = MatX::Zero(d, d);
        db(i, i) = std::exp(term.log_kappa[i]);
        out.push_back(kron(db, k));
    }
    return out;
}

}  // namespace

LikelihoodValue dense_likelihood(const HgpModel& model, const HgpData& data, bool with_gradient) {
    LikelihoodValue out;
    out.path = LikelihoodPath::Dense;
    const Eigen::Index t = static_cast<Eigen::Index>(data.frames());
    const DenseLayout l = dense_layout(data);
    const MatX sigma = dense_covariance(model, data, l);
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
        out.status = LikelihoodStatus::NonFinite;
        out.message = "non-finite dense log likelihood";
        return out;
    }
    out.status = LikelihoodStatus::Ok;
    if (!with_gradient) return out;
    // W = α αᵀ − Σ⁻¹; ∂ log p/∂θ = ½ tr(W ∂Σ/∂θ) = ½ Σ_ij W_ij ∂Σ_ij.
    MatX w = alpha * alpha.transpose() - llt.solve(MatX::Identity(sigma.rows(), sigma.cols()));
    out.gradient = VecX::Zero(static_cast<Eigen::Index>(model.parameter_count()));
    Eigen::Index o = 0;
    for (const auto& term : model.child.terms)
        for (const MatX& dk : term_derivatives(term, data.times))
            out.gradient[o++] = 0.5 * w.cwiseProduct(assemble_dense(l, nullptr, nullptr, &dk, nullptr)).sum();
    if (model.grouped)
        for (const auto& term : model.group.terms)
            for (const MatX& dk : term_derivatives(term, data.times))
                out.gradient[o++] = 0.5 * w.cwiseProduct(assemble_dense(l, nullptr, &dk, nullptr, nullptr)).sum();
    if (model.hierarchical)
        for (const auto& term : model.parent.terms)
            for (const MatX& dk : term_derivatives(term, data.times))
                out.gradient[o++] = 0.5 * w.cwiseProduct(assemble_dense(l, &dk, nullptr, nullptr, nullptr)).sum();
    const Eigen::Index nt = static_cast<Eigen::Index>(data.outputs()) * t;
    const MatX zero = MatX::Zero(nt, nt);
    for (Eigen::Index d = 0; d < static_cast<Eigen::Index>(model.outputs()); ++d) {
        VecX dn = VecX::Zero(nt);
        dn.segment(d * t, t).setConstant(std::exp(model.log_noise[d]));
        out.gradient[o++] = 0.5 * w.cwiseProduct(assemble_dense(l, nullptr, nullptr, &zero, &dn)).sum();
    }
    return out;
}

GaussianPrediction condition_dense(const HgpModel& model, const HgpData& data, const VecX& t_star, Target target) {
    const Eigen::Index d = static_cast<Eigen::Index>(data.outputs());
    const Eigen::Index ts = t_star.size();
    const DenseLayout l = dense_layout(data);
    const MatX sigma = dense_covariance(model, data, l);
    // The target's group (h_s enters the covariance with the values of that group's children).
    const bool with_group = model.grouped && target.kind != Target::Parent;
    const std::size_t group = target.kind == Target::Group   ? target.index
                              : target.kind == Target::Child ? group_of(data, target.index)
                                                             : 0;
    MatX kgs, khs, kfs;
    if (model.hierarchical) kgs = lmc_covariance(model.parent, t_star, data.times);
    if (with_group) khs = lmc_covariance(model.group, t_star, data.times);
    if (target.kind == Target::Child) kfs = lmc_covariance(model.child, t_star, data.times);
    const Eigen::Index n = static_cast<Eigen::Index>(l.flat.size());
    MatX cross = MatX::Zero(d * ts, n);
    for (Eigen::Index j = 0; j < n; ++j) {
        if (model.hierarchical) cross.col(j) += kgs.col(l.flat[j]);
        if (with_group && l.group[j] == group) cross.col(j) += khs.col(l.flat[j]);
        if (target.kind == Target::Child && l.child[j] == target.index) cross.col(j) += kfs.col(l.flat[j]);
    }
    MatX prior = MatX::Zero(d * ts, d * ts);
    if (model.hierarchical) prior += lmc_covariance(model.parent, t_star, t_star);
    if (with_group) prior += lmc_covariance(model.group, t_star, t_star);
    if (target.kind == Target::Child) prior += lmc_covariance(model.child, t_star, t_star);
    Eigen::LLT<MatX> llt(sigma);
    GaussianPrediction p;
    p.noise = model.noise_variance();
    if (llt.info() != Eigen::Success)
        throw NumericalError("GP prediction: the dense joint covariance is not positive definite for these parameters");
    const VecX mean = cross * llt.solve(l.y);
    const MatX v = llt.matrixL().solve(cross.transpose());
    const VecX var = prior.diagonal() - v.colwise().squaredNorm().transpose();
    p.mean = unvec_output_major(mean, d, ts);
    p.variance = unvec_output_major(var, d, ts);
    return p;
}

}  // namespace mocapdb::gp::detail
