#include "structured_likelihood.hpp"

#include <cmath>
#include <functional>
#include <map>

#include <Eigen/Cholesky>

#include "gp_internal.hpp"
#include "mocapdb/core/error.hpp"

namespace mocapdb::gp::detail {

namespace {

/// X = K_f + noise + a·K_h + b·K_g at the shared times.
MatX level_covariance(const HgpModel& model, const VecX& times, const VecX& noise_flat, double a, double b) {
    MatX x = lmc_covariance(model.child, times, times);
    x.diagonal() += noise_flat;
    if (a != 0.0) x.noalias() += a * lmc_covariance(model.group, times, times);
    if (b != 0.0) x.noalias() += b * lmc_covariance(model.parent, times, times);
    return x;
}

std::string level_name(double a, double b) {
    std::string s = "K_f + noise";
    if (a != 0.0) s += " + " + std::to_string(static_cast<long long>(a)) + "·K_h";
    if (b != 0.0) s += " + " + std::to_string(static_cast<long long>(b)) + "·K_g";
    return s;
}

/// Adds ½ tr(W ∂X/∂θ) for X = c_f·(K_f + noise) + c_h·K_h + c_g·K_g (layers with a zero weight skipped).
void add_layer_gradients(const HgpModel& model, const MatX& w, const VecX& times, double cf, double ch, double cg,
                         const ParameterOffsets& off, VecX& grad) {
    auto layer = [&](const Lmc& lmc, double weight, std::size_t offset) {
        if (weight == 0.0) return;
        VecX tmp(static_cast<Eigen::Index>(lmc.parameter_count()));
        std::size_t o = 0;
        for (const auto& term : lmc.terms) o = lmc_term_gradient(term, w, times, o, tmp);
        grad.segment(static_cast<Eigen::Index>(offset), tmp.size()) += weight * tmp;
    };
    layer(model.child, cf, off.child);
    if (model.grouped) layer(model.group, ch, off.group);
    if (model.hierarchical) layer(model.parent, cg, off.parent);
    if (cf == 0.0) return;
    const Eigen::Index t = times.size();
    for (Eigen::Index i = 0; i < model.log_noise.size(); ++i)
        grad[static_cast<Eigen::Index>(off.noise) + i] +=
            cf * 0.5 * w.diagonal().segment(i * t, t).sum() * std::exp(model.log_noise[i]);
}

/// One level's share of the likelihood and of the gradient.
struct LevelResult {
    LikelihoodStatus status = LikelihoodStatus::NotPositiveDefinite;  ///< until computed
    double value = 0.0;
    VecX gradient;
    std::string message;
};

/// The coupled size classes (three layers, unequal groups): w_c = √R_c ȳ_c are jointly
/// N(0, blockdiag(C_c) + v vᵀ ⊗ B) with v_c = √R_c, C_c = K_f + noise + n_c K_h, B = K_g. With
/// M = Σ R_c C_c⁻¹ = L Lᵀ, J = I + Lᵀ B L and F = (B⁻¹ + M)⁻¹ = B − B L J⁻¹ Lᵀ B (B may be singular
/// and is never inverted):
///   log det = Σ log det C_c + log det J,  quad = Σ R_c ȳ_cᵀ C_c⁻¹ ȳ_c − bᵀ F b,  b = Σ R_c C_c⁻¹ ȳ_c.
/// Gradient (W = α αᵀ − Σ⁻¹), with a_c = C_c⁻¹ (ȳ_c − F b) and β = Σ R_c a_c:
///   W_cc = R_c a_c a_cᵀ − C_c⁻¹ + R_c C_c⁻¹ F C_c⁻¹          through C_c (K_f, noise, n_c·K_h)
///   Σ_cc' √(R_c R_c') W_cc' = β βᵀ − M + M F M                through B (K_g).
LevelResult coupled_classes(const HgpModel& model, const HgpData& data, const std::vector<CoupledClass>& classes,
                            const VecX& noise_flat, bool with_gradient, int threads, const ParameterOffsets& off,
                            Eigen::Index parameters) {
    LevelResult res;
    const std::size_t k = classes.size();
    std::vector<MatX> cinv(k);
    std::vector<VecX> p(k);
    std::vector<double> logdet(k, 0.0);
    std::vector<char> ok(k, 0);
    std::vector<std::function<void()>> tasks;
    for (std::size_t c = 0; c < k; ++c)
        tasks.push_back([&, c] {
            MatX x = level_covariance(model, data.times, noise_flat, classes[c].group_size, 0.0);
            if (!factor_in_place(x, logdet[c])) return;
            p[c] = classes[c].mean;
            x.triangularView<Eigen::Lower>().solveInPlace(p[c]);
            x.triangularView<Eigen::Lower>().transpose().solveInPlace(p[c]);
            invert_from_factor_in_place(x);
            cinv[c] = std::move(x);
            ok[c] = 1;
        });
    run_tasks(tasks, threads);
    for (std::size_t c = 0; c < k; ++c)
        if (!ok[c]) {
            res.message = level_name(classes[c].group_size, 0.0) + " is not positive definite";
            return res;
        }
    const Eigen::Index n = classes.front().mean.size();
    MatX m = MatX::Zero(n, n);
    VecX b = VecX::Zero(n);
    double quad = 0.0, sum_logdet = 0.0;
    for (std::size_t c = 0; c < k; ++c) {
        m.noalias() += classes[c].children * cinv[c];
        b.noalias() += classes[c].children * p[c];
        quad += classes[c].children * classes[c].mean.dot(p[c]);
        sum_logdet += logdet[c];
    }
    Eigen::LLT<MatX> llt_m(m);
    if (llt_m.info() != Eigen::Success) {
        res.message = "Σ R_c C_c⁻¹ is not positive definite";
        return res;
    }
    const MatX l = llt_m.matrixL();
    const MatX bg = lmc_covariance(model.parent, data.times, data.times);
    const MatX bl = bg * l;
    MatX j = MatX::Identity(n, n);
    j.noalias() += l.transpose() * bl;
    double logdet_j = 0.0;
    if (!factor_in_place(j, logdet_j)) {
        res.message = "I + Lᵀ K_g L is not positive definite";
        return res;
    }
    MatX h = bl.transpose();  // Lᵀ B
    j.triangularView<Eigen::Lower>().solveInPlace(h);
    MatX f = bg;
    f.noalias() -= h.transpose() * h;  // B − B L J⁻¹ Lᵀ B
    const VecX fb = f * b;
    quad -= b.dot(fb);
    res.value = -0.5 * (quad + sum_logdet + logdet_j);
    res.status = std::isfinite(res.value) ? LikelihoodStatus::Ok : LikelihoodStatus::NonFinite;
    if (res.status != LikelihoodStatus::Ok) {
        res.message = "non-finite log likelihood of the coupled size classes";
        return res;
    }
    if (!with_gradient) return res;
    res.gradient = VecX::Zero(parameters);
    VecX beta = VecX::Zero(n);
    for (std::size_t c = 0; c < k; ++c) {
        const double rc = classes[c].children;
        const VecX a = cinv[c] * (classes[c].mean - fb);
        beta += rc * a;
        const MatX tmp = f * cinv[c];
        MatX w = -cinv[c];
        w.noalias() += rc * cinv[c] * tmp;
        w.noalias() += rc * a * a.transpose();
        add_layer_gradients(model, w, data.times, 1.0, classes[c].group_size, 0.0, off, res.gradient);
    }
    MatX wb = beta * beta.transpose() - m;
    const MatX fm = f * m;
    wb.noalias() += m * fm;
    add_layer_gradients(model, wb, data.times, 0.0, 0.0, 1.0, off, res.gradient);
    return res;
}

LikelihoodValue combine(std::vector<LevelResult>& parts, LikelihoodPath path, double constant, bool with_gradient,
                        Eigen::Index parameters) {
    LikelihoodValue out;
    out.path = path;
    out.log_likelihood = constant;
    if (with_gradient) out.gradient = VecX::Zero(parameters);
    for (const auto& p : parts) {
        if (p.status != LikelihoodStatus::Ok) {
            out.status = p.status;
            out.message = p.message;
            out.gradient.resize(0);
            return out;
        }
        out.log_likelihood += p.value;
        if (with_gradient) out.gradient += p.gradient;
    }
    if (!std::isfinite(out.log_likelihood)) {
        out.status = LikelihoodStatus::NonFinite;
        out.message = "non-finite log likelihood";
        out.gradient.resize(0);
        return out;
    }
    out.status = LikelihoodStatus::Ok;
    return out;
}

}  // namespace

Levels make_levels(const HgpModel& model, const HgpData& data) {
    if (!data.all_complete()) throw InvalidArgument("structured likelihood: every child must be complete");
    const Eigen::Index t = static_cast<Eigen::Index>(data.frames());
    const Eigen::Index n = static_cast<Eigen::Index>(data.outputs()) * t;
    const Eigen::Index r = static_cast<Eigen::Index>(data.child_count());
    const double rd = static_cast<double>(r);
    MatX ys(n, r);
    for (Eigen::Index c = 0; c < r; ++c) ys.col(c) = vec_output_major(data.children[static_cast<std::size_t>(c)]);
    Levels lv;
    if (!model.hierarchical) {
        lv.independent.push_back({ys, rd, 0.0, 0.0});
        return lv;
    }
    if (!model.grouped) {
        const VecX mean = ys.rowwise().mean();
        if (r > 1) lv.independent.push_back({ys.colwise() - mean, rd - 1.0, 0.0, 0.0});
        lv.independent.push_back({std::sqrt(rd) * mean, 1.0, 0.0, rd});
        return lv;
    }
    if (data.groups.size() != data.child_count())
        throw InvalidArgument("a three-layer model needs each child's group (HgpData::groups)");
    const std::size_t s = data.group_count();
    MatX group_mean = MatX::Zero(n, static_cast<Eigen::Index>(s));
    std::vector<std::size_t> size(s, 0);
    for (std::size_t c = 0; c < data.child_count(); ++c) {
        group_mean.col(static_cast<Eigen::Index>(data.groups[c])) += ys.col(static_cast<Eigen::Index>(c));
        ++size[data.groups[c]];
    }
    for (std::size_t g = 0; g < s; ++g) group_mean.col(static_cast<Eigen::Index>(g)) /= static_cast<double>(size[g]);
    // Deviations from the group means: R − S independent directions.
    if (data.child_count() > s) {
        MatX e(n, r);
        for (std::size_t c = 0; c < data.child_count(); ++c)
            e.col(static_cast<Eigen::Index>(c)) =
                ys.col(static_cast<Eigen::Index>(c)) - group_mean.col(static_cast<Eigen::Index>(data.groups[c]));
        lv.independent.push_back({std::move(e), rd - static_cast<double>(s), 0.0, 0.0});
    }
    // Groups of one size n_c: √n_c·ȳ_s ~ N(√n_c·g, C_c), deviations from their class mean: S_c − 1 directions.
    std::map<std::size_t, std::vector<std::size_t>> classes;
    for (std::size_t g = 0; g < s; ++g) classes[size[g]].push_back(g);
    std::vector<CoupledClass> coupled;
    for (const auto& [nc, members] : classes) {
        const double ncd = static_cast<double>(nc), sc = static_cast<double>(members.size());
        VecX mean = VecX::Zero(n);
        for (std::size_t g : members) mean += group_mean.col(static_cast<Eigen::Index>(g));
        mean /= sc;
        if (members.size() > 1) {
            MatX e(n, static_cast<Eigen::Index>(members.size()));
            for (std::size_t i = 0; i < members.size(); ++i)
                e.col(static_cast<Eigen::Index>(i)) =
                    std::sqrt(ncd) * (group_mean.col(static_cast<Eigen::Index>(members[i])) - mean);
            lv.independent.push_back({std::move(e), sc - 1.0, ncd, 0.0});
        }
        coupled.push_back({std::move(mean), ncd, ncd * sc});
    }
    if (coupled.size() == 1)
        lv.independent.push_back({std::sqrt(rd) * coupled.front().mean, 1.0, coupled.front().group_size, rd});
    else lv.coupled = std::move(coupled);
    return lv;
}

ParameterOffsets parameter_offsets(const HgpModel& model) {
    ParameterOffsets o;
    o.child = 0;
    o.group = model.child.parameter_count();
    o.parent = o.group + (model.grouped ? model.group.parameter_count() : 0);
    o.noise = o.parent + (model.hierarchical ? model.parent.parameter_count() : 0);
    return o;
}

LikelihoodValue structured_likelihood(const HgpModel& model, const HgpData& data, bool with_gradient, int threads) {
    const Levels lv = make_levels(model, data);
    const Eigen::Index t = static_cast<Eigen::Index>(data.frames());
    const Eigen::Index n = static_cast<Eigen::Index>(data.outputs()) * t;
    const VecX noise_flat = flat_noise(model.noise_variance(), t);
    const ParameterOffsets off = parameter_offsets(model);
    const Eigen::Index parameters = static_cast<Eigen::Index>(model.parameter_count());
    std::vector<LevelResult> parts(lv.independent.size());
    std::vector<std::function<void()>> tasks;
    for (std::size_t k = 0; k < lv.independent.size(); ++k)
        tasks.push_back([&, k] {
            const Level& lev = lv.independent[k];
            LevelResult& res = parts[k];
            MatX x = level_covariance(model, data.times, noise_flat, lev.group_weight, lev.parent_weight);
            double logdet = 0.0;
            if (!factor_in_place(x, logdet)) {
                res.message = level_name(lev.group_weight, lev.parent_weight) + " is not positive definite";
                return;
            }
            MatX p = lev.e;
            x.triangularView<Eigen::Lower>().solveInPlace(p);
            const double quad = p.squaredNorm();
            x.triangularView<Eigen::Lower>().transpose().solveInPlace(p);
            res.value = -0.5 * (quad + lev.count * logdet);
            res.status = std::isfinite(res.value) ? LikelihoodStatus::Ok : LikelihoodStatus::NonFinite;
            if (res.status != LikelihoodStatus::Ok)
                res.message = "non-finite log likelihood of " + level_name(lev.group_weight, lev.parent_weight);
            if (res.status != LikelihoodStatus::Ok || !with_gradient) return;
            invert_from_factor_in_place(x);
            MatX& w = x;  // W = P Pᵀ − count·X⁻¹
            w *= -lev.count;
            w.noalias() += p * p.transpose();
            res.gradient = VecX::Zero(parameters);
            add_layer_gradients(model, w, data.times, 1.0, lev.group_weight, lev.parent_weight, off, res.gradient);
        });
    // The coupled classes need every class's factor: they run after the independent levels (each on
    // two threads over its classes).
    run_tasks(tasks, threads);
    if (!lv.coupled.empty())
        parts.push_back(coupled_classes(model, data, lv.coupled, noise_flat, with_gradient, threads, off, parameters));
    const double constant = -0.5 * static_cast<double>(data.child_count()) * static_cast<double>(n) * kLog2Pi;
    return combine(parts, LikelihoodPath::Structured, constant, with_gradient, parameters);
}

namespace {

struct LayerFactors {
    std::vector<KernelFactor> child, group, parent;
};

LayerFactors layer_factors(const HgpModel& model, const VecX& times) {
    LayerFactors f;
    for (const auto& term : model.child.terms) f.child.push_back(factor_kernel(term, times));
    if (model.grouped)
        for (const auto& term : model.group.terms) f.group.push_back(factor_kernel(term, times));
    if (model.hierarchical)
        for (const auto& term : model.parent.terms) f.parent.push_back(factor_kernel(term, times));
    return f;
}

/// One level of the low-rank path: columns e over D outputs × `frames`, covariance Σ weight·B_q ⊗ k_q
/// (+ noise), each term with the offset of its parameters.
struct LowRankLevel {
    MatX e;
    double count = 1.0;
    Eigen::Index frames = 0;
    std::vector<WeightedTerm> terms;
    std::vector<std::size_t> offsets;
    std::string name;
};

void add_terms(const Lmc& lmc, const std::vector<KernelFactor>& factors, double weight, std::size_t offset,
               LowRankLevel& level) {
    if (weight == 0.0) return;
    for (std::size_t q = 0; q < lmc.terms.size(); ++q) {
        level.terms.push_back({&lmc.terms[q], &factors[q], weight});
        level.offsets.push_back(offset);
        offset += lmc.terms[q].parameter_count();
    }
}

/// The low-rank levels: the independent ones over the shared times, and the coupled size classes
/// (if any) as one covariance over D outputs × (class, time): with v_c = √R_c,
///   Σ = Σ_q B_q^f ⊗ (I ⊗ k_q) + Σ_q B_q^h ⊗ (diag(n_c) ⊗ k_q) + Σ_q B_q^g ⊗ (v vᵀ ⊗ k_q) + noise,
/// an LMC over extended inputs whose kernels stay factored (extended_factor). `extended` holds their
/// factors (it must outlive the levels).
std::vector<LowRankLevel> low_rank_levels(const HgpModel& model, const HgpData& data, const Levels& levels,
                                          const LayerFactors& f, std::vector<KernelFactor>& extended) {
    const ParameterOffsets off = parameter_offsets(model);
    const Eigen::Index t = static_cast<Eigen::Index>(data.frames());
    std::vector<LowRankLevel> out;
    for (const Level& lev : levels.independent) {
        LowRankLevel l;
        l.e = lev.e;
        l.count = lev.count;
        l.frames = t;
        l.name = level_name(lev.group_weight, lev.parent_weight);
        add_terms(model.child, f.child, 1.0, off.child, l);
        if (model.grouped) add_terms(model.group, f.group, lev.group_weight, off.group, l);
        if (model.hierarchical) add_terms(model.parent, f.parent, lev.parent_weight, off.parent, l);
        out.push_back(std::move(l));
    }
    if (levels.coupled.empty()) return out;
    const Eigen::Index k = static_cast<Eigen::Index>(levels.coupled.size());
    const Eigen::Index d = static_cast<Eigen::Index>(data.outputs());
    VecX ones = VecX::Ones(k), sizes(k), v(k);
    for (Eigen::Index c = 0; c < k; ++c) {
        sizes[c] = levels.coupled[static_cast<std::size_t>(c)].group_size;
        v[c] = std::sqrt(levels.coupled[static_cast<std::size_t>(c)].children);
    }
    LowRankLevel l;
    l.frames = k * t;
    l.name = "the coupled size classes";
    l.e.resize(d * k * t, 1);
    for (Eigen::Index c = 0; c < k; ++c) {
        const VecX& mean = levels.coupled[static_cast<std::size_t>(c)].mean;
        for (Eigen::Index i = 0; i < d; ++i) l.e.block(i * k * t + c * t, 0, t, 1) = v[c] * mean.segment(i * t, t);
    }
    // Reserved: the levels point into `extended`.
    extended.clear();
    extended.reserve(model.child.terms.size() + model.group.terms.size() + model.parent.terms.size());
    auto add = [&](const Lmc& lmc, const std::vector<KernelFactor>& base, const VecX& a, bool rank1,
                   std::size_t offset) {
        for (std::size_t q = 0; q < lmc.terms.size(); ++q) {
            extended.push_back(extended_factor(lmc.terms[q], base[q], data.times, a, rank1));
            l.terms.push_back({&lmc.terms[q], &extended.back(), 1.0});
            l.offsets.push_back(offset);
            offset += lmc.terms[q].parameter_count();
        }
    };
    add(model.child, f.child, ones, false, off.child);
    add(model.group, f.group, sizes, false, off.group);
    add(model.parent, f.parent, v, true, off.parent);
    out.push_back(std::move(l));
    return out;
}

}  // namespace

LikelihoodValue low_rank_likelihood(const HgpModel& model, const HgpData& data, const Levels& levels,
                                    bool with_gradient, int threads) {
    const Eigen::Index d = static_cast<Eigen::Index>(data.outputs());
    const Eigen::Index n = d * static_cast<Eigen::Index>(data.frames());
    const VecX noise = model.noise_variance();
    const ParameterOffsets off = parameter_offsets(model);
    const Eigen::Index parameters = static_cast<Eigen::Index>(model.parameter_count());
    const LayerFactors f = layer_factors(model, data.times);
    std::vector<KernelFactor> extended;
    const std::vector<LowRankLevel> lr = low_rank_levels(model, data, levels, f, extended);
    std::vector<LevelResult> parts(lr.size());
    std::vector<std::function<void()>> tasks;
    for (std::size_t k = 0; k < lr.size(); ++k)
        tasks.push_back([&, k] {
            const LowRankLevel& lev = lr[k];
            LevelResult& res = parts[k];
            BlockLowRank fx;
            std::string msg;
            if (!fx.build(lev.terms, noise, lev.frames, msg)) {
                res.message = lev.name + ": " + msg;
                return;
            }
            const MatX p = fx.solve(lev.e);
            res.value = -0.5 * (lev.e.cwiseProduct(p).sum() + lev.count * fx.log_det);
            res.status = std::isfinite(res.value) ? LikelihoodStatus::Ok : LikelihoodStatus::NonFinite;
            if (res.status != LikelihoodStatus::Ok) res.message = "non-finite log likelihood of " + lev.name;
            if (res.status != LikelihoodStatus::Ok || !with_gradient) return;
            // W = P Pᵀ − count·X⁻¹ = P Pᵀ − count·P_X⁻¹ + count·V K⁻¹ Vᵀ (block_low_rank.hpp).
            const Eigen::Index cols = p.cols(), m = fx.v.cols(), rows = lev.e.rows();
            StructuredSymmetric g;
            g.blocks.resize(static_cast<std::size_t>(d));
            for (Eigen::Index i = 0; i < d; ++i)
                g.blocks[static_cast<std::size_t>(i)] = -lev.count * fx.p_inverse[static_cast<std::size_t>(i)];
            g.u.resize(rows, cols + m);
            g.x.resize(rows, cols + m);
            g.u.leftCols(cols) = p;
            g.x.leftCols(cols) = p;
            if (m > 0) {
                g.u.rightCols(m) = fx.v;
                g.x.rightCols(m).noalias() = lev.count * fx.v * fx.cap_inverse;
            }
            res.gradient = VecX::Zero(parameters);
            for (std::size_t j = 0; j < lev.terms.size(); ++j)
                structured_term_gradient(*lev.terms[j].term, *lev.terms[j].factor, g, lev.terms[j].weight, data.times,
                                         lev.offsets[j], res.gradient);
            const VecX tr = structured_block_traces(g, d, lev.frames);
            for (Eigen::Index i = 0; i < d; ++i)
                res.gradient[static_cast<Eigen::Index>(off.noise) + i] = 0.5 * tr[i] * std::exp(model.log_noise[i]);
        });
    run_tasks(tasks, threads);
    const double constant = -0.5 * static_cast<double>(data.child_count()) * static_cast<double>(n) * kLog2Pi;
    return combine(parts, LikelihoodPath::LowRank, constant, with_gradient, parameters);
}

bool low_rank_is_cheaper(const HgpModel& model, const HgpData& data, const Levels& levels) {
    const Eigen::Index d = static_cast<Eigen::Index>(data.outputs());
    const double n = static_cast<double>(d * static_cast<Eigen::Index>(data.frames())), dd = static_cast<double>(d);
    const LayerFactors f = layer_factors(model, data.times);
    std::vector<KernelFactor> extended;
    double structured = 0.0, low_rank = 0.0;
    for (const LowRankLevel& lev : low_rank_levels(model, data, levels, f, extended)) {
        const double td = static_cast<double>(lev.frames), rows = dd * td;
        // Structured: a factorization and an inverse per level; the coupled classes about 12 n³.
        structured += lev.frames == static_cast<Eigen::Index>(data.frames()) ? n * n * n : 12.0 * n * n * n;
        const double m = static_cast<double>(BlockLowRank::rank_of(lev.terms));
        const double width = static_cast<double>(lev.e.cols()) + m;
        low_rank += 3.0 * dd * td * td * td + 2.0 * rows * td * m + 4.0 * rows * m * m + 2.0 * m * m * m +
                    static_cast<double>(lev.terms.size()) * 8.0 * rows * td * width;
    }
    return low_rank < structured;
}

}  // namespace mocapdb::gp::detail
