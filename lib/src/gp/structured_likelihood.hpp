#pragma once
// Internal to the gp module: the structured and low-rank likelihood paths (every child complete).
//
// The children are rotated into independent "levels" (hierarchical_gp.hpp): level k holds columns e_k,
// each ~ N(0, X_k) with X_k = K_f + noise + a_k·K_h + b_k·K_g, and contributes
//     −½ (tr(e_kᵀ X_k⁻¹ e_k) + count_k · log det X_k)
// (count_k = the number of independent directions the level stands for). Three-layer data whose groups
// differ in size adds a coupled part: the size classes' mean functions ȳ_c = g + N(0, C_c / R_c),
// C_c = K_f + noise + n_c·K_h, which share the trend g ~ N(0, K_g) (see coupled_classes in the .cpp).
// The gradient is accumulated level by level, ½ tr(W_k ∂X_k/∂θ) with W_k = X_k⁻¹ e_k e_kᵀ X_k⁻¹ −
// count_k X_k⁻¹, so no level needs another's matrices and the levels run concurrently.
#include "block_low_rank.hpp"
#include "mocapdb/gp/hierarchical_gp.hpp"

namespace mocapdb::gp::detail {

struct Level {
    MatX e;                      ///< n × k columns
    double count = 0.0;          ///< copies of log det X
    double group_weight = 0.0;   ///< a_k
    double parent_weight = 0.0;  ///< b_k
};

/// The mean of one size class of groups (three layers, groups of unequal size).
struct CoupledClass {
    VecX mean;                ///< ȳ_c, n values
    double group_size = 0.0;  ///< n_c
    double children = 0.0;    ///< R_c = n_c × (groups of this size)
};

struct Levels {
    std::vector<Level> independent;
    std::vector<CoupledClass> coupled;  ///< empty, or ≥ 2 classes
};

/// The decomposition of complete children (InvalidArgument if a child is incomplete or a three-layer
/// model has no groups). Levels with count 0 (their columns are exactly zero) are left out.
Levels make_levels(const HgpModel& model, const HgpData& data);

/// Offsets of each layer's parameters in HgpModel::parameters().
struct ParameterOffsets {
    std::size_t child = 0, group = 0, parent = 0, noise = 0;
};
ParameterOffsets parameter_offsets(const HgpModel& model);

LikelihoodValue structured_likelihood(const HgpModel& model, const HgpData& data, bool with_gradient, int threads);

/// Low-rank path. The coupled size classes become one block-diagonal-plus-low-rank covariance over
/// D outputs × (class, time) pairs (see the .cpp).
LikelihoodValue low_rank_likelihood(const HgpModel& model, const HgpData& data, const Levels& levels,
                                    bool with_gradient, int threads);

/// Rough flop counts of one evaluation with gradient: true when the low-rank path is the cheaper.
bool low_rank_is_cheaper(const HgpModel& model, const HgpData& data, const Levels& levels);

}  // namespace mocapdb::gp::detail
