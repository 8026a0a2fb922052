#include "mocapdb/kriging/trend.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <Eigen/SVD>

#include "mocapdb/core/error.hpp"
#include "mocapdb/core/types.hpp"

namespace mocapdb::kriging {

const char* to_string(TrendKind kind) { return kind == TrendKind::None ? "none" : "linear"; }

TrendBasis TrendBasis::build(const Eigen::Ref<const Eigen::MatrixXd>& coords, TrendKind kind, double rank_tolerance) {
    const Eigen::Index n = coords.rows();
    const Eigen::Index p = coords.cols();
    if (n < 1 || p < 1) {
        throw InvalidArgument("TrendBasis: coords must be N by P with N >= 1 and P >= 1, got " + std::to_string(n) +
                              "x" + std::to_string(p));
    }
    if (!coords.allFinite()) throw InvalidArgument("TrendBasis: coords must be finite");
    if (!(rank_tolerance > 0.0 && rank_tolerance < 1.0)) {
        throw InvalidArgument("TrendBasis: rank_tolerance must be in (0, 1)");
    }
    TrendBasis b;
    b.kind_ = kind;
    b.mean_ = coords.colwise().mean().transpose();
    if (kind == TrendKind::None) {
        b.rank_ = 0;
        b.projection_.resize(p, 0);
        b.sample_basis_ = Eigen::MatrixXd::Ones(n, 1);
        return b;
    }
    const Eigen::MatrixXd centered = coords.rowwise() - b.mean_.transpose();
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(centered, Eigen::ComputeThinU | Eigen::ComputeThinV);
    const Eigen::VectorXd& s = svd.singularValues();
    Eigen::Index r = 0;
    const double smax = s.size() > 0 ? s(0) : 0.0;
    // Singular values of exactly-collinear data sit at rounding level, i.e. ~eps * smax * sqrt(N):
    // rank_tolerance must stay well above that.
    for (Eigen::Index k = 0; k < s.size(); ++k) {
        if (smax > 0.0 && s(k) > rank_tolerance * smax) ++r;
    }
    b.rank_ = r;
    b.projection_ = svd.matrixV().leftCols(r) * s.head(r).cwiseInverse().asDiagonal();
    b.sample_basis_.resize(n, 1 + r);
    b.sample_basis_.col(0).setOnes();
    b.sample_basis_.rightCols(r) = svd.matrixU().leftCols(r);
    return b;
}

void TrendBasis::evaluate(const Eigen::Ref<const Eigen::VectorXd>& c, Eigen::Ref<Eigen::VectorXd> out_g) const {
    if (c.size() != dimension() || out_g.size() != size()) {
        throw InvalidArgument("TrendBasis::evaluate: c must have P = " + std::to_string(dimension()) +
                              " entries and out_g K = " + std::to_string(size()));
    }
    out_g(0) = 1.0;
    // (c - mean)^T V S^-1 one column at a time: no temporary vector on this per-query path.
    for (Eigen::Index k = 0; k < rank_; ++k) out_g(1 + k) = projection_.col(k).dot(c - mean_);
}

Eigen::MatrixXd TrendBasis::evaluate_batch(const Eigen::Ref<const Eigen::MatrixXd>& queries) const {
    if (queries.cols() != dimension()) {
        throw InvalidArgument("TrendBasis::evaluate_batch: queries must be Q by P with P = " +
                              std::to_string(dimension()) + ", got " + std::to_string(queries.cols()) + " columns");
    }
    Eigen::MatrixXd g(size(), queries.rows());
    g.row(0).setOnes();
    if (rank_ > 0) {
        const Eigen::MatrixXd centered = (queries.rowwise() - mean_.transpose()).transpose();
        g.bottomRows(rank_).noalias() = projection_.transpose() * centered;
    }
    return g;
}

double TrendBasis::to_hyperplane(const Eigen::Ref<const Eigen::VectorXd>& a, Eigen::Ref<Eigen::VectorXd> out_l) const {
    if (a.size() != size() || out_l.size() != dimension()) {
        throw InvalidArgument("TrendBasis::to_hyperplane: a must have K entries and out_l P entries");
    }
    out_l.setZero();
    if (rank_ > 0) out_l.noalias() = projection_ * a.tail(rank_);
    return a(0) - out_l.dot(mean_);
}

OlsTrend fit_trend_ols(const TrendBasis& basis, const Eigen::Ref<const Eigen::MatrixXd>& samples) {
    const Eigen::MatrixXd& g = basis.sample_basis();
    if (samples.rows() != g.rows()) {
        throw InvalidArgument("fit_trend_ols: samples must have N = " + std::to_string(g.rows()) + " rows, got " +
                              std::to_string(samples.rows()));
    }
    OlsTrend fit;
    // G = [1, U] with U orthonormal and orthogonal to 1: (G^T G)^-1 = diag(1/N, I).
    fit.coefficients.noalias() = g.transpose() * samples;
    fit.coefficients.row(0) /= static_cast<double>(g.rows());
    fit.residuals = samples;
    fit.residuals.noalias() -= g * fit.coefficients;
    return fit;
}

Eigen::MatrixXd evaluate_trend(const TrendBasis& basis, const Eigen::Ref<const Eigen::MatrixXd>& coefficients,
                               const Eigen::Ref<const Eigen::MatrixXd>& queries) {
    if (coefficients.rows() != basis.size()) {
        throw InvalidArgument("evaluate_trend: coefficients must be K by D with K = " + std::to_string(basis.size()));
    }
    const Eigen::MatrixXd g = basis.evaluate_batch(queries);
    Eigen::MatrixXd out(queries.rows(), coefficients.cols());
    out.noalias() = g.transpose() * coefficients;
    return out;
}

double wrap_to_half_period(double x, double period) {
    const double r = x - period * std::floor(x / period + 0.5);
    return r >= 0.5 * period ? r - period : r;
}

ControlScaling ControlScaling::from_data(const Eigen::Ref<const Eigen::MatrixXd>& coords,
                                         const Eigen::Ref<const Eigen::VectorXd>& periods,
                                         const std::vector<int>& levels) {
    if (coords.rows() < 1 || coords.cols() < 1 || !coords.allFinite()) {
        throw InvalidArgument("ControlScaling::from_data: coords must be a finite N by P matrix with N, P >= 1");
    }
    if (periods.size() != 0 && periods.size() != coords.cols())
        throw InvalidArgument("ControlScaling::from_data: periods must be empty or have P = " +
                              std::to_string(coords.cols()) + " entries");
    if (!periods.allFinite() || (periods.array() < 0.0).any())
        throw InvalidArgument("ControlScaling::from_data: periods must be finite and >= 0");
    ControlScaling s;
    s.offset = coords.colwise().mean().transpose();
    s.scale.resize(coords.cols());
    if ((periods.array() > 0.0).any()) s.period = periods;
    if (std::any_of(levels.begin(), levels.end(), [](int l) { return l != 0; })) s.levels = levels;
    for (Eigen::Index k = 0; k < coords.cols(); ++k) {
        double sd;
        if (s.categorical(k)) {  // a level index: neither centred nor scaled
            s.offset(k) = 0.0;
            sd = 1.0;
        } else if (s.period.size() != 0 && s.period(k) > 0.0) {
            const double t = s.period(k);
            const double two_pi = 2.0 * kPi;
            const Eigen::ArrayXd angle = coords.col(k).array() * (two_pi / t);
            const double c = angle.cos().mean(), sn = angle.sin().mean();
            // The circular mean (any value when the angles cancel out; the first sample's then).
            s.offset(k) = std::hypot(c, sn) > 1e-12 ? std::atan2(sn, c) * t / two_pi : coords(0, k);
            double sum = 0.0;
            for (Eigen::Index i = 0; i < coords.rows(); ++i) {
                const double d = wrap_to_half_period(coords(i, k) - s.offset(k), t);
                sum += d * d;
            }
            sd = std::sqrt(sum / static_cast<double>(coords.rows()));
        } else {
            sd = std::sqrt((coords.col(k).array() - s.offset(k)).square().mean());
        }
        s.scale(k) = sd > 0.0 ? sd : 1.0;
    }
    return s;
}

ControlScaling ControlScaling::identity(Eigen::Index dimension) {
    ControlScaling s;
    s.offset = Eigen::VectorXd::Zero(dimension);
    s.scale = Eigen::VectorXd::Ones(dimension);
    return s;
}

void ControlScaling::validate(Eigen::Index dimension) const {
    if (offset.size() != dimension || scale.size() != dimension) {
        throw InvalidArgument("ControlScaling: offset and scale must have P = " + std::to_string(dimension) +
                              " entries");
    }
    if (!offset.allFinite() || !(scale.array() > 0.0).all() || !scale.allFinite()) {
        throw InvalidArgument("ControlScaling: offsets must be finite and scales finite and > 0");
    }
    if (period.size() != 0 && (period.size() != dimension || !period.allFinite() || (period.array() < 0.0).any()))
        throw InvalidArgument("ControlScaling: periods must be empty or P = " + std::to_string(dimension) +
                              " finite values >= 0");
    if (!levels.empty() && static_cast<Eigen::Index>(levels.size()) != dimension)
        throw InvalidArgument("ControlScaling: level counts must be empty or P = " + std::to_string(dimension));
    for (std::size_t k = 0; k < levels.size(); ++k)
        if (levels[k] == 1 || levels[k] < 0 ||
            (levels[k] > 0 && period.size() != 0 && period(static_cast<Eigen::Index>(k)) > 0.0))
            throw InvalidArgument("ControlScaling: axis " + std::to_string(k) +
                                  ": a level count must be 0 (numeric) or >= 2 (categorical, not periodic), got " +
                                  std::to_string(levels[k]));
}

bool ControlScaling::has_periodic_axis() const { return period.size() != 0 && (period.array() > 0.0).any(); }

bool ControlScaling::has_categorical_axis() const {
    return std::any_of(levels.begin(), levels.end(), [](int l) { return l > 0; });
}

bool ControlScaling::categorical(Eigen::Index k) const {
    return static_cast<std::size_t>(k) < levels.size() && levels[static_cast<std::size_t>(k)] > 0;
}

Eigen::Index ControlScaling::embedded_dimension() const {
    Eigen::Index d =
        offset.size() + (period.size() != 0 ? static_cast<Eigen::Index>((period.array() > 0.0).count()) : 0);
    for (const int l : levels)
        if (l > 0) d += l - 1;
    return d;
}

Eigen::MatrixXd ControlScaling::apply(const Eigen::Ref<const Eigen::MatrixXd>& coords) const {
    validate(coords.cols());
    if (!has_periodic_axis() && !has_categorical_axis()) {
        Eigen::MatrixXd out = (coords.rowwise() - offset.transpose());
        out.array().rowwise() /= scale.transpose().array();
        return out;
    }
    const double two_pi = 2.0 * kPi;
    Eigen::MatrixXd out(coords.rows(), embedded_dimension());
    Eigen::Index col = 0;
    for (Eigen::Index k = 0; k < coords.cols(); ++k) {
        if (categorical(k)) {
            const int count = levels[static_cast<std::size_t>(k)];
            out.middleCols(col, count).setZero();
            for (Eigen::Index i = 0; i < coords.rows(); ++i) {
                const double x = coords(i, k);
                if (!(x >= 0.0 && x < count && x == std::floor(x)))
                    throw InvalidArgument("ControlScaling: coordinate " + std::to_string(k) + " of point " +
                                          std::to_string(i) + " is categorical with " + std::to_string(count) +
                                          " levels; expected a level index 0 to " + std::to_string(count - 1) +
                                          ", got " + std::to_string(x));
                out(i, col + static_cast<Eigen::Index>(x)) = kLevelCoordinate;
            }
            col += count;
        } else if (period.size() != 0 && period(k) > 0.0) {
            const double radius = period(k) / (two_pi * scale(k));
            const Eigen::ArrayXd angle = (coords.col(k).array() - offset(k)) * (two_pi / period(k));
            out.col(col++) = radius * angle.cos();
            out.col(col++) = radius * angle.sin();
        } else {
            out.col(col++) = (coords.col(k).array() - offset(k)) / scale(k);
        }
    }
    return out;
}

void ControlScaling::apply_point(const Eigen::Ref<const Eigen::VectorXd>& c, Eigen::VectorXd& out) const {
    if (c.size() != offset.size())
        throw InvalidArgument("ControlScaling: a point must have P = " + std::to_string(offset.size()) + " entries");
    if (!has_periodic_axis() && !has_categorical_axis()) {
        if (out.size() != c.size()) out.resize(c.size());
        out = ((c - offset).array() / scale.array()).matrix();
        return;
    }
    out = apply(c.transpose()).transpose();  // the same operations as a batch, so the same bits
}

}  // namespace mocapdb::kriging
