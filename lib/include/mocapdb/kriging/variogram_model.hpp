#pragma once
// Theoretical variogram models of the geostatistical motion interpolation paper (Mukai & Kuriyama 2005,
// Figure 4 and Section 4.2): the spherical model (the paper's p = 0) and the stable / exponential-power
// family gamma(h) = theta0 + theta1 (1 - exp(-(h / theta2)^p)), 0 < p <= 2 (gstat calls it "Exc";
// p = 1 is the exponential model, p = 2 the Gaussian one).
//
// Conventions used by every kriging function:
//   gamma(0) = 0 exactly (the nugget is a discontinuity at the origin),
//   gamma(h) = nugget + sill * shape(h / range) for h > 0, with shape rising from 0 to 1,
//   covariance(h) = nugget + sill - gamma(h), so covariance(0) = nugget + sill (the total sill).
#include <string>

#include <Eigen/Core>

namespace mocapdb::kriging {

/// Shape of the model; the exponent of the stable family is a separate field.
enum class VariogramFamily {
    Spherical,  ///< theta0 + theta1 (3x/2 - x^3/2) for x = h/theta2 < 1, theta0 + theta1 beyond.
    Stable,     ///< theta0 + theta1 (1 - exp(-(h/theta2)^p)), 0 < p <= 2.
};

/// Name used in text output and on the command line: "sph" or "stable".
const char* to_string(VariogramFamily family);

/// A fitted or user-given variogram model (theta0 = nugget, theta1 = sill, theta2 = range in the paper).
struct VariogramModel {
    VariogramFamily family = VariogramFamily::Spherical;
    double exponent = 1.0;  ///< p of the stable family, 0 < p <= 2 (ignored by the spherical model).
    double nugget = 0.0;    ///< theta0 >= 0: white-noise intensity.
    double sill = 1.0;      ///< theta1 >= 0: partial sill (dissimilarity at infinity minus the nugget).
    double range = 1.0;     ///< theta2 > 0: distance scale (the spherical model reaches the sill there).

    /// Spherical model. Throws InvalidArgument unless nugget >= 0, sill >= 0, range > 0 (all finite).
    static VariogramModel spherical(double nugget, double sill, double range);
    /// Stable model with exponent p. Throws InvalidArgument unless 0 < p <= 2 and the constraints above.
    static VariogramModel stable(double p, double nugget, double sill, double range);
    /// The paper's single parameter p: p == 0 selects the spherical model, 0 < p <= 2 the stable one.
    static VariogramModel from_paper_p(double p, double nugget, double sill, double range);

    /// The paper's p: 0 for the spherical model, the exponent for the stable model.
    double paper_p() const { return family == VariogramFamily::Spherical ? 0.0 : exponent; }
    /// nugget + sill: gamma at infinite distance and covariance at distance 0.
    double total_sill() const { return nugget + sill; }

    /// Throws InvalidArgument naming the violated constraint when the parameters are out of range.
    void validate() const;

    /// gamma(h) for a distance h >= 0 (gamma(0) = 0).
    double operator()(double h) const;
    /// shape(h / range) in [0, 1], so gamma(h) = nugget + sill * shape for h > 0.
    double shape(double h) const;
    /// covariance(h) = total_sill() - gamma(h); covariance(0) = total_sill().
    double covariance(double h) const { return total_sill() - (*this)(h); }

    /// Vectorized gamma of SQUARED distances: out_gamma(i) = gamma(sqrt(squared_distances(i))). (A squared
    /// distance below DBL_MIN, i.e. a distance below ~1.5e-154, is blended towards gamma(0) = 0.)
    /// squared_distances: M (entries >= 0); out_gamma: M (may alias squared_distances).
    void gamma_of_squared(const Eigen::Ref<const Eigen::VectorXd>& squared_distances,
                          Eigen::Ref<Eigen::VectorXd> out_gamma) const;

    /// One-line description, e.g. "stable(p=1.5) nugget=0.05 sill=0.55 range=500".
    std::string to_string() const;
};

}  // namespace mocapdb::kriging
