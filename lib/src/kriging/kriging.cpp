#include "mocapdb/kriging/kriging.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include "mocapdb/core/error.hpp"
#include "mocapdb/core/huge_pages.hpp"
#include "gamma_vector.hpp"
#include "query_kernels.hpp"
#include "prepared_points.hpp"

namespace mocapdb::kriging {

const char* to_string(TrendFit fit) { return fit == TrendFit::OLS ? "ols" : "gls"; }

const char* to_string(ReliabilityVariance v) { return v == ReliabilityVariance::Paper ? "paper" : "prediction"; }

const char* to_string(FactorizationStatus status) {
    switch (status) {
        case FactorizationStatus::Ok: return "ok";
        case FactorizationStatus::Jittered: return "jittered";
        case FactorizationStatus::Regularized: return "regularized";
    }
    return "unknown";
}

namespace {

// Columns of the inverse computed per progress report.
constexpr Eigen::Index kInverseBlock = 256;

// f(i, j) for every i > j of an M by M matrix, square tile after square tile (a transposed pass over a
// whole matrix misses the cache at every element).
template <class F>
void each_lower_pair(Eigen::Index m, F f) {
    constexpr Eigen::Index tile = 64;
    for (Eigen::Index j0 = 0; j0 < m; j0 += tile)
        for (Eigen::Index i0 = j0; i0 < m; i0 += tile)
            for (Eigen::Index j = j0; j < std::min(j0 + tile, m); ++j)
                for (Eigen::Index i = std::max(i0, j + 1); i < std::min(i0 + tile, m); ++i) f(i, j);
}

// a = (a + a^T) / 2 in place.
void symmetrize(Eigen::MatrixXd& a) {
    each_lower_pair(a.rows(), [&a](Eigen::Index i, Eigen::Index j) {
        const double v = 0.5 * (a(i, j) + a(j, i));
        a(i, j) = v;
        a(j, i) = v;
    });
}

// The inverse of L L^T from its Cholesky factor, exactly symmetric. Column block B = [j0, j0 + nb):
// its rows >= j0 are (L_jj L_jj^T)^-1 E with L_jj the trailing factor from j0 (L is lower triangular, so
// neither solve reaches rows < j0) and E the identity's columns B from row j0; the rows above are the
// mirror of earlier blocks. M^3 / 3 multiply-adds against M^3 for solving with the whole identity.
Eigen::MatrixXd inverse_of_factor(const Eigen::LLT<Eigen::MatrixXd>& llt, const ProgressCallback& progress) {
    const Eigen::MatrixXd& l = llt.matrixLLT();
    const Eigen::Index m = l.rows();
    Eigen::MatrixXd inv(m, m);
    advise_huge_pages(inv);
    Eigen::MatrixXd x;
    for (Eigen::Index j0 = 0; j0 < m; j0 += kInverseBlock) {
        const Eigen::Index nb = std::min(kInverseBlock, m - j0);
        const Eigen::Index rows = m - j0;
        x = Eigen::MatrixXd::Identity(rows, nb);
        const auto trailing = l.bottomRightCorner(rows, rows).triangularView<Eigen::Lower>();
        trailing.solveInPlace(x);
        trailing.adjoint().solveInPlace(x);
        inv.block(j0, j0, rows, nb) = x;
        if (progress) progress({static_cast<std::uint64_t>(j0 + nb), static_cast<std::uint64_t>(m), "kernel system"});
    }
    // The upper triangle: the mirror of the lower one, except in the diagonal blocks (computed whole): their mean.
    each_lower_pair(m, [&inv](Eigen::Index i, Eigen::Index j) {
        const double a = i / kInverseBlock == j / kInverseBlock ? 0.5 * (inv(i, j) + inv(j, i)) : inv(i, j);
        inv(i, j) = a;
        inv(j, i) = a;
    });
    return inv;
}

// Inverse of a symmetric matrix expected to be positive definite, with jitter escalation and, as a last
// resort, eigenvalue clamping. Fills status fields.
Eigen::MatrixXd robust_spd_inverse(const Eigen::MatrixXd& c, double scale, const KrigingOptions& options,
                                   KrigingStatus& status, const ProgressCallback& progress) {
    {
        Eigen::LLT<Eigen::MatrixXd> llt(c);
        if (llt.info() == Eigen::Success) {
            const double rc = llt.rcond();
            if (std::isfinite(rc) && rc >= options.min_rcond) {
                status.factorization = FactorizationStatus::Ok;
                status.jitter = 0.0;
                status.rcond = rc;
                return inverse_of_factor(llt, progress);
            }
        }
    }
    for (double rel = 1e-12; rel <= options.max_jitter * (1.0 + 1e-9); rel *= 10.0) {
        const double delta = rel * scale;
        Eigen::MatrixXd cj = c;
        cj.diagonal().array() += delta;
        Eigen::LLT<Eigen::MatrixXd> llt(cj);
        if (llt.info() != Eigen::Success) continue;
        const double rc = llt.rcond();
        if (std::isfinite(rc) && rc >= options.min_rcond) {
            status.factorization = FactorizationStatus::Jittered;
            status.jitter = delta;
            status.rcond = rc;
            return inverse_of_factor(llt, progress);
        }
    }
    // Nearest positive definite matrix: clamp the spectrum from below.
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(c);
    Eigen::VectorXd lambda = eig.eigenvalues();
    const double lmax = std::max(lambda.maxCoeff(), scale);
    const double floor_value = std::max(options.max_jitter, 1e-12) * lmax;
    lambda = lambda.cwiseMax(floor_value);
    status.factorization = FactorizationStatus::Regularized;
    status.jitter = floor_value;
    status.rcond = lambda.minCoeff() / lambda.maxCoeff();
    Eigen::MatrixXd inv = eig.eigenvectors() * lambda.cwiseInverse().asDiagonal() * eig.eigenvectors().transpose();
    symmetrize(inv);
    return inv;
}

// gamma: the variogram matrix of the points (M by M, diagonal 0): its lower triangle one vectorized
// column at a time, then mirrored (exactly symmetric).
void fill_gamma(const Eigen::MatrixXd& points, const VariogramModel& model, Eigen::MatrixXd& gamma) {
    const Eigen::Index m = points.rows();
    gamma.resize(m, m);
    advise_huge_pages(gamma);
    for (Eigen::Index j = 0; j < m; ++j)
        detail::gamma_vector(points.bottomRows(m - j), model, points.row(j).transpose(), gamma.col(j).tail(m - j));
    each_lower_pair(m, [&gamma](Eigen::Index i, Eigen::Index j) { gamma(j, i) = gamma(i, j); });
}

// The covariance matrix nugget + sill - gamma off the diagonal, nugget + sill on it.
Eigen::MatrixXd covariance_of(const Eigen::MatrixXd& gamma, double total_sill) {
    Eigen::MatrixXd cov(gamma.rows(), gamma.cols());
    advise_huge_pages(cov);
    cov = (total_sill - gamma.array()).matrix();
    cov.diagonal().setConstant(total_sill);
    return cov;
}

}  // namespace

Kriging Kriging::build(const Eigen::Ref<const Eigen::MatrixXd>& coords, const VariogramModel& model,
                       const KrigingOptions& options) {
    return build(coords, model, options, nullptr);
}

CovarianceInverse Kriging::covariance_inverse(const Eigen::Ref<const Eigen::MatrixXd>& coords,
                                              const VariogramModel& model, const KrigingOptions& options,
                                              const ProgressCallback& progress) {
    Kriging k = prepare(coords, model, options);
    fill_gamma(k.points_, model, k.gamma_);
    // Reported before the factorization (a sixth of the work, not divisible into steps), then per block.
    if (progress) progress({0, static_cast<std::uint64_t>(k.points_.rows()), "kernel system"});
    CovarianceInverse out;
    out.inverse = robust_spd_inverse(covariance_of(k.gamma_, model.total_sill()), model.total_sill(), options,
                                     k.status_, progress);
    out.factorization = k.status_.factorization;
    out.jitter = k.status_.jitter;
    out.rcond = k.status_.rcond;
    return out;
}

Kriging Kriging::prepare(const Eigen::Ref<const Eigen::MatrixXd>& coords, const VariogramModel& model,
                         const KrigingOptions& options) {
    detail::validate_coords("Kriging::build", coords);
    model.validate();
    if (!(model.total_sill() > 0.0)) {
        throw InvalidArgument("Kriging::build: the model must have nugget + sill > 0");
    }
    if (!(options.duplicate_tolerance >= 0.0) || !std::isfinite(options.duplicate_tolerance)) {
        throw InvalidArgument("Kriging::build: duplicate_tolerance must be finite and >= 0");
    }
    if (!(options.min_rcond >= 0.0 && options.min_rcond < 1.0)) {
        throw InvalidArgument("Kriging::build: min_rcond must be in [0, 1)");
    }
    if (!(options.max_jitter > 0.0 && options.max_jitter < 1.0)) {
        throw InvalidArgument("Kriging::build: max_jitter must be in (0, 1)");
    }

    Kriging k;
    k.model_ = model;
    k.query_model_ = model;
    if (options.filter_nugget) k.query_model_.nugget = 0.0;
    k.options_ = options;

    // Duplicates grouped (merged or kept) and the trend basis over the resulting points.
    detail::PreparedPoints prepared =
        detail::prepare_points(coords, options.duplicate_tolerance, options.duplicates == DuplicatePolicy::Merge,
                               options.trend, options.trend_rank_tolerance);
    k.points_ = std::move(prepared.points);
    k.group_ = std::move(prepared.group);
    k.group_size_ = std::move(prepared.group_size);
    k.merged_ = prepared.merged;
    k.basis_ = std::move(prepared.basis);
    const Eigen::Index m = k.points_.rows();
    k.status_.duplicate_pairs = prepared.duplicate_pairs;
    k.status_.unique_points = m;
    k.status_.duplicates_merged = coords.rows() - m;
    k.status_.trend_rank = k.basis_.rank();
    k.status_.trend_rank_deficient = k.basis_.rank_deficient();
    return k;
}

Kriging Kriging::build(const Eigen::Ref<const Eigen::MatrixXd>& coords, const VariogramModel& model,
                       const KrigingOptions& options, const CovarianceInverse* precomputed,
                       const ProgressCallback& progress) {
    Kriging k = prepare(coords, model, options);
    fill_gamma(k.points_, model, k.gamma_);
    const Eigen::Index m = k.points_.rows();
    Eigen::MatrixXd computed;
    const bool reuse = precomputed && precomputed->inverse.rows() == m && precomputed->inverse.cols() == m;
    if (reuse) {
        k.status_.factorization = precomputed->factorization;
        k.status_.jitter = precomputed->jitter;
        k.status_.rcond = precomputed->rcond;
    } else {
        if (progress) progress({0, static_cast<std::uint64_t>(m), "kernel system"});
        computed = robust_spd_inverse(covariance_of(k.gamma_, model.total_sill()), model.total_sill(), options,
                                      k.status_, progress);
    }
    const Eigen::MatrixXd& cinv = reuse ? precomputed->inverse : computed;

    // Kernel system: F is the trend basis (OK / GLS) or the constant only (OLS kernel, paper Eq. 3).
    const bool ols = options.trend_fit == TrendFit::OLS && options.trend == TrendKind::Linear;
    const Eigen::MatrixXd f = ols ? Eigen::MatrixXd(Eigen::MatrixXd::Ones(m, 1)) : k.basis_.sample_basis();
    const Eigen::Index kk = f.cols();
    k.kernel_trend_size_ = kk;
    Eigen::MatrixXd cinv_f(m, kk);
    cinv_f.noalias() = cinv * f;
    Eigen::MatrixXd schur(kk, kk);
    schur.noalias() = f.transpose() * cinv_f;
    schur = 0.5 * (schur + schur.transpose()).eval();
    k.s_inverse_ = schur.ldlt().solve(Eigen::MatrixXd::Identity(kk, kk));
    Eigen::MatrixXd v(m, kk);
    v.noalias() = cinv_f * k.s_inverse_;
    // Wc = C^-1 - V (C^-1 F)^T, exactly symmetric; built in place (a computed inverse is moved in).
    if (reuse) {
        k.kernel_inverse_.resize(m, m);
        advise_huge_pages(k.kernel_inverse_);
        k.kernel_inverse_ = cinv;
    } else {
        k.kernel_inverse_ = std::move(computed);
    }
    k.kernel_inverse_.noalias() -= v * cinv_f.transpose();
    symmetrize(k.kernel_inverse_);
    k.v_transpose_ = v.transpose();
    // The kernel operator [-Wc, V] is kept for GLS / OK (their weight operator); OLS folds it into
    // weight_operator_ below, and solve_block reads Wc and V.
    if (!ols) {
        k.operator_.resize(m, m + kk);
        advise_huge_pages(k.operator_);
        k.operator_.leftCols(m) = -k.kernel_inverse_;
        k.operator_.rightCols(kk) = v;
    }
#ifdef MOCAPDB_KRIGING_QUERY_KERNELS
    // The single-query operator (query_kernels.hpp) of -Wc (exactly symmetric).
    k.query_operator_ = std::make_shared<const detail::QueryOperator>(k.kernel_inverse_, v, k.basis_.sample_basis());
#endif
    if (ols) {
        k.ols_u_ = k.basis_.sample_basis().rightCols(k.basis_.rank());
        // The OLS weights w = b + U (g_u(c) - U^T b), b = [-Wc, v] [gamma; 1], folded into one operator so
        // that a query is one matrix-vector product: w = [(I - U U^T) [-Wc, v], U] [gamma; g(c)], with
        // g(c) = [1, g_u(c)] the trend basis at c (as for GLS).
        const Eigen::Index r = k.ols_u_.cols();
        k.weight_operator_.resize(m, m + 1 + r);
        advise_huge_pages(k.weight_operator_);
        k.weight_operator_.leftCols(m) = -k.kernel_inverse_;
        k.weight_operator_.col(m) = v;
        if (r > 0) {
            Eigen::MatrixXd ut_op(r, m + 1);
            ut_op.noalias() = k.ols_u_.transpose() * k.weight_operator_.leftCols(m + 1);
            k.weight_operator_.leftCols(m + 1).noalias() -= k.ols_u_ * ut_op;
            k.weight_operator_.rightCols(r) = k.ols_u_;
        }
    }
    return k;
}

const Eigen::MatrixXd& Kriging::weight_operator() const {
    return weight_operator_.size() > 0 ? weight_operator_ : operator_;
}

void Kriging::weights_from_rhs(const Eigen::Ref<const Eigen::MatrixXd>& rhs, Eigen::Ref<Eigen::MatrixXd> out,
                               Eigen::MatrixXd& scratch) const {
    const Eigen::Index m = points_.rows();
    const Eigen::Index kk = basis_.size();
    out.noalias() = weight_operator() * rhs;
    // Re-impose G^T w = g(c) exactly (partition of unity and reproduction of the trend): a no-op in exact
    // arithmetic that removes the constraint-violating part of rounding errors of an ill-conditioned
    // system. G = [1, U] has orthogonal columns, 1^T 1 = M and U^T U = I.
    const Eigen::MatrixXd& gb = basis_.sample_basis();
    scratch.resize(kk, rhs.cols());
    scratch = rhs.bottomRows(kk);
    scratch.noalias() -= gb.transpose() * out;
    scratch.row(0) /= static_cast<double>(m);
    out.noalias() += gb * scratch;
}

void Kriging::gamma_vector(const Eigen::Ref<const Eigen::VectorXd>& c, Eigen::Ref<Eigen::VectorXd> out) const {
    detail::gamma_vector(points_, query_model_, c, out);
}

void Kriging::gamma_block(const Eigen::Ref<const Eigen::MatrixXd>& queries, Eigen::Ref<Eigen::MatrixXd> out) const {
    detail::gamma_block(points_, query_model_, queries, out);
}

void Kriging::solve_block(const Eigen::Ref<const Eigen::MatrixXd>& gamma, const Eigen::Ref<const Eigen::MatrixXd>& g,
                          Eigen::MatrixXd& out_kernel, Eigen::MatrixXd& out_weights) const {
    const Eigen::Index m = points_.rows();
    out_kernel.resize(m, gamma.cols());
    out_kernel.noalias() = -kernel_inverse_ * gamma;
    if (options_.trend_fit == TrendFit::OLS && options_.trend == TrendKind::Linear) {
        out_kernel.colwise() += v_transpose_.row(0).transpose();
        // Partition of unity enforced exactly (see the GLS branch).
        const Eigen::RowVectorXd defect = (1.0 - out_kernel.colwise().sum().array()) / static_cast<double>(m);
        out_kernel.rowwise() += defect;
        out_weights = out_kernel;
        const Eigen::Index r = ols_u_.cols();
        if (r > 0) {
            Eigen::MatrixXd corr = g.bottomRows(r);
            corr.noalias() -= ols_u_.transpose() * out_kernel;
            out_weights.noalias() += ols_u_ * corr;
        }
    } else {
        out_kernel.noalias() += v_transpose_.transpose() * g;
        // Enforce the unbiasedness constraints G^T w = g exactly (a no-op in exact arithmetic; removes the
        // constraint-violating part of rounding errors of an ill-conditioned system).
        const Eigen::MatrixXd& gb = basis_.sample_basis();
        Eigen::MatrixXd corr = g;
        corr.noalias() -= gb.transpose() * out_kernel;
        corr.row(0) /= static_cast<double>(m);
        out_kernel.noalias() += gb * corr;
        out_weights = out_kernel;
    }
}

void Kriging::weights(const Eigen::Ref<const Eigen::VectorXd>& c, Eigen::Ref<Eigen::VectorXd> out_weights,
                      QueryWorkspace& ws) const {
    const Eigen::Index m = points_.rows();
    const Eigen::Index n = group_.size();
    if (c.size() != dimension() || out_weights.size() != n) {
        throw InvalidArgument("Kriging::weights: c must have P = " + std::to_string(dimension()) +
                              " entries and out_weights N = " + std::to_string(n));
    }
    if (m == 0) throw InvalidArgument("Kriging::weights: the kriging object is empty (not built)");
    // No allocation once the workspace has its sizes.
    const Eigen::Index kk = basis_.size();
    if (ws.tmp2.size() != kk) ws.tmp2.resize(kk);
#ifdef MOCAPDB_KRIGING_QUERY_KERNELS
    // rhs = [gamma(c); zero padding; g(c)], then the weights from the packed operator (query_kernels.hpp;
    // for OLS its projection also applies the U correction that weight_operator_ folds in).
    const detail::QueryOperator& qo = *query_operator_;
    const Eigen::Index mp = qo.padded_size();
    if (ws.rhs.size() != mp + kk) ws.rhs.resize(mp + kk);
    if (ws.tmp.size() != mp) ws.tmp.resize(mp);
    gamma_vector(c, ws.rhs.head(m));
    ws.rhs.segment(m, mp - m).setZero();
    basis_.evaluate(c, ws.rhs.tail(kk));
    qo.weights(ws.rhs.data(), ws.rhs.data() + mp, ws.tmp.data(), ws.tmp2.data(),
               merged_ ? ws.tmp.data() : out_weights.data());
#else
    // rhs = [gamma(c); g(c)], w = weight_operator() rhs, then G^T w = g(c) re-imposed as in
    // weights_from_rhs, G = [1, U]: K dot products and one pass over w (plain vector operations: Eigen's
    // general matrix-vector kernels cost more than the arithmetic at these sizes).
    if (ws.rhs.size() != m + kk) ws.rhs.resize(m + kk);
    gamma_vector(c, ws.rhs.head(m));
    basis_.evaluate(c, ws.rhs.tail(kk));
    const Eigen::MatrixXd& gb = basis_.sample_basis();
    if (ws.tmp.size() != m) ws.tmp.resize(m);
    Eigen::Ref<Eigen::VectorXd> w = merged_ ? Eigen::Ref<Eigen::VectorXd>(ws.tmp) : out_weights;
    w.noalias() = weight_operator() * ws.rhs;
    ws.tmp2(0) = (ws.rhs(m) - w.sum()) / static_cast<double>(m);
    for (Eigen::Index k = 1; k < kk; ++k) ws.tmp2(k) = ws.rhs(m + k) - gb.col(k).dot(w);
    w.array() += ws.tmp2(0);
    for (Eigen::Index k = 1; k < kk; ++k) w += ws.tmp2(k) * gb.col(k);
#endif
    if (merged_) {
        for (Eigen::Index i = 0; i < n; ++i) out_weights(i) = ws.tmp(group_(i)) / group_size_(group_(i));
    }
}

namespace {
// Queries are processed in blocks of this many columns: the temporaries stay in cache and are reused,
// instead of fresh multi-megabyte buffers per call.
constexpr Eigen::Index kBlock = 256;
}  // namespace

void Kriging::weights_batch(const Eigen::Ref<const Eigen::MatrixXd>& queries,
                            Eigen::Ref<Eigen::MatrixXd> out_weights) const {
    if (queries.cols() != dimension() || out_weights.rows() != num_samples() || out_weights.cols() != queries.rows()) {
        throw InvalidArgument("Kriging::weights_batch: queries must be Q by P (P = " + std::to_string(dimension()) +
                              ") and out_weights N by Q (N = " + std::to_string(num_samples()) + ")");
    }
    // Per block of queries: rhs = [gamma; g] (M + K by nb), then one matrix product with the weight
    // operator (a GEMM), written straight into out_weights unless duplicates were merged.
    const Eigen::Index m = points_.rows();
    const Eigen::Index kk = basis_.size();
    Eigen::MatrixXd rhs;
    Eigen::MatrixXd w;
    Eigen::MatrixXd scratch;
    for (Eigen::Index q0 = 0; q0 < queries.rows(); q0 += kBlock) {
        const Eigen::Index nb = std::min(kBlock, queries.rows() - q0);
        rhs.resize(m + kk, nb);
        gamma_block(queries.middleRows(q0, nb), rhs.topRows(m));
        rhs.bottomRows(kk) = basis_.evaluate_batch(queries.middleRows(q0, nb));
        if (merged_) {
            w.resize(m, nb);
            weights_from_rhs(rhs, w, scratch);
            detail::expand_to_samples(group_, group_size_, w, out_weights.middleCols(q0, nb));
        } else {
            weights_from_rhs(rhs, out_weights.middleCols(q0, nb), scratch);
        }
    }
}

KrigingBatch Kriging::estimate_batch(const Eigen::Ref<const Eigen::MatrixXd>& queries) const {
    if (queries.cols() != dimension()) {
        throw InvalidArgument("Kriging::estimate_batch: queries must be Q by P with P = " +
                              std::to_string(dimension()));
    }
    const Eigen::Index m = points_.rows();
    const Eigen::Index nq = queries.rows();
    const bool ols = options_.trend_fit == TrendFit::OLS && options_.trend == TrendKind::Linear;
    KrigingBatch out;
    out.weights.resize(num_samples(), nq);
    out.variance.resize(nq);
    out.paper_variance.resize(nq);
    out.reliability.resize(nq);
    Eigen::MatrixXd gamma;
    Eigen::MatrixXd kernel;
    Eigen::MatrixXd w;
    Eigen::MatrixXd aux;
    for (Eigen::Index q0 = 0; q0 < nq; q0 += kBlock) {
        const Eigen::Index nb = std::min(kBlock, nq - q0);
        gamma.resize(m, nb);
        gamma_block(queries.middleRows(q0, nb), gamma);
        const Eigen::MatrixXd g = basis_.evaluate_batch(queries.middleRows(q0, nb));
        solve_block(gamma, g, kernel, w);
        if (ols || options_.filter_nugget) {
            // 2 w^T gamma - w^T Gamma w (+ the nugget when gamma is the filtered one: the error variance of
            // the noise-free signal; valid for any weights that sum to one).
            aux.resize(m, nb);
            aux.noalias() = gamma_ * w;
            out.variance.segment(q0, nb) = 2.0 * (w.array() * gamma.array()).colwise().sum().transpose() -
                                           (w.array() * aux.array()).colwise().sum().transpose();
            if (options_.filter_nugget) out.variance.segment(q0, nb).array() += model_.nugget;
        } else {
            // sigma^2 = b^T gamma + mu^T g,  mu = S^-1 g - s e1 + V^T gamma.
            aux.resize(kernel_trend_size_, nb);
            aux.noalias() = s_inverse_ * g;
            aux.row(0).array() -= model_.total_sill();
            aux.noalias() += v_transpose_ * gamma;
            out.variance.segment(q0, nb) = (kernel.array() * gamma.array()).colwise().sum().transpose() +
                                           (aux.array() * g.array()).colwise().sum().transpose();
        }
        out.paper_variance.segment(q0, nb) = (kernel.array() * gamma.array()).colwise().sum().transpose();
        if (merged_) {
            detail::expand_to_samples(group_, group_size_, w, out.weights.middleCols(q0, nb));
        } else {
            out.weights.middleCols(q0, nb) = w;
        }
    }
    out.variance = out.variance.cwiseMax(0.0);
    out.paper_variance = out.paper_variance.cwiseMax(0.0);
    const Eigen::VectorXd& v = options_.reliability == ReliabilityVariance::Paper ? out.paper_variance : out.variance;
    out.reliability = (1.0 - v.array() / model_.total_sill()).cwiseMax(0.0).cwiseMin(1.0).matrix();
    return out;
}

KrigingEstimate Kriging::estimate(const Eigen::Ref<const Eigen::VectorXd>& c) const {
    if (c.size() != dimension()) {
        throw InvalidArgument("Kriging::estimate: c must have P = " + std::to_string(dimension()) + " entries");
    }
    const Eigen::MatrixXd q = c.transpose();
    KrigingBatch b = estimate_batch(q);
    KrigingEstimate e;
    e.weights = b.weights.col(0);
    e.variance = b.variance(0);
    e.paper_variance = b.paper_variance(0);
    e.reliability = b.reliability(0);
    // Kernel b(c): recompute (cheap) so that it is exposed on the original samples.
    const Eigen::Index m = points_.rows();
    Eigen::MatrixXd gamma(m, 1);
    gamma_block(q, gamma);
    const Eigen::MatrixXd g = basis_.evaluate_batch(q);
    Eigen::MatrixXd kernel;
    Eigen::MatrixXd w;
    solve_block(gamma, g, kernel, w);
    e.kernel.resize(num_samples());
    if (merged_) {
        Eigen::MatrixXd tmp(num_samples(), 1);
        detail::expand_to_samples(group_, group_size_, kernel, tmp);
        e.kernel = tmp.col(0);
    } else {
        e.kernel = kernel.col(0);
    }
    return e;
}

Eigen::VectorXd Kriging::reliability(const Eigen::Ref<const Eigen::MatrixXd>& queries) const {
    return estimate_batch(queries).reliability;
}

LooResult Kriging::leave_one_out(const Eigen::Ref<const Eigen::MatrixXd>& values) const {
    const Eigen::Index n = num_samples();
    const Eigen::Index m = points_.rows();
    if (values.rows() != n || values.cols() < 1) {
        throw InvalidArgument("Kriging::leave_one_out: values must be N by D with N = " + std::to_string(n) +
                              " and D >= 1, got " + std::to_string(values.rows()) + "x" +
                              std::to_string(values.cols()));
    }
    if (!values.allFinite()) throw InvalidArgument("Kriging::leave_one_out: values must be finite");
    const Eigen::Index d = values.cols();
    Eigen::MatrixXd z = Eigen::MatrixXd::Zero(m, d);
    for (Eigen::Index i = 0; i < n; ++i) z.row(group_(i)) += values.row(i) / group_size_(group_(i));
    const bool ols = options_.trend_fit == TrendFit::OLS && options_.trend == TrendKind::Linear;
    if (ols) z = fit_trend_ols(basis_, z).residuals;
    Eigen::MatrixXd e(m, d);
    e.noalias() = kernel_inverse_ * z;
    const Eigen::VectorXd diag = kernel_inverse_.diagonal();
    LooResult out;
    out.prediction.resize(n, d);
    out.residual.resize(n, d);
    out.variance.resize(n);
    out.zscore.resize(n, d);
    for (Eigen::Index i = 0; i < n; ++i) {
        const Eigen::Index u = group_(i);
        if (group_size_(u) > 1.0) {
            Eigen::RowVectorXd others = Eigen::RowVectorXd::Zero(d);
            for (Eigen::Index j = 0; j < n; ++j) {
                if (j != i && group_(j) == u) others += values.row(j);
            }
            out.prediction.row(i) = others / (group_size_(u) - 1.0);
            out.variance(i) = 0.0;
        } else {
            const double dii = diag(u);
            if (dii > 0.0 && std::isfinite(dii)) {
                out.prediction.row(i) = values.row(i) - e.row(u) / dii;
                out.variance(i) = 1.0 / dii;
            } else {
                // Degenerate (cannot happen for a positive definite system); fall back to the mean.
                out.prediction.row(i) = values.colwise().mean();
                out.variance(i) = model_.total_sill();
            }
        }
        out.residual.row(i) = values.row(i) - out.prediction.row(i);
        const double sd = std::sqrt(std::max(out.variance(i), 0.0));
        out.zscore.row(i) = sd > 0.0 ? Eigen::RowVectorXd(out.residual.row(i) / sd) : Eigen::RowVectorXd::Zero(d);
    }
    out.mse = out.residual.squaredNorm() / static_cast<double>(n * d);
    return out;
}

Eigen::VectorXd Kriging::leave_one_out_reliability() const {
    const Eigen::Index n = num_samples();
    const Eigen::Index m = points_.rows();
    // Leaving unique point u out, the kernel on the others is b_j = -Wc(j,u) / Wc(u,u), so
    // sigma^2 = sum_j b_j gamma(j,u) = -(Gamma Wc)(u,u) / Wc(u,u).
    Eigen::VectorXd rho_unique(m);
    for (Eigen::Index u = 0; u < m; ++u) {
        const double dii = kernel_inverse_(u, u);
        double sigma2 = model_.total_sill();
        if (dii > 0.0 && options_.reliability == ReliabilityVariance::Paper) {
            const double gw = gamma_.col(u).dot(kernel_inverse_.col(u));
            sigma2 = std::max(-gw / dii, 0.0);
        } else if (dii > 0.0) {
            sigma2 = std::max(1.0 / dii - (options_.filter_nugget ? model_.nugget : 0.0), 0.0);
        }
        rho_unique(u) = std::clamp(1.0 - sigma2 / model_.total_sill(), 0.0, 1.0);
    }
    Eigen::VectorXd rho(n);
    for (Eigen::Index i = 0; i < n; ++i) {
        const Eigen::Index u = group_(i);
        rho(i) = group_size_(u) > 1.0 ? 1.0 : rho_unique(u);
    }
    return rho;
}

}  // namespace mocapdb::kriging
