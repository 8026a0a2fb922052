#pragma once
// Internal to the gp module: LMC covariances over shared times as "block diagonal plus low rank".
//
// With B_q = W_q W_qᵀ + diag(κ_q), a sum of weighted LMC terms plus per-output noise over D outputs at
// T shared times (output-major, n = D·T) is
//     Σ = Σ_q c_q (W_q W_qᵀ + diag κ_q) ⊗ k_q + diag(σ²) ⊗ I_T = P + L Lᵀ
// where P is block diagonal (block d, T×T: Σ_q c_q κ_{q,d} k_q + σ²_d I) and L = [√c_q w_{q,j} ⊗ S_q]
// (one column block per term q and column j of W_q) with k_q = S_q S_qᵀ, S_q = U √Λ from the
// eigendecomposition of k_q (eigenvalues at or below the eigensolver's precision, T·ε·λ_max, are
// treated as 0 and their columns dropped: the RBF matrix is numerically singular and must not be
// inverted). Then (matrix determinant lemma, Woodbury) with the M×M capacitance K = I + Lᵀ P⁻¹ L:
//     log det Σ = Σ_d log det P_d + log det K,      Σ⁻¹ = P⁻¹ − V K⁻¹ Vᵀ,  V = P⁻¹ L
// costing O(D·T³ + n·M·T + n·M² + M³) instead of O(n³).
//
// Gradients: a symmetric "structured" matrix G = blockdiag(G_d) + X Uᵀ (X = U H with H symmetric, so
// X Uᵀ = U Xᵀ) is contracted with each term's covariance derivatives without forming any n×n matrix:
//     M(d,d') = tr(G_dd' k),  N = Σ_dd' B(d,d') G_dd'
// with the low-rank parts computed through (I_D ⊗ k) U, Ū_j = (w_jᵀ ⊗ I_T) U and X̄_j likewise.
#include <string>
#include <utility>
#include <vector>

#include "mocapdb/core/types.hpp"
#include "mocapdb/gp/lmc.hpp"

namespace mocapdb::gp::detail {

/// k = kernel matrix at the shared times, s = its square-root factor (T × m, k ≈ s sᵀ, m ≤ T columns
/// with eigenvalue above T·ε·λ_max). A factor may also describe an "extended" kernel A ⊗ k over
/// (class, time) pairs (the coupled size classes of three-layer data): then dk holds ∂k/∂log ℓ of that
/// kernel (empty: computed from the term and the times).
struct KernelFactor {
    MatX k;
    MatX s;
    MatX dk;
};
/// The factor of A ⊗ k for a K×K matrix A = a aᵀ (a_rank1) or diag(a) (!a_rank1), with dk.
KernelFactor extended_factor(const LmcTerm& term, const KernelFactor& base, const VecX& times, const VecX& a,
                             bool a_rank1);
KernelFactor factor_kernel(const LmcTerm& term, const VecX& times);

/// One weighted term c·(B_q ⊗ k_q) of a covariance.
struct WeightedTerm {
    const LmcTerm* term = nullptr;
    const KernelFactor* factor = nullptr;
    double weight = 1.0;
};

/// Σ = P + L Lᵀ, factorized. n = D·T.
class BlockLowRank {
public:
    /// False (with a message) when a block P_d or the capacitance is not positive definite.
    bool build(const std::vector<WeightedTerm>& terms, const VecX& noise, Eigen::Index t, std::string& message);

    /// Columns M of L (given the factors), without building anything.
    static Eigen::Index rank_of(const std::vector<WeightedTerm>& terms);

    /// Σ⁻¹ Z for Z n×k.
    MatX solve(const MatX& z) const;
    /// blockdiag(P⁻¹) Z.
    MatX apply_p_inverse(const MatX& z) const;

    double log_det = 0.0;
    Eigen::Index outputs = 0, frames = 0;
    std::vector<MatX> p_inverse;  ///< D blocks P_d⁻¹ (T×T)
    MatX v;                       ///< P⁻¹ L (n×M)
    MatX cap_inverse;             ///< (I + Lᵀ P⁻¹ L)⁻¹ (M×M)
};

/// G = blockdiag(blocks) + x uᵀ (symmetric), n = D·T.
struct StructuredSymmetric {
    std::vector<MatX> blocks;  ///< D blocks (T×T), symmetric
    MatX u, x;                 ///< n×m each
};

/// Writes ½ tr(G ∂(scale·B⊗k)/∂θ) for the term's parameters at `offset` of `out_gradient`
/// (append_parameters order); returns the new offset.
std::size_t structured_term_gradient(const LmcTerm& term, const KernelFactor& factor, const StructuredSymmetric& g,
                                     double scale, const VecX& times, std::size_t offset, VecX& out_gradient);

/// The diagonal of G summed per output: tr(G_dd), D values.
VecX structured_block_traces(const StructuredSymmetric& g, Eigen::Index d, Eigen::Index t);

}  // namespace mocapdb::gp::detail
