#pragma once
// Hierarchical multi-output Gaussian process (MOHGP) over replicate motions, after Hensman et al. (2013)
// and Gil López (2017, §4.1). Two layers:
//   g(t)   ~ GP(0, K_g)          the parent trend (D outputs)
//   f_r(t) ~ GP(g(t), K_f)       child r = 1..R, a replicate deviating from the parent
//   y_r(t) = f_r(t) + ε,  ε ~ N(0, diag(σ²_d))   per-output white noise
// with LMC covariances K_g, K_f (lmc.hpp). Two values of one child covary by K_g + K_f (+ noise), of
// different children by K_g. The MOA baseline is the same LMC without the hierarchy: children are
// independent draws of one GP(0, K_f) (+ noise); `hierarchical = false` selects it.
//
// Details: docs/headers/gp.md (mocapdb/gp/hierarchical_gp.hpp).
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "mocapdb/core/types.hpp"
#include "mocapdb/gp/lmc.hpp"

namespace mocapdb::gp {

/// Parameters of a MOHGP (or of the MOA baseline when !hierarchical).
struct HgpModel {
    Lmc child;       ///< K_f: a child's deviation from its parent (MOA: the whole signal covariance)
    Lmc group;       ///< K_h: a group's deviation from the trend; used (non-empty) only when grouped
    Lmc parent;      ///< K_g: the parent trend; ignored (and may be empty) when !hierarchical
    VecX log_noise;  ///< D values; σ²_d = noise_floor + exp(log_noise[d])
    double noise_floor = 1e-6;
    bool hierarchical = true;
    bool grouped = false;  ///< three layers (trend → group → child); needs hierarchical and HgpData::groups

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
    VecX times;                  ///< T sample times (seconds), shared by every child
    std::vector<MatX> children;  ///< R matrices, D by T
    /// Per child: T flags (true = frame observed), or empty = every frame observed. May be empty.
    std::vector<std::vector<bool>> observed;
    /// Per child its group 0..S−1 (three-layer models; every group non-empty). Empty: no groups.
    std::vector<std::size_t> groups;

    std::size_t child_count() const noexcept { return children.size(); }
    std::size_t outputs() const noexcept {
        return children.empty() ? 0 : static_cast<std::size_t>(children.front().rows());
    }
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
    Auto,  ///< structure present: the cheaper of LowRank and Structured (LowRank falls back to
           ///< Structured when its block-diagonal part is not positive definite); dense otherwise
    Dense,
    Structured,  ///< one (D·T)² factorization per level; InvalidArgument when a child has missing frames
    LowRank,     ///< the structured decomposition with each level's covariance as block diagonal plus
                 ///< low rank (Woodbury); the same preconditions as Structured
};

enum class LikelihoodStatus {
    Ok,
    NotPositiveDefinite,  ///< a covariance could not be factorized (message: which)
    NonFinite,            ///< the value came out infinite or NaN (message: of which part)
};
const char* to_string(LikelihoodStatus status);

struct LikelihoodValue {
    LikelihoodStatus status = LikelihoodStatus::NotPositiveDefinite;  ///< until computed
    double log_likelihood = 0.0;
    VecX gradient;        ///< ∂ log p / ∂ parameters (HgpModel::parameters order); empty unless asked
    std::string message;  ///< what failed, when status is not Ok
    bool ok() const noexcept { return status == LikelihoodStatus::Ok; }
    LikelihoodPath path = LikelihoodPath::Auto;  ///< the path actually used
};

/// Log marginal likelihood log p(Y | θ) and (with_gradient) its gradient.
/// `threads` (1 or 2): the structured path factorizes its two matrices concurrently when 2.
LikelihoodValue log_likelihood(const HgpModel& model, const HgpData& data, bool with_gradient,
                               LikelihoodPath path = LikelihoodPath::Auto, int threads = 2);

/// Gaussian marginals of a D-output prediction at T* times. NumericalError when a covariance the
/// prediction needs is not positive definite (no prediction exists for these parameters).
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
GaussianPrediction predict_child(const HgpModel& model, const HgpData& data, std::size_t child, const VecX& t_star);
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
std::vector<MatX> sample_children(const HgpModel& model, const HgpData& data, const VecX& t_star, std::size_t count,
                                  const SampleOptions& options = {});

}  // namespace mocapdb::gp
