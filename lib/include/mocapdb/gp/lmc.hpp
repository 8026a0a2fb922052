#pragma once
// Linear model of coregionalization (LMC) for D outputs on scalar inputs:
//   K(t, t') = Σ_q B_q k_q(t, t'),   B_q = W_q W_qᵀ + diag(κ_q)   (ICM when Q = 1).
// Every hyperparameter is unconstrained: W_q as is, κ_q = exp(log_kappa), ℓ_q = exp(log_lengthscale).
//
// Vectorization convention used throughout the gp module ("output-major"): the values of D outputs
// at T times, a D by T matrix Y, are stacked as y[d·T + t] = Y(d, t), so that a covariance over them
// is the Kronecker product Σ_q B_q ⊗ k_q(T, T) (block (d, d') = Σ_q B_q(d, d') k_q(T, T)).
#include <string>
#include <vector>

#include "mocapdb/core/types.hpp"
#include "mocapdb/gp/kernels.hpp"

namespace mocapdb::gp {

/// One term B_q k_q of an LMC.
struct LmcTerm {
    KernelType kernel = KernelType::Rbf;
    double log_lengthscale = 0.0;
    MatX W;          ///< D by rank
    VecX log_kappa;  ///< D values, κ = exp(log_kappa)

    std::size_t outputs() const noexcept { return static_cast<std::size_t>(log_kappa.size()); }
    /// B = W Wᵀ + diag(κ), D by D.
    MatX coregionalization() const;
    /// Number of free parameters: 1 + D·rank + D.
    std::size_t parameter_count() const noexcept {
        return 1 + static_cast<std::size_t>(W.size()) + static_cast<std::size_t>(log_kappa.size());
    }
};

struct Lmc {
    std::vector<LmcTerm> terms;

    std::size_t outputs() const noexcept { return terms.empty() ? 0 : terms.front().outputs(); }
    std::size_t parameter_count() const noexcept;
};

/// Throws InvalidArgument unless every term has D = `outputs` kappas, a D-row W, finite values.
void validate(const Lmc& lmc, std::size_t outputs, const std::string& what);

/// The LMC covariance between D outputs at times t1 and D outputs at times t2, output-major:
/// (D·|t1|) by (D·|t2|).
MatX lmc_covariance(const Lmc& lmc, const VecX& t1, const VecX& t2);

/// Appends the term's parameters to `out` in the fixed order [log ℓ, W (column-major), log κ].
void append_parameters(const LmcTerm& term, std::vector<double>& out);
/// Reads a term's parameters from `p` starting at `offset` (same order); returns the new offset.
std::size_t read_parameters(LmcTerm& term, const VecX& p, std::size_t offset);

/// Partial derivatives of a scalar objective through one LMC term, given the two contractions of an
/// (output-major) symmetric matrix G with the term's covariance derivatives:
///   M(d, d') = Σ_{t,t'} G[(d,t),(d',t')] k(t, t')        (D by D)
///   N(t, t') = Σ_{d,d'} B(d, d') G[(d,t),(d',t')]         (T by T)
/// the objective's differential ½ tr(G dK) gives ∂/∂θ = ½ Σ N ∘ ∂k/∂θ, ∂/∂W = M W, ∂/∂log κ_d = ½ M(d,d) κ_d.
/// Writes them at `offset` of `out_gradient` in the append_parameters order; returns the new offset.
std::size_t lmc_term_gradient(const LmcTerm& term, const MatX& G, const VecX& times, std::size_t offset,
                              VecX& out_gradient);

}  // namespace mocapdb::gp
