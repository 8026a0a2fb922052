#pragma once
// Fitting a variogram model to an experimental variogram (paper Appendix A) and choosing the model's
// exponent p by leave-one-out cross validation.
//
// Details: docs/headers/kriging.md (mocapdb/kriging/variogram_fit.hpp).
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "mocapdb/kriging/kriging.hpp"
#include "mocapdb/kriging/variogram.hpp"
#include "mocapdb/kriging/variogram_model.hpp"

namespace mocapdb::kriging {

enum class FitWeighting { Cressie, CressieFixed, Npairs, Unweighted };
enum class FitAbscissa {
    MeanDistance,  ///< h_u = mean pair distance of the bin (gstat).
    BinCenter,     ///< h_u = center of the bin (the paper's h_step (u - 1/2)).
};

const char* to_string(FitWeighting weighting);

struct VariogramFitOptions {
    FitWeighting weighting = FitWeighting::Cressie;
    FitAbscissa abscissa = FitAbscissa::MeanDistance;
    /// Start model for CressieFixed (its weights) and an extra LM start point for the others. Its
    /// family/exponent are ignored (the ones passed to fit_variogram are used).
    std::optional<VariogramModel> start;
    bool fit_nugget = true;          ///< false: theta0 fixed at 0.
    double gamma_floor = 1e-6;       ///< (0, 1): relative floor of gamma* inside the weights.
    double range_min_factor = 1e-3;  ///< > 0.
    double range_max_factor = 1e2;   ///< > range_min_factor.
    int max_iterations = 500;        ///< LM iterations per start point (>= 1).
    /// >= 0: lower bound of the nugget (with fit_nugget false the nugget is fixed at this value). A Gaussian
    /// (p = 2) model needs one: without a nugget its kriging system is numerically singular.
    double min_nugget = 0.0;
    /// >= 0, 0 = none: upper bound of nugget + sill (e.g. tied to the variance of the trend residuals, so
    /// that a variogram rising as h^2 over the lags cannot run to an arbitrary sill).
    double max_total_sill = 0.0;
};

/// What a fit is worth (like gstat's "singular model" / "no convergence" warnings). A fit that is
/// not Ok is still a valid model, but the caller must report the status, never use it silently.
enum class FitStatus {
    Ok,
    RangeAtBound,  ///< the range sits on range_max_factor * h_ref: the lags do not show where the sill is reached
    SillAtBound,   ///< nugget + sill sits on max_total_sill
    PureNugget,    ///< sill ~ 0: no spatial correlation (the kernel reduces to the trend)
    Degenerate,    ///< no usable bins or all gammabar are 0: the model is a placeholder
};

const char* to_string(FitStatus status);

struct VariogramFit {
    VariogramModel model;
    double objective = 0.0;  ///< R(theta) at the solution (with the chosen weighting).
    int iterations = 0;      ///< LM iterations of the winning start.
    bool converged = false;  ///< LM stopped on its tolerance (not on the iteration limit).
    int bins_used = 0;       ///< non-empty bins.
    FitStatus status = FitStatus::Ok;
};

/// Fits nugget, sill and range of the given family / exponent (exponent ignored for Spherical).
/// Throws InvalidArgument for an invalid exponent, a start model required (CressieFixed) but absent, or
/// out-of-range options. A variogram without usable bins gives degenerate = true.
VariogramFit fit_variogram(const ExperimentalVariogram& ev, VariogramFamily family, double exponent,
                           const VariogramFitOptions& options = {});

/// R(theta) of a given model under the options' weighting (CressieFixed uses options.start).
double fit_objective(const ExperimentalVariogram& ev, const VariogramModel& model, const VariogramFitOptions& options);

/// The paper's grid p = 0.0, 0.2, ..., 2.0 (p = 0 is the spherical model).
std::vector<double> paper_exponent_grid();

struct ExponentSelection {
    std::vector<double> grid;        ///< candidate p (paper convention: 0 = spherical).
    std::vector<VariogramFit> fits;  ///< one fit per candidate.
    Eigen::VectorXd loo_mse;         ///< leave-one-out mean squared error per candidate (inf if unusable).
    std::size_t best = 0;            ///< index of the smallest loo_mse.
    const VariogramModel& model() const { return fits.at(best).model; }
};

/// For each p of the grid: fit theta to ev, build the kriging system (one factorization) and compute the
/// closed-form leave-one-out MSE of the values; returns all of them and the best.
/// coords: N by P; values: N by D (D >= 1: each column is cross-validated with the same kernel).
/// Throws InvalidArgument on shape mismatch, an empty grid or a p outside [0, 2].
ExponentSelection select_exponent(const ExperimentalVariogram& ev, const Eigen::Ref<const Eigen::MatrixXd>& coords,
                                  const Eigen::Ref<const Eigen::MatrixXd>& values,
                                  const KrigingOptions& kriging_options, const VariogramFitOptions& fit_options = {},
                                  const std::vector<double>& grid = paper_exponent_grid());

}  // namespace mocapdb::kriging
