#pragma once
// Experimental (empirical) variograms: pairs of samples are binned by the distance h = |c_i - c_j|
// between their control parameters, and each bin gets a robust (Cressie-Hawkins) or a classical
// (Matheron) estimate of the semivariance from the pairwise differences d_ij of the samples.
//
// Details: docs/headers/kriging.md (mocapdb/kriging/variogram.hpp).
#include <cstddef>
#include <vector>

#include <Eigen/Core>

namespace mocapdb::kriging {

enum class VariogramEstimator {
    Cressie,   ///< Cressie-Hawkins robust estimate (three-term denominator).
    Matheron,  ///< Classical method-of-moments estimate.
};

const char* to_string(VariogramEstimator estimator);

struct VariogramOptions {
    int bins = 10;        ///< N_I >= 1.
    double cutoff = 0.0;  ///< > 0; 0 means h_max / 2.
    VariogramEstimator estimator = VariogramEstimator::Cressie;
};

/// One experimental variogram. All vectors have `bins` entries; empty bins have npairs == 0 and
/// dist == gamma == 0 (they are skipped by the fit).
struct ExperimentalVariogram {
    Eigen::VectorXd center;               ///< bin centers h_u = w (u - 1/2) (the paper's abscissa).
    Eigen::VectorXd dist;                 ///< mean pair distance in the bin (gstat's "dist").
    Eigen::VectorXd gamma;                ///< semivariance estimate.
    std::vector<std::size_t> npairs;      ///< n(I_u): number of pairs in the bin.
    double cutoff = 0.0;                  ///< upper end of the last bin.
    double width = 0.0;                   ///< bin width w.
    double max_distance = 0.0;            ///< h_max over all pairs.
    std::size_t zero_distance_pairs = 0;  ///< pairs with h == 0 (counted in bin 1).
    VariogramEstimator estimator = VariogramEstimator::Cressie;

    int bins() const { return static_cast<int>(gamma.size()); }
    /// Number of bins with at least one pair.
    int nonempty_bins() const;
};

/// Core estimator. distances: N by N symmetric matrix of control-space distances h_ij; differences:
/// N by N symmetric matrix of sample dissimilarities d_ij >= 0. Only the strict upper triangles are
/// read. Throws InvalidArgument on shape mismatch, N < 2, bins < 1, negative cutoff, or a negative or
/// non-finite entry in either upper triangle.
ExperimentalVariogram experimental_variogram(const Eigen::Ref<const Eigen::MatrixXd>& distances,
                                             const Eigen::Ref<const Eigen::MatrixXd>& differences,
                                             const VariogramOptions& options = {});

/// Scalar samples. coords: N by P control parameters; values: N (e.g. trend residuals r_i).
ExperimentalVariogram experimental_variogram_scalar(const Eigen::Ref<const Eigen::MatrixXd>& coords,
                                                    const Eigen::Ref<const Eigen::VectorXd>& values,
                                                    const VariogramOptions& options = {});

/// Vector samples with the Euclidean distance between rows. coords: N by P; samples: N by D.
ExperimentalVariogram experimental_variogram_rows(const Eigen::Ref<const Eigen::MatrixXd>& coords,
                                                  const Eigen::Ref<const Eigen::MatrixXd>& samples,
                                                  const VariogramOptions& options = {});

/// Euclidean distances between the rows of points (N by P): returns N by N.
Eigen::MatrixXd pairwise_distances(const Eigen::Ref<const Eigen::MatrixXd>& points);

/// The Cressie-Hawkins denominator with three terms: 0.457 + 0.494/n + 0.045/n^2.
double cressie_denominator(std::size_t npairs);
/// Converts a robust estimate computed with gstat's two-term denominator (0.457 + 0.494/n) to the
/// three-term convention used here.
double cressie_gstat_to_three_term(double gamma_gstat, std::size_t npairs);

}  // namespace mocapdb::kriging
