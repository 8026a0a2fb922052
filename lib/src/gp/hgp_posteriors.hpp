#pragma once
// The posteriors of the hierarchical GP (internal to the gp module, used by hierarchical_gp.cpp): the
// dense path over every observed value (dense_posterior.cpp: likelihood and conditioning, whatever
// frames are missing) and the structured path over a time grid, conditioned group by group
// (grid_posterior.cpp: every child, or every sibling, complete).
#include <cstddef>
#include <vector>

#include "mocapdb/gp/hierarchical_gp.hpp"

namespace mocapdb::gp::detail {

// ---- Dense ----------------------------------------------------------------------------------------

struct DenseLayout {
    std::vector<std::size_t> child;  ///< owning child of each observed value
    std::vector<std::size_t> group;  ///< its group
    std::vector<Eigen::Index> flat;  ///< its index in the child's output-major vector
    VecX y;
};

/// The observed values of the data, child by child.
DenseLayout dense_layout(const HgpData& data);

/// The log likelihood (and its gradient) from the covariance of every observed value.
LikelihoodValue dense_likelihood(const HgpModel& model, const HgpData& data, bool with_gradient);

/// What a posterior is about: the trend g, group s's function h_s, or child r's latent f_r.
struct Target {
    enum Kind { Parent, Group, Child } kind = Parent;
    std::size_t index = 0;
};

/// The posterior of `target` at t_star given every observed value (NumericalError when the covariance
/// is not positive definite).
GaussianPrediction condition_dense(const HgpModel& model, const HgpData& data, const VecX& t_star, Target target);

// ---- Structured: Gaussians over a time grid ------------------------------------------------------

/// The data's times followed by the query times not among them; where each query time sits.
struct Grid {
    VecX z;
    std::vector<Eigen::Index> query;
};

Grid make_grid(const VecX& times, const VecX& tq);

/// A Gaussian over D outputs at the grid times (output-major: index d·|z| + i).
struct GridGaussian {
    VecX mean;
    MatX cov;
    bool ok = true;
};

/// Posterior of the trend g on the grid given the complete children `members` (structured).
/// Two layers: their mean ȳ = g + N(0, A / R'). Three layers: per group its members' mean, groups of one
/// size n_c averaged: ȳ_c = g + N(0, (A + n_c K_h) / (n_c S_c)), conditioned class by class.
GridGaussian trend_on_grid(const HgpModel& model, const HgpData& data, const std::vector<std::size_t>& members,
                           const Grid& grid);

/// Posterior of h_s (three layers) on the grid given the complete children other than `excluded`.
GridGaussian group_on_grid(const HgpModel& model, const HgpData& data, std::size_t s, std::ptrdiff_t excluded,
                           const Grid& grid);

/// The grid Gaussian at the query times: mean and full covariance (output-major over the queries).
GridGaussian at_queries(const GridGaussian& g, const Grid& grid, Eigen::Index d);

/// The prior of child `child`'s latent f on the grid given its (complete) siblings: its parent function
/// (g, or h_s with three layers) given them, plus K_f.
GridGaussian child_prior_on_grid(const HgpModel& model, const HgpData& data, std::size_t child, const Grid& grid);

/// Conditions a child's prior on its own observed frames (`mask`, or its HgpData mask when empty).
bool condition_on_own_frames(GridGaussian& g, const HgpModel& model, const HgpData& data, std::size_t child,
                             const std::vector<bool>* mask, const Grid& grid, bool full_cov);

/// Mean and latent variance of a grid Gaussian at the grid's query times.
GaussianPrediction grid_prediction(const GridGaussian& g, const Grid& grid, Eigen::Index d, const VecX& noise);

}  // namespace mocapdb::gp::detail
