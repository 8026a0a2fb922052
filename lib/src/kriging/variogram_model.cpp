#include "mocapdb/kriging/variogram_model.hpp"

#include <cmath>
#include <limits>
#include <sstream>

#include "mocapdb/core/error.hpp"

namespace mocapdb::kriging {

const char* to_string(VariogramFamily family) {
    return family == VariogramFamily::Spherical ? "sph" : "stable";
}

VariogramModel VariogramModel::spherical(double nugget, double sill, double range) {
    VariogramModel m;
    m.family = VariogramFamily::Spherical;
    m.exponent = 1.0;
    m.nugget = nugget;
    m.sill = sill;
    m.range = range;
    m.validate();
    return m;
}

VariogramModel VariogramModel::stable(double p, double nugget, double sill, double range) {
    VariogramModel m;
    m.family = VariogramFamily::Stable;
    m.exponent = p;
    m.nugget = nugget;
    m.sill = sill;
    m.range = range;
    m.validate();
    return m;
}

VariogramModel VariogramModel::from_paper_p(double p, double nugget, double sill, double range) {
    if (!(p >= 0.0 && p <= 2.0)) {
        throw InvalidArgument("variogram model: p must satisfy 0 <= p <= 2 (0 = spherical), got " +
                              std::to_string(p));
    }
    return p == 0.0 ? spherical(nugget, sill, range) : stable(p, nugget, sill, range);
}

void VariogramModel::validate() const {
    if (!(std::isfinite(nugget) && nugget >= 0.0)) {
        throw InvalidArgument("variogram model: nugget (theta0) must be finite and >= 0, got " +
                              std::to_string(nugget));
    }
    if (!(std::isfinite(sill) && sill >= 0.0)) {
        throw InvalidArgument("variogram model: sill (theta1) must be finite and >= 0, got " +
                              std::to_string(sill));
    }
    if (!(std::isfinite(range) && range > 0.0)) {
        throw InvalidArgument("variogram model: range (theta2) must be finite and > 0, got " +
                              std::to_string(range));
    }
    if (family == VariogramFamily::Stable && !(exponent > 0.0 && exponent <= 2.0)) {
        throw InvalidArgument("variogram model: stable exponent p must satisfy 0 < p <= 2, got " +
                              std::to_string(exponent));
    }
}

double VariogramModel::shape(double h) const {
    if (!(h > 0.0)) return 0.0;
    const double x = h / range;
    if (family == VariogramFamily::Spherical) {
        return x >= 1.0 ? 1.0 : x * (1.5 - 0.5 * x * x);
    }
    const double t = exponent == 1.0 ? x : (exponent == 2.0 ? x * x : std::pow(x, exponent));
    return -std::expm1(-t);
}

double VariogramModel::operator()(double h) const {
    if (!(h > 0.0)) return 0.0;
    return nugget + sill * shape(h);
}

void VariogramModel::gamma_of_squared(const Eigen::Ref<const Eigen::VectorXd>& squared_distances,
                                      Eigen::Ref<Eigen::VectorXd> out_gamma) const {
    if (out_gamma.size() != squared_distances.size()) {
        throw InvalidArgument("gamma_of_squared: out_gamma must have the size of squared_distances");
    }
    const double inv_r2 = 1.0 / (range * range);
    const auto d2 = squared_distances.array();
    auto out = out_gamma.array();
    // Single-pass, fully vectorizable expressions (this runs once per kriging query; Eigen 3.4 does not
    // vectorize select(), so gamma(0) = 0 is imposed by the factor mask = min(d2 / DBL_MIN, 1), which is
    // 1 for every d2 >= DBL_MIN and 0 at d2 = 0). log(0) = -inf gives exp(-inf) = 0, never NaN. out may
    // alias d2: each coefficient is read before it is written.
    constexpr double inv_dbl_min = 1.0 / std::numeric_limits<double>::min();
    if (family == VariogramFamily::Spherical) {
        out = (nugget + sill * ((d2 * inv_r2).sqrt().min(1.0) * (1.5 - 0.5 * (d2 * inv_r2).min(1.0)))) *
              (d2 * inv_dbl_min).min(1.0);
    } else if (exponent == 2.0) {
        out = (nugget + sill * (1.0 - (-(d2 * inv_r2)).exp())) * (d2 * inv_dbl_min).min(1.0);
    } else if (exponent == 1.0) {
        out = (nugget + sill * (1.0 - (-(d2 * inv_r2).sqrt()).exp())) * (d2 * inv_dbl_min).min(1.0);
    } else if (exponent == 1.5) {
        // Half-integer exponents by square roots instead of exp(p log x): x^1.5 = sqrt(t sqrt(t)), t = x^2.
        out = (nugget + sill * (1.0 - (-((d2 * inv_r2) * (d2 * inv_r2).sqrt()).sqrt()).exp())) *
              (d2 * inv_dbl_min).min(1.0);
    } else if (exponent == 0.5) {
        out = (nugget + sill * (1.0 - (-(d2 * inv_r2).sqrt().sqrt()).exp())) * (d2 * inv_dbl_min).min(1.0);
    } else {
        const double half_p = 0.5 * exponent;
        out = (nugget + sill * (1.0 - (-((half_p * (d2 * inv_r2).log()).exp())).exp())) * (d2 * inv_dbl_min).min(1.0);
    }
}

std::string VariogramModel::to_string() const {
    std::ostringstream os;
    os.precision(10);
    if (family == VariogramFamily::Spherical) {
        os << "sph";
    } else {
        os << "stable(p=" << exponent << ")";
    }
    os << " nugget=" << nugget << " sill=" << sill << " range=" << range;
    return os.str();
}

}  // namespace mocapdb::kriging
