#pragma once
// Trend surfaces in the control space (paper Section 3.3): a D-dimensional hyperplane
// m(c) = l0 + l1 c1 + ... + lP cP fitted by least squares, and the basis the kriging systems use for
// their unbiasedness constraints.
//
// Internally the linear basis is centered and orthonormalized over the samples:
//   g(c) = [1, S^-1 V^T (c - mean)],   with  (C - 1 mean^T) = U S V^T (thin SVD, rank r),
// so that the N by (1 + r) sample basis G = [1, U] has orthogonal columns. Directions in which the
// control points do not vary (collinear or coplanar points, a constant axis) have singular values
// below rank_tolerance * s_max and are dropped: the trend is taken as flat along them (the
// minimum-norm / pseudo-inverse solution the paper uses), and the status reports the deficiency.
// The function space is that of the plain hyperplane whenever the points are in general position.
#include <vector>

#include <Eigen/Core>

namespace mocapdb::kriging {

enum class TrendKind {
    None,    ///< constant mean only (ordinary kriging).
    Linear,  ///< hyperplane in c (universal kriging with a linear drift).
};

const char* to_string(TrendKind kind);

/// The basis functions of a trend, built from the sample control points (immutable).
class TrendBasis {
public:
    TrendBasis() = default;

    /// coords: N by P control points (N >= 1). rank_tolerance: relative singular-value threshold.
    /// Throws InvalidArgument on N == 0, P == 0, non-finite coordinates or a non-positive tolerance.
    static TrendBasis build(const Eigen::Ref<const Eigen::MatrixXd>& coords, TrendKind kind,
                            double rank_tolerance = 1e-10);

    TrendKind kind() const { return kind_; }
    /// Number of basis functions K = 1 + rank (Linear) or 1 (None).
    Eigen::Index size() const { return 1 + rank_; }
    /// Control-space dimension P.
    Eigen::Index dimension() const { return mean_.size(); }
    /// Rank of the centered control points kept in the basis (0 for TrendKind::None).
    Eigen::Index rank() const { return rank_; }
    /// True when a Linear trend lost directions (P - rank of the centered points > 0).
    bool rank_deficient() const { return kind_ == TrendKind::Linear && rank_ < dimension(); }

    /// g(c). c: P; out_g: K.
    void evaluate(const Eigen::Ref<const Eigen::VectorXd>& c, Eigen::Ref<Eigen::VectorXd> out_g) const;
    /// queries: Q by P; returns K by Q (column q is g of query q).
    Eigen::MatrixXd evaluate_batch(const Eigen::Ref<const Eigen::MatrixXd>& queries) const;
    /// G: N by K, the basis at the sample points (first column all ones, others orthonormal).
    const Eigen::MatrixXd& sample_basis() const { return sample_basis_; }

