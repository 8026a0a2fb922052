// The structured posteriors of the hierarchical GP (hgp_posteriors.hpp): Gaussians over a time grid
// (the data's times, then the query times), conditioned on the children's means group by group.
#include <cmath>
#include <map>

#include <Eigen/Cholesky>

#include "mocapdb/core/error.hpp"
#include "gp_internal.hpp"
#include "hgp_posteriors.hpp"

namespace mocapdb::gp::detail {
namespace {

/// Indices of the grid entries at `frames` of the data times (which are the grid's first T), every output.
std::vector<Eigen::Index> grid_indices(Eigen::Index d, Eigen::Index grid_size,
                                       const std::vector<Eigen::Index>& frames) {
    std::vector<Eigen::Index> idx;
    for (Eigen::Index k = 0; k < d; ++k)
        for (Eigen::Index f : frames) idx.push_back(k * grid_size + f);
    return idx;
}

std::vector<Eigen::Index> all_frames(Eigen::Index t) {
    std::vector<Eigen::Index> f(static_cast<std::size_t>(t));
    for (Eigen::Index i = 0; i < t; ++i) f[static_cast<std::size_t>(i)] = i;
    return f;
}

/// Conditions g on y = g[sel] + ε, ε ~ N(0, noise_cov). With !full_cov only the diagonal of the
/// covariance is updated (the last step of a prediction). False when the innovation covariance is not
/// positive definite.
bool condition(GridGaussian& g, const std::vector<Eigen::Index>& sel, const VecX& y, const MatX& noise_cov,
               bool full_cov = true) {
    const Eigen::Index m = static_cast<Eigen::Index>(sel.size()), n = g.mean.size();
    MatX s = noise_cov;
    MatX c(m, n);
    VecX r(m);
    for (Eigen::Index i = 0; i < m; ++i) {
        c.row(i) = g.cov.row(sel[static_cast<std::size_t>(i)]);
        r[i] = y[i] - g.mean[sel[static_cast<std::size_t>(i)]];
        for (Eigen::Index j = 0; j < m; ++j)
            s(i, j) += g.cov(sel[static_cast<std::size_t>(i)], sel[static_cast<std::size_t>(j)]);
    }
    Eigen::LLT<MatX> llt(s);
    if (llt.info() != Eigen::Success) return false;
    llt.matrixL().solveInPlace(c);  // L⁻¹ C
    llt.matrixL().solveInPlace(r);
    g.mean.noalias() += c.transpose() * r;
    if (full_cov) {
        // Lower triangle by a rank-m update (half the flops of a product), then mirrored.
        g.cov.selfadjointView<Eigen::Lower>().rankUpdate(c.transpose(), -1.0);
        g.cov.triangularView<Eigen::StrictlyUpper>() = g.cov.transpose();
    } else {
        g.cov.diagonal() -= c.colwise().squaredNorm().transpose();
    }
    return g.mean.allFinite();
}

}  // namespace

Grid make_grid(const VecX& times, const VecX& tq) {
    Grid g;
    std::vector<double> z(times.data(), times.data() + times.size());
    for (Eigen::Index i = 0; i < tq.size(); ++i) {
        Eigen::Index at = -1;
        for (Eigen::Index j = 0; j < static_cast<Eigen::Index>(z.size()); ++j)
            if (z[static_cast<std::size_t>(j)] == tq[i]) {
                at = j;
                break;
            }
        if (at < 0) {
            at = static_cast<Eigen::Index>(z.size());
            z.push_back(tq[i]);
        }
        g.query.push_back(at);
    }
    g.z = Eigen::Map<const VecX>(z.data(), static_cast<Eigen::Index>(z.size()));
    return g;
}

/// Posterior of the trend g on the grid given the complete children `members` (structured).
/// Two layers: their mean ȳ = g + N(0, A / R'). Three layers: per group its members' mean, groups of one
/// size n_c averaged: ȳ_c = g + N(0, (A + n_c K_h) / (n_c S_c)), conditioned class by class.
GridGaussian trend_on_grid(const HgpModel& model, const HgpData& data, const std::vector<std::size_t>& members,
                           const Grid& grid) {
    const Eigen::Index d = static_cast<Eigen::Index>(data.outputs());
    const Eigen::Index t = static_cast<Eigen::Index>(data.frames());
    GridGaussian g;
    g.cov = lmc_covariance(model.parent, grid.z, grid.z);
    g.mean = VecX::Zero(g.cov.rows());
    if (members.empty()) return g;
    MatX a = lmc_covariance(model.child, data.times, data.times);
    a.diagonal() += flat_noise(model.noise_variance(), t);
    const auto sel = grid_indices(d, grid.z.size(), all_frames(t));
    if (!model.grouped) {
        VecX mean = VecX::Zero(d * t);
        for (std::size_t m : members) mean += vec_output_major(data.children[m]);
        const double rc = static_cast<double>(members.size());
        g.ok = condition(g, sel, mean / rc, a / rc);
        return g;
    }
    std::map<std::size_t, std::vector<std::size_t>> by_group;
    for (std::size_t m : members) by_group[data.groups[m]].push_back(m);
    std::map<std::size_t, std::vector<VecX>> class_means;  // group size → its groups' means
    for (const auto& [s, kids] : by_group) {
        VecX mean = VecX::Zero(d * t);
        for (std::size_t m : kids) mean += vec_output_major(data.children[m]);
        class_means[kids.size()].push_back(mean / static_cast<double>(kids.size()));
    }
    const MatX kh = lmc_covariance(model.group, data.times, data.times);
    for (const auto& [nc, means] : class_means) {
        VecX mean = VecX::Zero(d * t);
        for (const VecX& m : means) mean += m;
        const double sc = static_cast<double>(means.size()), ncd = static_cast<double>(nc);
        MatX noise_cov = a + ncd * kh;
        noise_cov /= ncd * sc;
        if (!condition(g, sel, mean / sc, noise_cov)) {
            g.ok = false;
            return g;
        }
    }
    return g;
}

/// Posterior of h_s (three layers) on the grid given the complete children other than `excluded`.
GridGaussian group_on_grid(const HgpModel& model, const HgpData& data, std::size_t s, std::ptrdiff_t excluded,
                           const Grid& grid) {
    std::vector<std::size_t> others, own;
    for (std::size_t r = 0; r < data.child_count(); ++r) {
        if (static_cast<std::ptrdiff_t>(r) == excluded) continue;
        (data.groups[r] == s ? own : others).push_back(r);
    }
    GridGaussian g = trend_on_grid(model, data, others, grid);
    if (!g.ok) return g;
    g.cov += lmc_covariance(model.group, grid.z, grid.z);
    if (own.empty()) return g;
    const Eigen::Index d = static_cast<Eigen::Index>(data.outputs());
    const Eigen::Index t = static_cast<Eigen::Index>(data.frames());
    VecX mean = VecX::Zero(d * t);
    for (std::size_t m : own) mean += vec_output_major(data.children[m]);
    const double rc = static_cast<double>(own.size());
    MatX a = lmc_covariance(model.child, data.times, data.times);
    a.diagonal() += flat_noise(model.noise_variance(), t);
    g.ok = condition(g, grid_indices(d, grid.z.size(), all_frames(t)), mean / rc, a / rc);
    return g;
}

/// The grid Gaussian at the query times: mean and full covariance (output-major over the queries).
GridGaussian at_queries(const GridGaussian& g, const Grid& grid, Eigen::Index d) {
    const auto idx = grid_indices(d, grid.z.size(), grid.query);
    GridGaussian out;
    const Eigen::Index m = static_cast<Eigen::Index>(idx.size());
    out.mean.resize(m);
    out.cov.resize(m, m);
    for (Eigen::Index i = 0; i < m; ++i) {
        out.mean[i] = g.mean[idx[static_cast<std::size_t>(i)]];
        for (Eigen::Index j = 0; j < m; ++j)
            out.cov(i, j) = g.cov(idx[static_cast<std::size_t>(i)], idx[static_cast<std::size_t>(j)]);
    }
    out.ok = g.ok;
    return out;
}

/// The prior of child `child`'s latent f on the grid given its (complete) siblings: its parent function
/// (g, or h_s with three layers) given them, plus K_f.
GridGaussian child_prior_on_grid(const HgpModel& model, const HgpData& data, std::size_t child, const Grid& grid) {
    const Eigen::Index d = static_cast<Eigen::Index>(data.outputs());
    GridGaussian g;
    if (!model.hierarchical) {
        g.mean = VecX::Zero(d * grid.z.size());
        g.cov = MatX::Zero(g.mean.size(), g.mean.size());
    } else if (model.grouped) {
        g = group_on_grid(model, data, data.groups[child], static_cast<std::ptrdiff_t>(child), grid);
    } else {
        std::vector<std::size_t> members;
        for (std::size_t r = 0; r < data.child_count(); ++r)
            if (r != child) members.push_back(r);
        g = trend_on_grid(model, data, members, grid);
    }
    if (g.ok) g.cov += lmc_covariance(model.child, grid.z, grid.z);
    return g;
}

/// Conditions a child's prior on its own observed frames (`mask`, or its HgpData mask when empty).
bool condition_on_own_frames(GridGaussian& g, const HgpModel& model, const HgpData& data, std::size_t child,
                             const std::vector<bool>* mask, const Grid& grid, bool full_cov) {
    const Eigen::Index d = static_cast<Eigen::Index>(data.outputs());
    const Eigen::Index t = static_cast<Eigen::Index>(data.frames());
    std::vector<Eigen::Index> frames;
    for (Eigen::Index f = 0; f < t; ++f)
        if (mask ? (*mask)[static_cast<std::size_t>(f)] : data.is_observed(child, static_cast<std::size_t>(f)))
            frames.push_back(f);
    if (frames.empty()) return true;
    const auto sel = grid_indices(d, grid.z.size(), frames);
    const VecX y = vec_output_major(data.children[child]);
    const VecX noise = model.noise_variance();
    VecX yo(static_cast<Eigen::Index>(sel.size()));
    VecX no(yo.size());
    const Eigen::Index nf = static_cast<Eigen::Index>(frames.size());
    for (Eigen::Index k = 0; k < d; ++k)
        for (Eigen::Index i = 0; i < nf; ++i) {
            yo[k * nf + i] = y[k * t + frames[static_cast<std::size_t>(i)]];
            no[k * nf + i] = noise[k];
        }
    return condition(g, sel, yo, no.asDiagonal().toDenseMatrix(), full_cov);
}

/// Mean and latent variance of a grid Gaussian at the grid's query times.
GaussianPrediction grid_prediction(const GridGaussian& g, const Grid& grid, Eigen::Index d, const VecX& noise) {
    const Eigen::Index ts = static_cast<Eigen::Index>(grid.query.size());
    if (!g.ok)
        throw NumericalError("GP prediction: a posterior covariance is not positive definite for these parameters");
    GaussianPrediction p;
    p.mean.resize(d, ts);
    p.variance.resize(d, ts);
    const Eigen::Index nz = grid.z.size();
    for (Eigen::Index k = 0; k < d; ++k)
        for (Eigen::Index i = 0; i < ts; ++i) {
            const Eigen::Index at = k * nz + grid.query[static_cast<std::size_t>(i)];
            p.mean(k, i) = g.mean[at];
            p.variance(k, i) = g.cov(at, at);
        }
    p.noise = noise;
    return p;
}

}  // namespace mocapdb::gp::detail
