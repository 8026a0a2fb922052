#include "mocapdb/kriging/rbf.hpp"

#include <cmath>
#include <limits>
#include <string>

#include <Eigen/LU>

#include "mocapdb/core/error.hpp"
#include "prepared_points.hpp"

namespace mocapdb::kriging {

const char* to_string(RadialFunction f) {
    switch (f) {
        case RadialFunction::CubicBSpline: return "cubic-bspline";
        case RadialFunction::Gaussian: return "gaussian";
        case RadialFunction::Linear: return "linear";
        case RadialFunction::Cubic: return "cubic";
        case RadialFunction::ThinPlate: return "thin-plate";
    }
    return "unknown";
}

namespace {

// Uniform cubic B-spline centered at 0, support [-2, 2], B(0) = 2/3.
double cubic_bspline(double x) {
    const double a = std::abs(x);
    if (a >= 2.0) return 0.0;
    if (a >= 1.0) {
        const double t = 2.0 - a;
        return t * t * t / 6.0;
    }
    return 2.0 / 3.0 - a * a + 0.5 * a * a * a;
}

double radial(RadialFunction f, double r, double radius) {
    switch (f) {
        case RadialFunction::CubicBSpline: return cubic_bspline(2.0 * r / radius);
        case RadialFunction::Gaussian: return std::exp(-(r / radius) * (r / radius));
        case RadialFunction::Linear: return r;
        case RadialFunction::Cubic: return r * r * r;
        case RadialFunction::ThinPlate: return r > 0.0 ? r * r * std::log(r) : 0.0;
    }
    return 0.0;
}

}  // namespace

RbfInterpolator RbfInterpolator::build(const Eigen::Ref<const Eigen::MatrixXd>& coords, const RbfOptions& options) {
    detail::validate_coords("RbfInterpolator::build", coords);
    if (!(options.radius_scale > 0.0) || !std::isfinite(options.radius_scale)) {
        throw InvalidArgument("RbfInterpolator::build: radius_scale must be finite and > 0");
    }
    if (!(options.width >= 0.0) || !std::isfinite(options.width)) {
        throw InvalidArgument("RbfInterpolator::build: width must be finite and >= 0 (0 = automatic)");
    }
    if (!(options.duplicate_tolerance >= 0.0) || !std::isfinite(options.duplicate_tolerance)) {
        throw InvalidArgument("RbfInterpolator::build: duplicate_tolerance must be finite and >= 0");
    }
    RbfInterpolator rb;
    rb.options_ = options;
    detail::PreparedPoints prepared =
        detail::prepare_points(coords, options.duplicate_tolerance, true, options.trend, options.trend_rank_tolerance);
    rb.points_ = std::move(prepared.points);
    rb.group_ = std::move(prepared.group);
    rb.group_size_ = std::move(prepared.group_size);
    rb.merged_ = prepared.merged;
    rb.basis_ = std::move(prepared.basis);
    const Eigen::Index m = rb.points_.rows();
    rb.status_.unique_points = m;
    rb.status_.duplicates_merged = coords.rows() - m;
    rb.status_.trend_rank = rb.basis_.rank();
    rb.status_.trend_rank_deficient = rb.basis_.rank_deficient();

    // Nearest-neighbour distances set the radii.
    Eigen::VectorXd nn = Eigen::VectorXd::Constant(m, std::numeric_limits<double>::infinity());
    Eigen::MatrixXd dist(m, m);
    for (Eigen::Index j = 0; j < m; ++j) {
        dist(j, j) = 0.0;
        for (Eigen::Index i = j + 1; i < m; ++i) {
            const double d = (rb.points_.row(i) - rb.points_.row(j)).norm();
            dist(i, j) = d;
            dist(j, i) = d;
            nn(i) = std::min(nn(i), d);
            nn(j) = std::min(nn(j), d);
        }
    }
    if (m == 1) nn(0) = 1.0;
    rb.radii_.resize(m);
    if (options.function == RadialFunction::CubicBSpline) {
        rb.radii_ = options.radius_scale * nn;
    } else {
        const double w = options.width > 0.0 ? options.width : nn.mean();
        rb.radii_.setConstant(w > 0.0 ? w : 1.0);
    }
    Eigen::MatrixXd phi(m, m);
    for (Eigen::Index j = 0; j < m; ++j) {
        for (Eigen::Index i = 0; i < m; ++i) phi(i, j) = radial(options.function, dist(i, j), rb.radii_(j));
    }
    // Phi^-T with a ridge fallback for a (near-)singular radial matrix.
    const Eigen::MatrixXd phit = phi.transpose();
    Eigen::MatrixXd phi_inv_t;
    const double scale = std::max(phi.cwiseAbs().maxCoeff(), 1e-300);
    double ridge = 0.0;
    for (int attempt = 0; attempt < 12; ++attempt) {
        Eigen::MatrixXd a = phit;
        a.diagonal().array() += ridge;
        Eigen::PartialPivLU<Eigen::MatrixXd> lu(a);
        const double rc = lu.rcond();
        if (std::isfinite(rc) && rc > 1e-14) {
            phi_inv_t = lu.inverse();
            rb.status_.rcond = rc;
            rb.status_.ridge = ridge;
            rb.status_.factorization = ridge > 0.0 ? FactorizationStatus::Jittered : FactorizationStatus::Ok;
            break;
        }
        ridge = ridge == 0.0 ? 1e-12 * scale : ridge * 10.0;
    }
    if (phi_inv_t.size() == 0) {
        // Still singular: fall back to the pseudo-inverse-like heavy ridge (never NaN).
        Eigen::MatrixXd a = phit;
        a.diagonal().array() += 1e-1 * scale;
        Eigen::PartialPivLU<Eigen::MatrixXd> lu(a);
        phi_inv_t = lu.inverse();
        rb.status_.ridge = 1e-1 * scale;
        rb.status_.rcond = lu.rcond();
        rb.status_.factorization = FactorizationStatus::Regularized;
    }
    const Eigen::MatrixXd& g = rb.basis_.sample_basis();  // [1, U]
    const Eigen::Index kk = g.cols();
    const Eigen::Index r = kk - 1;
    // (I - H) Phi^-T with H = 11^T / M + U U^T.
    Eigen::MatrixXd p = phi_inv_t;
    const Eigen::RowVectorXd colmean = phi_inv_t.colwise().mean();
    p.rowwise() -= colmean;
    if (r > 0) {
        Eigen::MatrixXd ut_p(r, m);
        ut_p.noalias() = g.rightCols(r).transpose() * phi_inv_t;
        p.noalias() -= g.rightCols(r) * ut_p;
    }
    rb.operator_.resize(m, m + kk);
    rb.operator_.leftCols(m) = p;
    rb.operator_.col(m).setConstant(1.0 / static_cast<double>(m));
    if (r > 0) rb.operator_.rightCols(r) = g.rightCols(r);
    return rb;
}

void RbfInterpolator::radial_vector(const Eigen::Ref<const Eigen::VectorXd>& c, Eigen::Ref<Eigen::VectorXd> out) const {
    for (Eigen::Index j = 0; j < points_.rows(); ++j) {
        out(j) = radial(options_.function, (points_.row(j).transpose() - c).norm(), radii_(j));
    }
}

void RbfInterpolator::weights(const Eigen::Ref<const Eigen::VectorXd>& c, Eigen::Ref<Eigen::VectorXd> out_weights,
                              QueryWorkspace& ws) const {
    const Eigen::Index m = points_.rows();
    const Eigen::Index n = group_.size();
    if (c.size() != dimension() || out_weights.size() != n) {
        throw InvalidArgument("RbfInterpolator::weights: c must have P = " + std::to_string(dimension()) +
                              " entries and out_weights N = " + std::to_string(n));
    }
    const Eigen::Index kk = basis_.size();
    if (ws.rhs.size() != m + kk) ws.rhs.resize(m + kk);
    radial_vector(c, ws.rhs.head(m));
    basis_.evaluate(c, ws.rhs.tail(kk));
    if (ws.tmp.size() != m) ws.tmp.resize(m);
    ws.tmp.noalias() = operator_ * ws.rhs;
    if (merged_) {
        for (Eigen::Index i = 0; i < n; ++i) out_weights(i) = ws.tmp(group_(i)) / group_size_(group_(i));
    } else {
        out_weights = ws.tmp;
    }
}

void RbfInterpolator::weights_batch(const Eigen::Ref<const Eigen::MatrixXd>& queries,
                                    Eigen::Ref<Eigen::MatrixXd> out_weights) const {
    if (queries.cols() != dimension() || out_weights.rows() != num_samples() || out_weights.cols() != queries.rows()) {
        throw InvalidArgument(
            "RbfInterpolator::weights_batch: queries must be Q by P (P = " + std::to_string(dimension()) +
            ") and out_weights N by Q (N = " + std::to_string(num_samples()) + ")");
    }
    const Eigen::Index m = points_.rows();
    const Eigen::Index kk = basis_.size();
    Eigen::MatrixXd rhs(m + kk, queries.rows());
    for (Eigen::Index q = 0; q < queries.rows(); ++q) radial_vector(queries.row(q).transpose(), rhs.col(q).head(m));
    rhs.bottomRows(kk) = basis_.evaluate_batch(queries);
    Eigen::MatrixXd w(m, queries.rows());
    w.noalias() = operator_ * rhs;
    if (merged_) {
        detail::expand_to_samples(group_, group_size_, w, out_weights);
    } else {
        out_weights = w;
    }
}

}  // namespace mocapdb::kriging