    /// Maps the coefficients a (K) of sum_k a_k g_k(c) to the hyperplane l0 + l^T c.
    /// out_l: P (slopes), returns l0.
    double to_hyperplane(const Eigen::Ref<const Eigen::VectorXd>& a, Eigen::Ref<Eigen::VectorXd> out_l) const;

private:
    TrendKind kind_ = TrendKind::None;
    Eigen::Index rank_ = 0;
    Eigen::VectorXd mean_;          // P
    Eigen::MatrixXd projection_;    // P by r: V S^-1
    Eigen::MatrixXd sample_basis_;  // N by K
};

/// Ordinary-least-squares trend of several signals over the same control points.
struct OlsTrend {
    Eigen::MatrixXd coefficients;  ///< K by D: coefficients in the TrendBasis.
    Eigen::MatrixXd residuals;     ///< N by D: samples minus trend at the samples.
};

/// Least-squares fit (paper Equation 2) of each column of samples (N by D) on the basis.
/// Throws InvalidArgument when samples has not N rows.
OlsTrend fit_trend_ols(const TrendBasis& basis, const Eigen::Ref<const Eigen::MatrixXd>& samples);

/// Trend values at queries: basis Q by P queries, coefficients K by D; returns Q by D.
Eigen::MatrixXd evaluate_trend(const TrendBasis& basis, const Eigen::Ref<const Eigen::MatrixXd>& coefficients,
                               const Eigen::Ref<const Eigen::MatrixXd>& queries);

/// Per-axis normalization of control parameters, c_normalized = (c - offset) / scale.
/// The motion pipeline normalizes so that every axis contributes comparably to distances (the paper
/// requires normalized parameters for intrinsic stationarity); users may override the scales.
///
/// Periodic axes (a bearing, period 2 pi rad or 360 deg): such an axis becomes two coordinates,
/// the point at angle 2 pi (c - offset) / period on a circle of radius period / (2 pi scale). Distances
/// along it are chords, so c and c + period coincide, and two values delta apart are
/// (period / (pi scale)) sin(pi delta / period) ~ delta / scale apart for small delta, as on a linear
/// axis. The kriging then works in embedded_dimension() coordinates (its linear trend in cos and sin of
/// the angle).
///
/// Categorical axes (L >= 2 levels; the coordinate is a level index 0 .. L-1, never standardized:
/// offset 0, scale 1) become L indicator coordinates, kLevelCoordinate at the level's one and 0 at the
/// others: two points of different levels are 2 apart along it (a balanced two-level indicator after
/// standardization), points of one level 0. A linear trend over the indicators is a mean per level
/// (universal kriging's per-category trend). A coordinate that is not a level index is refused.
/// Thread safety: plain data.
struct ControlScaling {
    Eigen::VectorXd offset;   ///< P
    Eigen::VectorXd scale;    ///< P, all > 0
    Eigen::VectorXd period;   ///< P periods (0 = a linear axis), or empty: every axis linear
    std::vector<int> levels;  ///< P level counts (0 = numeric, >= 2 = categorical), or empty: none categorical
    static constexpr double kLevelCoordinate = 1.4142135623730951;  ///< sqrt 2

    /// offset = per-axis mean, scale = per-axis population standard deviation; an axis with zero spread
    /// keeps scale 1. coords: N by P. periods: empty or P values >= 0 (0 = linear); on a periodic axis
    /// offset = the circular mean and scale = the root mean square of the deviations from it, each
    /// wrapped into [-period / 2, period / 2).
    /// levels: empty or P counts (0 = numeric); a categorical axis keeps offset 0, scale 1.
    static ControlScaling from_data(const Eigen::Ref<const Eigen::MatrixXd>& coords,
                                    const Eigen::Ref<const Eigen::VectorXd>& periods = Eigen::VectorXd(),
                                    const std::vector<int>& levels = {});
    /// offset = 0, scale = 1 (identity).
    static ControlScaling identity(Eigen::Index dimension);

    /// Throws InvalidArgument unless sizes agree, every scale is finite and > 0, every period finite
    /// and >= 0, and every level count 0 or >= 2 on an axis that is not periodic.
    void validate(Eigen::Index dimension) const;
    bool has_periodic_axis() const;
    bool has_categorical_axis() const;
    /// True when axis k has levels.
    bool categorical(Eigen::Index k) const;
    /// Coordinates after apply(): P plus one per periodic axis plus L - 1 per categorical axis.
    Eigen::Index embedded_dimension() const;
    /// coords: M by P; returns M by embedded_dimension() (M by P when no axis is periodic).
    Eigen::MatrixXd apply(const Eigen::Ref<const Eigen::MatrixXd>& coords) const;
    /// One point c (P values) into out (resized to embedded_dimension(); no allocation when it has that size).
    void apply_point(const Eigen::Ref<const Eigen::VectorXd>& c, Eigen::VectorXd& out) const;
};

/// x wrapped into [-period / 2, period / 2) (period > 0).
double wrap_to_half_period(double x, double period);

}  // namespace mocapdb::kriging
