#include "mocapdb/gp/hierarchical_gp.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <random>

#include <Eigen/Cholesky>

#include "gp_internal.hpp"
#include "structured_likelihood.hpp"
#include "mocapdb/core/error.hpp"

namespace mocapdb::gp {

namespace {

using Index = Eigen::Index;
using detail::flat_noise;
using detail::kLog2Pi;
using detail::unvec_output_major;
using detail::vec_output_major;

MatX kron(const MatX& a, const MatX& b) {
    MatX k(a.rows() * b.rows(), a.cols() * b.cols());
    for (Index j = 0; j < a.cols(); ++j)
        for (Index i = 0; i < a.rows(); ++i) k.block(i * b.rows(), j * b.cols(), b.rows(), b.cols()) = a(i, j) * b;
    return k;
}

/// Flat indices (output-major over the shared times) of one child's observed values.
std::vector<Index> observed_indices(const HgpData& data, std::size_t child) {
    const Index t = static_cast<Index>(data.frames());
    std::vector<Index> idx;
    for (Index d = 0; d < static_cast<Index>(data.outputs()); ++d)
        for (Index f = 0; f < t; ++f)
            if (data.is_observed(child, static_cast<std::size_t>(f))) idx.push_back(d * t + f);
    return idx;
}

/// The group of a child for the covariance (without groups: every child its own).
std::size_t group_of(const HgpData& data, std::size_t child) {
    return data.groups.empty() ? child : data.groups[child];
}

struct DenseLayout {
    std::vector<std::size_t> child;  ///< owning child of each observed value
    std::vector<std::size_t> group;  ///< its group
    std::vector<Index> flat;         ///< its index in the child's output-major vector
    VecX y;
};

DenseLayout dense_layout(const HgpData& data) {
    DenseLayout l;
    std::vector<double> y;
    for (std::size_t r = 0; r < data.child_count(); ++r) {
        const VecX v = vec_output_major(data.children[r]);
        for (Index i : observed_indices(data, r)) {
            l.child.push_back(r);
            l.group.push_back(group_of(data, r));
            l.flat.push_back(i);
            y.push_back(v[i]);
        }
    }
    l.y = Eigen::Map<const VecX>(y.data(), static_cast<Index>(y.size()));
    return l;
}

/// Σ over the observed values from per-child blocks: kg for every pair, kh within a group, kf (+ noise
/// diag) within a child.
MatX assemble_dense(const DenseLayout& l, const MatX* kg, const MatX* kh, const MatX* kf, const VecX* noise_flat) {
    const Index n = static_cast<Index>(l.flat.size());
    MatX s = MatX::Zero(n, n);
    for (Index j = 0; j < n; ++j)
        for (Index i = 0; i < n; ++i) {
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
    const VecX noise = flat_noise(model.noise_variance(), static_cast<Index>(data.frames()));
    return assemble_dense(l, model.hierarchical ? &kg : nullptr, model.grouped ? &kh : nullptr, &kf, &noise);
}

/// The derivative matrices (D·T square) of an LMC term's covariance w.r.t. each of its parameters,
/// in append_parameters order.
std::vector<MatX> term_derivatives(const LmcTerm& term, const VecX& times) {
    std::vector<MatX> out;
    const Index d = static_cast<Index>(term.outputs());
    const MatX b = term.coregionalization();
    const MatX k = kernel_matrix(term.kernel, term.log_lengthscale, times, times);
    out.push_back(kron(b, kernel_matrix_dlog_lengthscale(term.kernel, term.log_lengthscale, times, times)));
    for (Index j = 0; j < term.W.cols(); ++j)
        for (Index i = 0; i < d; ++i) {
            MatX db = MatX::Zero(d, d);
            db.row(i) += term.W.col(j).transpose();
            db.col(i) += term.W.col(j);
            out.push_back(kron(db, k));
        }
    for (Index i = 0; i < d; ++i) {
        MatX db = MatX::Zero(d, d);
        db(i, i) = std::exp(term.log_kappa[i]);
        out.push_back(kron(db, k));
    }
    return out;
}

LikelihoodValue dense_likelihood(const HgpModel& model, const HgpData& data, bool with_gradient) {
    LikelihoodValue out;
    out.path = LikelihoodPath::Dense;
    const Index t = static_cast<Index>(data.frames());
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
        out.message = "non-finite dense log likelihood";
        return out;
    }
    out.ok = true;
    if (!with_gradient) return out;
    // W = α αᵀ − Σ⁻¹; ∂ log p/∂θ = ½ tr(W ∂Σ/∂θ) = ½ Σ_ij W_ij ∂Σ_ij.
    MatX w = alpha * alpha.transpose() - llt.solve(MatX::Identity(sigma.rows(), sigma.cols()));
    out.gradient = VecX::Zero(static_cast<Index>(model.parameter_count()));
    Index o = 0;
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
    const Index nt = static_cast<Index>(data.outputs()) * t;
    const MatX zero = MatX::Zero(nt, nt);
    for (Index d = 0; d < static_cast<Index>(model.outputs()); ++d) {
        VecX dn = VecX::Zero(nt);
        dn.segment(d * t, t).setConstant(std::exp(model.log_noise[d]));
        out.gradient[o++] = 0.5 * w.cwiseProduct(assemble_dense(l, nullptr, nullptr, &zero, &dn)).sum();
    }
    return out;
}

void check_times(const VecX& t_star) {
    if (t_star.size() == 0 || !t_star.allFinite()) throw InvalidArgument("prediction times: expected ≥ 1 finite time");
}

/// What a posterior is about: the trend g, group s's function h_s, or child r's latent f_r.
struct Target {
    enum Kind { Parent, Group, Child } kind = Parent;
    std::size_t index = 0;
};

GaussianPrediction condition_dense(const HgpModel& model, const HgpData& data, const VecX& t_star, Target target) {
    const Index d = static_cast<Index>(data.outputs());
    const Index ts = t_star.size();
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
    const Index n = static_cast<Index>(l.flat.size());
    MatX cross = MatX::Zero(d * ts, n);
    for (Index j = 0; j < n; ++j) {
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
    if (llt.info() != Eigen::Success) {
        p.mean = MatX::Constant(d, ts, std::nan(""));
        p.variance = p.mean;
        return p;
    }
    const VecX mean = cross * llt.solve(l.y);
    const MatX v = llt.matrixL().solve(cross.transpose());
    const VecX var = prior.diagonal() - v.colwise().squaredNorm().transpose();
    p.mean = unvec_output_major(mean, d, ts);
    p.variance = unvec_output_major(var, d, ts);
    return p;
}

// ---- Structured posteriors: Gaussians over a time grid, conditioned group by group -------------------

/// The data's times followed by the query times not among them; where each query time sits.
struct Grid {
    VecX z;
    std::vector<Index> query;
};

Grid make_grid(const VecX& times, const VecX& tq) {
    Grid g;
    std::vector<double> z(times.data(), times.data() + times.size());
    for (Index i = 0; i < tq.size(); ++i) {
        Index at = -1;
        for (Index j = 0; j < static_cast<Index>(z.size()); ++j)
            if (z[static_cast<std::size_t>(j)] == tq[i]) {
                at = j;
                break;
            }
        if (at < 0) {
            at = static_cast<Index>(z.size());
            z.push_back(tq[i]);
        }
        g.query.push_back(at);
    }
    g.z = Eigen::Map<const VecX>(z.data(), static_cast<Index>(z.size()));
    return g;
}

/// A Gaussian over D outputs at the grid times (output-major: index d·|z| + i).
struct GridGaussian {
    VecX mean;
    MatX cov;
    bool ok = true;
};

/// Indices of the grid entries at `frames` of the data times (which are the grid's first T), every output.
std::vector<Index> grid_indices(Index d, Index grid_size, const std::vector<Index>& frames) {
    std::vector<Index> idx;
    for (Index k = 0; k < d; ++k)
        for (Index f : frames) idx.push_back(k * grid_size + f);
    return idx;
}

std::vector<Index> all_frames(Index t) {
    std::vector<Index> f(static_cast<std::size_t>(t));
    for (Index i = 0; i < t; ++i) f[static_cast<std::size_t>(i)] = i;
    return f;
}

/// Conditions g on y = g[sel] + ε, ε ~ N(0, noise_cov). With !full_cov only the diagonal of the
/// covariance is updated (the last step of a prediction). False when the innovation covariance is not
/// positive definite.
bool condition(GridGaussian& g, const std::vector<Index>& sel, const VecX& y, const MatX& noise_cov,
               bool full_cov = true) {
    const Index m = static_cast<Index>(sel.size()), n = g.mean.size();
    MatX s = noise_cov;
    MatX c(m, n);
    VecX r(m);
    for (Index i = 0; i < m; ++i) {
        c.row(i) = g.cov.row(sel[static_cast<std::size_t>(i)]);
        r[i] = y[i] - g.mean[sel[static_cast<std::size_t>(i)]];
        for (Index j = 0; j < m; ++j)
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

/// Posterior of the trend g on the grid given the complete children `members` (structured).
/// Two layers: their mean ȳ = g + N(0, A / R'). Three layers: per group its members' mean, groups of one
/// size n_c averaged: ȳ_c = g + N(0, (A + n_c K_h) / (n_c S_c)), conditioned class by class.
GridGaussian trend_on_grid(const HgpModel& model, const HgpData& data, const std::vector<std::size_t>& members,
                           const Grid& grid) {
    const Index d = static_cast<Index>(data.outputs());
    const Index t = static_cast<Index>(data.frames());
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
    const Index d = static_cast<Index>(data.outputs());
    const Index t = static_cast<Index>(data.frames());
    VecX mean = VecX::Zero(d * t);
    for (std::size_t m : own) mean += vec_output_major(data.children[m]);
    const double rc = static_cast<double>(own.size());
    MatX a = lmc_covariance(model.child, data.times, data.times);
    a.diagonal() += flat_noise(model.noise_variance(), t);
    g.ok = condition(g, grid_indices(d, grid.z.size(), all_frames(t)), mean / rc, a / rc);
    return g;
}

GaussianPrediction nan_prediction(Index d, Index ts, const VecX& noise) {
    GaussianPrediction p;
    p.mean = MatX::Constant(d, ts, std::nan(""));
    p.variance = p.mean;
    p.noise = noise;
    return p;
}

/// The grid Gaussian at the query times: mean and full covariance (output-major over the queries).
GridGaussian at_queries(const GridGaussian& g, const Grid& grid, Index d) {
    const auto idx = grid_indices(d, grid.z.size(), grid.query);
    GridGaussian out;
    const Index m = static_cast<Index>(idx.size());
    out.mean.resize(m);
    out.cov.resize(m, m);
    for (Index i = 0; i < m; ++i) {
        out.mean[i] = g.mean[idx[static_cast<std::size_t>(i)]];
        for (Index j = 0; j < m; ++j)
            out.cov(i, j) = g.cov(idx[static_cast<std::size_t>(i)], idx[static_cast<std::size_t>(j)]);
    }
    out.ok = g.ok;
    return out;
}

/// The prior of child `child`'s latent f on the grid given its (complete) siblings: its parent function
/// (g, or h_s with three layers) given them, plus K_f.
GridGaussian child_prior_on_grid(const HgpModel& model, const HgpData& data, std::size_t child, const Grid& grid) {
    const Index d = static_cast<Index>(data.outputs());
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
    const Index d = static_cast<Index>(data.outputs());
    const Index t = static_cast<Index>(data.frames());
    std::vector<Index> frames;
    for (Index f = 0; f < t; ++f)
        if (mask ? (*mask)[static_cast<std::size_t>(f)] : data.is_observed(child, static_cast<std::size_t>(f)))
            frames.push_back(f);
    if (frames.empty()) return true;
    const auto sel = grid_indices(d, grid.z.size(), frames);
    const VecX y = vec_output_major(data.children[child]);
    const VecX noise = model.noise_variance();
    VecX yo(static_cast<Index>(sel.size()));
    VecX no(yo.size());
    const Index nf = static_cast<Index>(frames.size());
    for (Index k = 0; k < d; ++k)
        for (Index i = 0; i < nf; ++i) {
            yo[k * nf + i] = y[k * t + frames[static_cast<std::size_t>(i)]];
            no[k * nf + i] = noise[k];
        }
    return condition(g, sel, yo, no.asDiagonal().toDenseMatrix(), full_cov);
}

/// Mean and latent variance of a grid Gaussian at the grid's query times.
GaussianPrediction grid_prediction(const GridGaussian& g, const Grid& grid, Index d, const VecX& noise) {
    const Index ts = static_cast<Index>(grid.query.size());
    if (!g.ok) return nan_prediction(d, ts, noise);
    GaussianPrediction p;
    p.mean.resize(d, ts);
    p.variance.resize(d, ts);
    const Index nz = grid.z.size();
    for (Index k = 0; k < d; ++k)
        for (Index i = 0; i < ts; ++i) {
            const Index at = k * nz + grid.query[static_cast<std::size_t>(i)];
            p.mean(k, i) = g.mean[at];
            p.variance(k, i) = g.cov(at, at);
        }
    p.noise = noise;
    return p;
}

void draw_gaussian(const VecX& mean, const MatX& cov, std::size_t count, std::mt19937_64& rng, Index d, Index ts,
                   std::vector<MatX>& out) {
    // Cholesky with a small relative jitter (sampling only; the covariance may be numerically singular).
    const double scale = std::max(cov.diagonal().cwiseAbs().maxCoeff(), 1e-300);
    MatX jittered = cov;
    Eigen::LLT<MatX> llt;
    for (double jitter = 1e-10; jitter < 1.0; jitter *= 10.0) {
        jittered = cov;
        jittered.diagonal().array() += jitter * scale;
        llt.compute(jittered);
        if (llt.info() == Eigen::Success) break;
    }
    if (llt.info() != Eigen::Success) throw InvalidArgument("sample_children: covariance cannot be factorized");
    const MatX l = llt.matrixL();
    std::normal_distribution<double> normal(0.0, 1.0);
    for (std::size_t s = 0; s < count; ++s) {
        VecX xi(mean.size());
        for (Index i = 0; i < xi.size(); ++i) xi[i] = normal(rng);
        out.push_back(unvec_output_major(mean + l * xi, d, ts));
    }
}

}  // namespace

VecX HgpModel::noise_variance() const { return (log_noise.array().exp() + noise_floor).matrix(); }

std::size_t HgpModel::parameter_count() const {
    return child.parameter_count() + (grouped ? group.parameter_count() : 0) +
           (hierarchical ? parent.parameter_count() : 0) + static_cast<std::size_t>(log_noise.size());
}

VecX HgpModel::parameters() const {
    std::vector<double> p;
    for (const auto& t : child.terms) append_parameters(t, p);
    if (grouped)
        for (const auto& t : group.terms) append_parameters(t, p);
    if (hierarchical)
        for (const auto& t : parent.terms) append_parameters(t, p);
    for (Index i = 0; i < log_noise.size(); ++i) p.push_back(log_noise[i]);
    return Eigen::Map<const VecX>(p.data(), static_cast<Index>(p.size()));
}

void HgpModel::set_parameters(const VecX& p) {
    if (static_cast<std::size_t>(p.size()) != parameter_count())
        throw InvalidArgument("HgpModel::set_parameters: expected " + std::to_string(parameter_count()) +
                              " values, found " + std::to_string(p.size()));
    std::size_t o = 0;
    for (auto& t : child.terms) o = read_parameters(t, p, o);
    if (grouped)
        for (auto& t : group.terms) o = read_parameters(t, p, o);
    if (hierarchical)
        for (auto& t : parent.terms) o = read_parameters(t, p, o);
    for (Index i = 0; i < log_noise.size(); ++i) log_noise[i] = p[static_cast<Index>(o) + i];
}

std::vector<std::string> HgpModel::parameter_names() const {
    std::vector<std::string> names;
    auto add = [&](const Lmc& lmc, const std::string& layer) {
        for (std::size_t q = 0; q < lmc.terms.size(); ++q) {
            const auto& t = lmc.terms[q];
            const std::string pre = layer + ".q" + std::to_string(q) + ".";
            names.push_back(pre + "log_lengthscale");
            for (Index j = 0; j < t.W.cols(); ++j)
                for (Index i = 0; i < t.W.rows(); ++i)
                    names.push_back(pre + "W[" + std::to_string(i) + "," + std::to_string(j) + "]");
            for (Index i = 0; i < t.log_kappa.size(); ++i)
                names.push_back(pre + "log_kappa[" + std::to_string(i) + "]");
        }
    };
    add(child, "child");
    if (grouped) add(group, "group");
    if (hierarchical) add(parent, "parent");
    for (Index i = 0; i < log_noise.size(); ++i) names.push_back("log_noise[" + std::to_string(i) + "]");
    return names;
}

void validate(const HgpModel& model) {
    const std::size_t d = model.outputs();
    if (d == 0) throw InvalidArgument("HgpModel: no outputs (log_noise is empty)");
    if (!model.log_noise.allFinite()) throw InvalidArgument("HgpModel: non-finite log_noise");
    if (!(model.noise_floor >= 0.0) || !std::isfinite(model.noise_floor))
        throw InvalidArgument("HgpModel: noise_floor must be finite and ≥ 0");
    if (model.child.terms.empty()) throw InvalidArgument("HgpModel: the child LMC needs at least one term");
    validate(model.child, d, "child LMC");
    if (model.hierarchical) {
        if (model.parent.terms.empty()) throw InvalidArgument("HgpModel: the parent LMC needs at least one term");
        validate(model.parent, d, "parent LMC");
    }
    if (model.grouped) {
        if (!model.hierarchical) throw InvalidArgument("HgpModel: a grouped (three-layer) model must be hierarchical");
        if (model.group.terms.empty()) throw InvalidArgument("HgpModel: the group LMC needs at least one term");
        validate(model.group, d, "group LMC");
    }
}

bool HgpData::is_observed(std::size_t child, std::size_t frame) const {
    if (child >= observed.size() || observed[child].empty()) return true;
    return observed[child][frame];
}

bool HgpData::is_complete(std::size_t child) const {
    if (child >= observed.size()) return true;
    for (bool b : observed[child])
        if (!b) return false;
    return true;
}

bool HgpData::all_complete() const {
    for (std::size_t r = 0; r < children.size(); ++r)
        if (!is_complete(r)) return false;
    return true;
}

std::size_t HgpData::observed_value_count() const {
    std::size_t n = 0;
    for (std::size_t r = 0; r < children.size(); ++r)
        for (std::size_t f = 0; f < frames(); ++f)
            if (is_observed(r, f)) n += outputs();
    return n;
}

HgpData without_child(const HgpData& data, std::size_t child) {
    if (child >= data.child_count()) throw InvalidArgument("without_child: no child " + std::to_string(child));
    HgpData out;
    out.times = data.times;
    std::vector<std::size_t> kept_groups;
    for (std::size_t r = 0; r < data.child_count(); ++r) {
        if (r == child) continue;
        out.children.push_back(data.children[r]);
        if (r < data.observed.size()) {
            out.observed.resize(out.children.size());
            out.observed.back() = data.observed[r];
        }
        if (!data.groups.empty()) kept_groups.push_back(data.groups[r]);
    }
    std::vector<std::size_t> present = kept_groups;
    std::sort(present.begin(), present.end());
    present.erase(std::unique(present.begin(), present.end()), present.end());
    for (std::size_t g : kept_groups)
        out.groups.push_back(
            static_cast<std::size_t>(std::lower_bound(present.begin(), present.end(), g) - present.begin()));
    return out;
}

std::size_t HgpData::group_count() const {
    std::size_t s = 0;
    for (std::size_t g : groups) s = std::max(s, g + 1);
    return s;
}

std::size_t HgpData::balanced_group_size() const {
    const std::size_t s = group_count();
    if (s == 0) return 0;
    std::vector<std::size_t> size(s, 0);
    for (std::size_t g : groups) ++size[g];
    for (std::size_t n : size)
        if (n != size.front()) return 0;
    return size.front();
}

void validate(const HgpData& data) {
    if (data.times.size() == 0 || !data.times.allFinite())
        throw InvalidArgument("HgpData: expected ≥ 1 finite sample time");
    if (data.children.empty()) throw InvalidArgument("HgpData: no children");
    const Index d = data.children.front().rows();
    if (d == 0) throw InvalidArgument("HgpData: children have no outputs");
    if (data.observed.size() > data.children.size())
        throw InvalidArgument("HgpData: more observation masks than children");
    for (std::size_t r = 0; r < data.children.size(); ++r) {
        const MatX& y = data.children[r];
        if (y.rows() != d || y.cols() != data.times.size())
            throw InvalidArgument("HgpData: child " + std::to_string(r) + " is " + std::to_string(y.rows()) + " by " +
                                  std::to_string(y.cols()) + ", expected " + std::to_string(d) + " by " +
                                  std::to_string(data.times.size()));
        if (r < data.observed.size() && !data.observed[r].empty() &&
            data.observed[r].size() != static_cast<std::size_t>(data.times.size()))
            throw InvalidArgument("HgpData: child " + std::to_string(r) + "'s mask has " +
                                  std::to_string(data.observed[r].size()) + " flags, expected " +
                                  std::to_string(data.times.size()));
        for (Index f = 0; f < y.cols(); ++f)
            if (data.is_observed(r, static_cast<std::size_t>(f)) && !y.col(f).allFinite())
                throw InvalidArgument("HgpData: child " + std::to_string(r) +
                                      " has a non-finite observed value at frame " + std::to_string(f));
    }
    if (data.observed_value_count() == 0) throw InvalidArgument("HgpData: nothing is observed");
    if (!data.groups.empty()) {
        if (data.groups.size() != data.children.size())
            throw InvalidArgument("HgpData: " + std::to_string(data.groups.size()) + " group indices for " +
                                  std::to_string(data.children.size()) + " children");
        std::vector<bool> used(data.group_count(), false);
        for (std::size_t g : data.groups) used[g] = true;
        for (std::size_t g = 0; g < used.size(); ++g)
            if (!used[g])
                throw InvalidArgument("HgpData: group " + std::to_string(g) + " has no child (groups are 0..S−1)");
    }
}

namespace {
void check_model_data(const HgpModel& model, const HgpData& data, const char* what) {
    validate(model);
    validate(data);
    if (model.outputs() != data.outputs())
        throw InvalidArgument(std::string(what) + ": model has " + std::to_string(model.outputs()) + " outputs, data " +
                              std::to_string(data.outputs()));
    if (model.grouped && data.groups.empty())
        throw InvalidArgument(std::string(what) + ": a three-layer model needs each child's group (HgpData::groups)");
}

/// Whether the structured and low-rank likelihoods apply: every child complete.
bool structure_applies(const HgpData& data) { return data.all_complete(); }
}  // namespace

LikelihoodValue log_likelihood(const HgpModel& model, const HgpData& data, bool with_gradient, LikelihoodPath path,
                               int threads) {
    check_model_data(model, data, "log_likelihood");
    const bool structured = structure_applies(data);
    if ((path == LikelihoodPath::Structured || path == LikelihoodPath::LowRank) && !structured)
        throw InvalidArgument(
            "log_likelihood: the structured and low-rank paths need every child complete (use Dense or Auto)");
    if (path == LikelihoodPath::Dense || (path == LikelihoodPath::Auto && !structured))
        return dense_likelihood(model, data, with_gradient);
    if (path == LikelihoodPath::Structured) return detail::structured_likelihood(model, data, with_gradient, threads);
    const detail::Levels levels = detail::make_levels(model, data);
    if (path == LikelihoodPath::LowRank)
        return detail::low_rank_likelihood(model, data, levels, with_gradient, threads);
    // Auto, every child complete.
    if (detail::low_rank_is_cheaper(model, data, levels)) {
        LikelihoodValue v = detail::low_rank_likelihood(model, data, levels, with_gradient, threads);
        if (v.ok) return v;
        // P (the κ and noise blocks) may be singular while the full covariance is not.
    }
    return detail::structured_likelihood(model, data, with_gradient, threads);
}

namespace {
void check_prediction_args(const HgpModel& model, const HgpData& data, const VecX& t_star) {
    check_model_data(model, data, "prediction");
    check_times(t_star);
}

std::vector<std::size_t> all_children(const HgpData& data) {
    std::vector<std::size_t> all(data.child_count());
    for (std::size_t r = 0; r < all.size(); ++r) all[r] = r;
    return all;
}
}  // namespace

GaussianPrediction predict_parent_dense(const HgpModel& model, const HgpData& data, const VecX& t_star) {
    check_prediction_args(model, data, t_star);
    if (!model.hierarchical) throw InvalidArgument("predict_parent: the MOA baseline has no parent");
    return condition_dense(model, data, t_star, Target{Target::Parent, 0});
}

namespace {
void check_group(const HgpModel& model, const HgpData& data, std::size_t group) {
    if (!model.grouped) throw InvalidArgument("predict_group: the model has no group layer");
    if (group >= data.group_count()) throw InvalidArgument("predict_group: no group " + std::to_string(group));
}
}  // namespace

GaussianPrediction predict_group_dense(const HgpModel& model, const HgpData& data, std::size_t group,
                                       const VecX& t_star) {
    check_prediction_args(model, data, t_star);
    check_group(model, data, group);
    return condition_dense(model, data, t_star, Target{Target::Group, group});
}

GaussianPrediction predict_group(const HgpModel& model, const HgpData& data, std::size_t group, const VecX& t_star) {
    check_prediction_args(model, data, t_star);
    check_group(model, data, group);
    if (!data.all_complete()) return condition_dense(model, data, t_star, Target{Target::Group, group});
    const Grid grid = make_grid(data.times, t_star);
    const Index d = static_cast<Index>(data.outputs());
    return grid_prediction(group_on_grid(model, data, group, -1, grid), grid, d, model.noise_variance());
}

GaussianPrediction predict_child_dense(const HgpModel& model, const HgpData& data, std::size_t child,
                                       const VecX& t_star) {
    check_prediction_args(model, data, t_star);
    if (child >= data.child_count()) throw InvalidArgument("predict_child: no child " + std::to_string(child));
    if (!model.hierarchical) {
        // MOA: the siblings are independent of the child; condition on its own values only.
        HgpData own;
        own.times = data.times;
        own.children = {data.children[child]};
        if (child < data.observed.size()) own.observed = {data.observed[child]};
        bool any = false;
        for (std::size_t f = 0; f < own.frames(); ++f) any = any || own.is_observed(0, f);
        if (!any) {
            GaussianPrediction p;
            p.mean = MatX::Zero(static_cast<Index>(data.outputs()), t_star.size());
            p.variance = unvec_output_major(lmc_covariance(model.child, t_star, t_star).diagonal(),
                                            static_cast<Index>(data.outputs()), t_star.size());
            p.noise = model.noise_variance();
            return p;
        }
        return condition_dense(model, own, t_star, Target{Target::Child, 0});
    }
    return condition_dense(model, data, t_star, Target{Target::Child, child});
}

GaussianPrediction predict_parent(const HgpModel& model, const HgpData& data, const VecX& t_star) {
    check_prediction_args(model, data, t_star);
    if (!model.hierarchical) throw InvalidArgument("predict_parent: the MOA baseline has no parent");
    if (!data.all_complete()) return condition_dense(model, data, t_star, Target{Target::Parent, 0});
    const Grid grid = make_grid(data.times, t_star);
    const Index d = static_cast<Index>(data.outputs());
    return grid_prediction(trend_on_grid(model, data, all_children(data), grid), grid, d, model.noise_variance());
}

GaussianPrediction predict_child(const HgpModel& model, const HgpData& data, std::size_t child, const VecX& t_star) {
    check_prediction_args(model, data, t_star);
    if (child >= data.child_count()) throw InvalidArgument("predict_child: no child " + std::to_string(child));
    bool siblings_complete = true;
    for (std::size_t r = 0; r < data.child_count(); ++r)
        if (r != child && !data.is_complete(r)) siblings_complete = false;
    if (model.hierarchical && !siblings_complete)
        return condition_dense(model, data, t_star, Target{Target::Child, child});
    const Grid grid = make_grid(data.times, t_star);
    GridGaussian g = child_prior_on_grid(model, data, child, grid);
    if (g.ok) g.ok = condition_on_own_frames(g, model, data, child, nullptr, grid, false);
    return grid_prediction(g, grid, static_cast<Index>(data.outputs()), model.noise_variance());
}

std::vector<GaussianPrediction> predict_child_masks(const HgpModel& model, const HgpData& data, std::size_t child,
                                                    const std::vector<std::vector<bool>>& masks) {
    check_prediction_args(model, data, data.times);
    if (child >= data.child_count()) throw InvalidArgument("predict_child_masks: no child " + std::to_string(child));
    for (std::size_t r = 0; r < data.child_count(); ++r)
        if (r != child && !data.is_complete(r))
            throw InvalidArgument("predict_child_masks: sibling " + std::to_string(r) + " has missing frames");
    for (const auto& m : masks)
        if (m.size() != data.frames())
            throw InvalidArgument("predict_child_masks: a mask has " + std::to_string(m.size()) + " flags, expected " +
                                  std::to_string(data.frames()));
    const Grid grid = make_grid(data.times, data.times);
    const GridGaussian prior = child_prior_on_grid(model, data, child, grid);
    std::vector<GaussianPrediction> out;
    for (const auto& m : masks) {
        GridGaussian g = prior;
        if (g.ok) g.ok = condition_on_own_frames(g, model, data, child, &m, grid, false);
        out.push_back(grid_prediction(g, grid, static_cast<Index>(data.outputs()), model.noise_variance()));
    }
    return out;
}

MatX synthesis_trend(const HgpModel& model, const HgpData& data, const VecX& t_star) {
    check_prediction_args(model, data, t_star);
    if (model.hierarchical) return predict_parent(model, data, t_star).mean;
    // MOA: every observed value of every child is a noisy observation of one function f ~ GP(0, K_f).
    const Index t = static_cast<Index>(data.frames());
    const Index d = static_cast<Index>(data.outputs());
    if (data.all_complete()) {
        // R complete replicates at the same times: their mean ȳ is sufficient, with noise N/R
        // (one (D·T)² factorization instead of (R·D·T)²).
        const double rd = static_cast<double>(data.child_count());
        VecX mean = VecX::Zero(d * t);
        for (const MatX& y : data.children) mean += vec_output_major(y);
        mean /= rd;
        MatX s = lmc_covariance(model.child, data.times, data.times);
        s.diagonal() += flat_noise(model.noise_variance(), t) / rd;
        Eigen::LLT<MatX> llt(s);
        if (llt.info() != Eigen::Success) return MatX::Constant(d, t_star.size(), std::nan(""));
        return unvec_output_major(lmc_covariance(model.child, t_star, data.times) * llt.solve(mean), d, t_star.size());
    }
    const DenseLayout l = dense_layout(data);
    const MatX kf = lmc_covariance(model.child, data.times, data.times);
    const VecX noise = flat_noise(model.noise_variance(), t);
    const Index n = static_cast<Index>(l.flat.size());
    MatX s(n, n);
    for (Index j = 0; j < n; ++j)
        for (Index i = 0; i < n; ++i) s(i, j) = kf(l.flat[i], l.flat[j]) + (i == j ? noise[l.flat[i]] : 0.0);
    const MatX ks = lmc_covariance(model.child, t_star, data.times);
    MatX cross(d * t_star.size(), n);
    for (Index j = 0; j < n; ++j) cross.col(j) = ks.col(l.flat[j]);
    Eigen::LLT<MatX> llt(s);
    if (llt.info() != Eigen::Success) return MatX::Constant(d, t_star.size(), std::nan(""));
    return unvec_output_major(cross * llt.solve(l.y), d, t_star.size());
}

std::vector<MatX> sample_children(const HgpModel& model, const HgpData& data, const VecX& t_star, std::size_t count,
                                  const SampleOptions& options) {
    check_prediction_args(model, data, t_star);
    const Index d = static_cast<Index>(data.outputs());
    const Index ts = t_star.size();
    VecX mean;
    MatX cov = lmc_covariance(model.child, t_star, t_star);
    const bool posterior_needed = options.group.has_value() || (model.hierarchical && options.parent_uncertainty);
    if (posterior_needed && !data.all_complete())
        throw InvalidArgument("sample_children: parent_uncertainty and group need every child complete");
    if (options.group) {
        // A new child of an existing group: that group's function's posterior, then K_f.
        check_group(model, data, *options.group);
        const Grid grid = make_grid(data.times, t_star);
        const GridGaussian pg = at_queries(group_on_grid(model, data, *options.group, -1, grid), grid, d);
        if (!pg.ok) throw InvalidArgument("sample_children: the group posterior cannot be computed");
        mean = pg.mean;
        if (options.parent_uncertainty) cov += pg.cov;
    } else {
        // Three layers: a new child of a new group deviates from the trend by h + f.
        if (model.grouped) cov += lmc_covariance(model.group, t_star, t_star);
        if (model.hierarchical && options.parent_uncertainty) {
            const Grid grid = make_grid(data.times, t_star);
            const GridGaussian pp = at_queries(trend_on_grid(model, data, all_children(data), grid), grid, d);
            if (!pp.ok) throw InvalidArgument("sample_children: the parent posterior cannot be computed");
            mean = pp.mean;
            cov += pp.cov;
        } else {
            mean = vec_output_major(synthesis_trend(model, data, t_star));
        }
    }
    if (!mean.allFinite())
        throw InvalidArgument("sample_children: the trend could not be computed (covariance not positive definite)");
    if (options.add_noise) cov.diagonal() += flat_noise(model.noise_variance(), ts);
    std::mt19937_64 rng(options.seed);
    std::vector<MatX> out;
    draw_gaussian(mean, cov, count, rng, d, ts, out);
    return out;
}

}  // namespace mocapdb::gp
