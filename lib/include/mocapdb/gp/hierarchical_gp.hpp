#pragma once
// Hierarchical multi-output Gaussian process (MOHGP) over replicate motions, after Hensman et al. (2013)
// and Gil López (2017, §4.1). Two layers:
//   g(t)   ~ GP(0, K_g)          the parent trend (D outputs)
//   f_r(t) ~ GP(g(t), K_f)       child r = 1..R, a replicate deviating from the parent
//   y_r(t) = f_r(t) + ε,  ε ~ N(0, diag(σ²_d))   per-output white noise
// with LMC covariances K_g, K_f (lmc.hpp). Two values of one child covary by K_g + K_f (+ noise), of
// different children by K_g. The MOA baseline is the same LMC without the hierarchy: children are
// independent draws of one GP(0, K_f) (+ noise); `hierarchical = false` selects it.
// Three layers (`grouped`, trend → group → child, e.g. trend → subject → trial): each child belongs to
// a group s (HgpData::groups) with its own function h_s ~ GP(g, K_h) and f_r ~ GP(h_s, K_f). Values of
// one child covary by K_g + K_h + K_f (+ noise), of two children of one group by K_g + K_h, of
// different groups by K_g.
//
// Data: all children share the sample times `times` (T values); each child is a D by T matrix,
// optionally with a per-frame mask of observed frames (all outputs of a frame observed together).
//
// Implementations of the log marginal likelihood and its gradient:
//   dense       builds the full covariance over every observed value of every child (the oracle;
//               any masks and groups), O((R·D·T)³);
//   structured  all children complete (three layers: and every group of the same size m): rotating
//               the children within their groups and the groups around their mean splits the
//               likelihood into independent Gaussian "levels", each over D·T values with one
//               covariance: two layers, A = K_f + noise for the R − 1 deviations from the mean and
//               A + R·K_g for √R·ȳ; three layers, A for the R − S deviations from the group means,
//               A + m·K_h for the S − 1 deviations of √m·ȳ_s from √m·ȳ, A + m·K_h + R·K_g for √R·ȳ.
//               Only the deviations' scatter enters each level: one factorization of size D·T per
//               level, O(levels·(D·T)³) independent of R. The levels run on two threads. Groups of
//               unequal size: the deviations within each size class are levels as above, and the K
//               classes' means ȳ_c = g + N(0, (A + n_c·K_h) / R_c) are one coupled Gaussian (Woodbury
//               without inverting K_g; about 12 (D·T)³ flops).
//   low rank    the same levels, but each covariance is written as P + L Lᵀ: P block diagonal over
//               the outputs (the diag(κ_q) ⊗ k_q terms and the noise, D blocks T×T) and
//               L = [w_qj ⊗ S_q] with k_q = S_q S_qᵀ (rank(W_q)·T columns per term); determinant lemma
//               and Woodbury with an M×M capacitance, M = Σ_q rank(W_q)·T, and gradient contractions
//               that never form a (D·T)² matrix: O(D·T³ + D·T²·M + D·T·M² + M³) per level. The coupled
//               size classes are an LMC over D outputs at K·T (class, time) inputs with kernels
//               I ⊗ k, diag(n_c) ⊗ k and v vᵀ ⊗ k (v_c = √R_c): the same algebra with K·T for T.
// Children with missing frames break the structure: the likelihood then falls back to the dense path
// (Auto), while the posterior of a partially observed child given complete siblings
// stays structured (the siblings enter through the posterior of g and of the child's group function,
// conditioned group by group).
//
// Numerical outcomes are values, never exceptions: a covariance that is not positive definite gives
// ok = false with a message. Arguments of the wrong shape throw InvalidArgument.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "mocapdb/core/types.hpp"
#include "mocapdb/gp/lmc.hpp"

