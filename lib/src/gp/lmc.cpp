#include "mocapdb/gp/lmc.hpp"

#include <cmath>

#include "mocapdb/core/error.hpp"

namespace mocapdb::gp {

MatX LmcTerm::coregionalization() const {
    MatX b = W * W.transpose();
    b.diagonal() += log_kappa.array().exp().matrix();
    return b;
}

std::size_t Lmc::parameter_count() const noexcept {
    std::size_t n = 0;
    for (const auto& t : terms) n += t.parameter_count();
    return n;
}

void validate(const Lmc& lmc, std::size_t outputs, const std::string& what) {
    for (std::size_t q = 0; q < lmc.terms.size(); ++q) {
        const auto& t = lmc.terms[q];
        const std::string name = what + " term " + std::to_string(q);
        if (t.outputs() != outputs || static_cast<std::size_t>(t.W.rows()) != outputs)
            throw InvalidArgument(name + ": expected " + std::to_string(outputs) + " outputs, found " +
                                  std::to_string(t.log_kappa.size()) + " kappas and a W of " +
                                  std::to_string(t.W.rows()) + " rows");
        if (!std::isfinite(t.log_lengthscale) || !t.W.allFinite() || !t.log_kappa.allFinite())
            throw InvalidArgument(name + ": non-finite hyperparameter");
    }
}

MatX lmc_covariance(const Lmc& lmc, const VecX& t1, const VecX& t2) {
    const Eigen::Index d = static_cast<Eigen::Index>(lmc.outputs());
    const Eigen::Index n1 = t1.size(), n2 = t2.size();
    MatX k = MatX::Zero(d * n1, d * n2);
    for (const auto& term : lmc.terms) {
        const MatX b = term.coregionalization();
        const MatX kt = kernel_matrix(term.kernel, term.log_lengthscale, t1, t2);
        for (Eigen::Index j = 0; j < d; ++j)
            for (Eigen::Index i = 0; i < d; ++i) k.block(i * n1, j * n2, n1, n2).noalias() += b(i, j) * kt;
    }
    return k;
}

void append_parameters(const LmcTerm& term, std::vector<double>& out) {
    out.push_back(term.log_lengthscale);
    for (Eigen::Index i = 0; i < term.W.size(); ++i) out.push_back(term.W.data()[i]);
    for (Eigen::Index i = 0; i < term.log_kappa.size(); ++i) out.push_back(term.log_kappa[i]);
}

std::size_t read_parameters(LmcTerm& term, const VecX& p, std::size_t offset) {
    if (offset + term.parameter_count() > static_cast<std::size_t>(p.size()))
        throw InvalidArgument("LMC parameters: vector too short");
    Eigen::Index o = static_cast<Eigen::Index>(offset);
    term.log_lengthscale = p[o++];
    for (Eigen::Index i = 0; i < term.W.size(); ++i) term.W.data()[i] = p[o++];
    for (Eigen::Index i = 0; i < term.log_kappa.size(); ++i) term.log_kappa[i] = p[o++];
    return static_cast<std::size_t>(o);
}

std::size_t lmc_term_gradient(const LmcTerm& term, const MatX& G, const VecX& times, std::size_t offset,
                              VecX& out_gradient) {
    const Eigen::Index d = static_cast<Eigen::Index>(term.outputs());
    const Eigen::Index n = times.size();
    if (G.rows() != d * n || G.cols() != d * n) throw InvalidArgument("lmc_term_gradient: G has the wrong size");
    const MatX b = term.coregionalization();
    const MatX k = kernel_matrix(term.kernel, term.log_lengthscale, times, times);
    const MatX dk = kernel_matrix_dlog_lengthscale(term.kernel, term.log_lengthscale, times, times);
    MatX m(d, d);
    MatX nmat = MatX::Zero(n, n);
    for (Eigen::Index j = 0; j < d; ++j) {
        for (Eigen::Index i = 0; i < d; ++i) {
            const auto block = G.block(i * n, j * n, n, n);
            m(i, j) = block.cwiseProduct(k).sum();
            nmat.noalias() += b(i, j) * block;
        }
    }
    Eigen::Index o = static_cast<Eigen::Index>(offset);
    out_gradient[o++] = 0.5 * nmat.cwiseProduct(dk).sum();
    const MatX msym = 0.5 * (m + m.transpose());
    const MatX gw = msym * term.W;  // ½·(M + Mᵀ)·W: d/dW of ½ Σ M ∘ (W Wᵀ)
    for (Eigen::Index i = 0; i < gw.size(); ++i) out_gradient[o++] = gw.data()[i];
    for (Eigen::Index i = 0; i < d; ++i) out_gradient[o++] = 0.5 * msym(i, i) * std::exp(term.log_kappa[i]);
    return static_cast<std::size_t>(o);
}

}  // namespace mocapdb::gp