namespace mocapdb::gp {

/// Parameters of a MOHGP (or of the MOA baseline when !hierarchical).
struct HgpModel {
    Lmc child;            ///< K_f: a child's deviation from its parent (MOA: the whole signal covariance)
    Lmc group;            ///< K_h: a group's deviation from the trend; used (non-empty) only when grouped
    Lmc parent;           ///< K_g: the parent trend; ignored (and may be empty) when !hierarchical
    VecX log_noise;       ///< D values; σ²_d = noise_floor + exp(log_noise[d])
    double noise_floor = 1e-6;
    bool hierarchical = true;
    bool grouped = false; ///< three layers (trend → group → child); needs hierarchical and HgpData::groups

    /// 1 (MOA), 2 (trend → child) or 3 (trend → group → child).
    int layers() const noexcept { return hierarchical ? (grouped ? 3 : 2) : 1; }
    std::size_t outputs() const noexcept { return static_cast<std::size_t>(log_noise.size()); }
    VecX noise_variance() const;
    /// Free parameters: child terms, then group terms (grouped only), then parent terms (hierarchical
    /// only), then log_noise.
    std::size_t parameter_count() const;
    VecX parameters() const;
    void set_parameters(const VecX& p);
    /// One name per parameter, in parameters() order ("child.q0.log_lengthscale", "parent.q1.W[3,0]",
    /// "child.q0.log_kappa[2]", "log_noise[5]").
    std::vector<std::string> parameter_names() const;
};

/// Throws InvalidArgument unless the model is consistent (D outputs everywhere, at least one child term,
/// at least one parent term when hierarchical, at least one group term when grouped, grouped only when
/// hierarchical, finite values, noise_floor ≥ 0).
void validate(const HgpModel& model);

/// Replicate observations sharing sample times.
struct HgpData {
    VecX times;                              ///< T sample times (seconds), shared by every child
    std::vector<MatX> children;              ///< R matrices, D by T
    /// Per child: T flags (true = frame observed), or empty = every frame observed. May be empty.
    std::vector<std::vector<bool>> observed;
    /// Per child its group 0..S−1 (three-layer models; every group non-empty). Empty: no groups.
    std::vector<std::size_t> groups;

    std::size_t child_count() const noexcept { return children.size(); }
    std::size_t outputs() const noexcept { return children.empty() ? 0 : static_cast<std::size_t>(children.front().rows()); }
    std::size_t frames() const noexcept { return static_cast<std::size_t>(times.size()); }
    bool is_observed(std::size_t child, std::size_t frame) const;
    bool is_complete(std::size_t child) const;
    bool all_complete() const;
    /// Number of observed values (frames observed × D, summed over children).
    std::size_t observed_value_count() const;
    /// S (1 + the largest group index), 0 without groups.
    std::size_t group_count() const;
    /// Children per group when every group has the same number, else 0 (also without groups).
    std::size_t balanced_group_size() const;
};

/// The data without child `child` (masks and groups follow; a group left empty is removed and the
/// later groups renumbered, keeping their order).
HgpData without_child(const HgpData& data, std::size_t child);

/// Throws InvalidArgument unless: T ≥ 1 finite times, ≥ 1 child, every child D by T with the same D ≥ 1,
/// observed values finite, masks of T flags, at least one observed frame overall, groups empty or one
/// index per child with every group 0..S−1 non-empty.
void validate(const HgpData& data);

enum class LikelihoodPath {
    Auto,        ///< structure present: the cheaper of LowRank and Structured (LowRank falls back to
                 ///< Structured when its block-diagonal part is not positive definite); dense otherwise
    Dense,
    Structured,  ///< one (D·T)² factorization per level; InvalidArgument when a child has missing frames
    LowRank,     ///< the structured decomposition with each level's covariance as block diagonal plus
                 ///< low rank (Woodbury); the same preconditions as Structured
};

struct LikelihoodValue {
    bool ok = false;            ///< false: a covariance was not positive definite (see message)
    double log_likelihood = 0.0;
    VecX gradient;              ///< ∂ log p / ∂ parameters (HgpModel::parameters order); empty unless asked
    std::string message;
    LikelihoodPath path = LikelihoodPath::Auto;  ///< the path actually used
};

/// Log marginal likelihood log p(Y | θ) and (with_gradient) its gradient.
/// `threads` (1 or 2): the structured path factorizes its two matrices concurrently when 2.
LikelihoodValue log_likelihood(const HgpModel& model, const HgpData& data, bool with_gradient,
                               LikelihoodPath path = LikelihoodPath::Auto, int threads = 2);

/// Gaussian marginals of a D-output prediction at T* times. When a covariance needed for the prediction
/// is not positive definite (a numerical outcome, not an argument error) mean and variance are NaN:
/// check mean.allFinite().
struct GaussianPrediction {
    MatX mean;      ///< D by T*
    MatX variance;  ///< D by T*, of the latent function (without observation noise)
    VecX noise;     ///< D observation-noise variances (add to `variance` for the predictive of y)
};

/// Posterior of the parent trend g at `t_star` given every observed value (hierarchical models only;
/// InvalidArgument for MOA). Structured when every child is complete, dense otherwise.
/// Three layers: the trend g, not a group's function.
GaussianPrediction predict_parent(const HgpModel& model, const HgpData& data, const VecX& t_star);
/// Posterior of child `child`'s latent f at `t_star` given every observed value (its own observed frames
/// and every sibling). Structured when every sibling is complete (the child itself may be partial).
GaussianPrediction predict_child(const HgpModel& model, const HgpData& data, std::size_t child,
                                 const VecX& t_star);
/// predict_child at the data's times under each of several observation masks of the same child (T flags
/// each; the child's own mask in `data` is ignored), every sibling complete (InvalidArgument otherwise):
/// the siblings' share — the posterior of the child's parent function — is computed once.
std::vector<GaussianPrediction> predict_child_masks(const HgpModel& model, const HgpData& data, std::size_t child,
                                                    const std::vector<std::vector<bool>>& masks);
/// The same two posteriors computed from the full dense joint covariance (the oracle).
GaussianPrediction predict_parent_dense(const HgpModel& model, const HgpData& data, const VecX& t_star);
GaussianPrediction predict_child_dense(const HgpModel& model, const HgpData& data, std::size_t child,
                                       const VecX& t_star);

/// Three layers: posterior of group s's function h_s at `t_star` given every observed value (structured
/// when every child is complete, dense otherwise). InvalidArgument unless the model is grouped.
GaussianPrediction predict_group(const HgpModel& model, const HgpData& data, std::size_t group, const VecX& t_star);
GaussianPrediction predict_group_dense(const HgpModel& model, const HgpData& data, std::size_t group,
                                       const VecX& t_star);

/// The trend new children are drawn around (thesis §5.2): for MOHGP the posterior mean of g given all
/// children; for MOA (no parent) the posterior mean of one GP(0, K_f) given every child as a noisy
/// replicate of it (the MOA "GP prediction given the observations" of the thesis). D by T*.
MatX synthesis_trend(const HgpModel& model, const HgpData& data, const VecX& t_star);

struct SampleOptions {
    std::uint64_t seed = 1;
    /// Also draw the parent from its posterior covariance (the thesis uses its mean only). Needs every
    /// child complete (InvalidArgument otherwise).
    bool parent_uncertainty = false;
    /// Add observation noise to the samples.
    bool add_noise = false;
    /// Three layers: draw new children of this existing group (its function's posterior mean + a draw of
    /// GP(0, K_f); with parent_uncertainty also its posterior covariance) instead of a new group.
    /// InvalidArgument for a model without groups or a group that does not exist.
    std::optional<std::size_t> group;
};

/// `count` new children at `t_star` (thesis §5.2): synthesis_trend + a draw of GP(0, K_f) (+ the options).
/// Three layers: each sample is a new child of a new group, synthesis_trend + a draw of GP(0, K_h + K_f),
/// or with options.group a new child of that group.
/// Deterministic for a given seed. Each sample is D by T*.
std::vector<MatX> sample_children(const HgpModel& model, const HgpData& data, const VecX& t_star,
                                  std::size_t count, const SampleOptions& options = {});

}  // namespace mocapdb::gp
