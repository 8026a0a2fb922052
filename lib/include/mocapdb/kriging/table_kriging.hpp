#pragma once
// Kriging of a plain table (`mocapdb variogram` and `mocapdb krige`, the geostatistics
// checks against gstat): a CSV table's coordinates and values (normalized per axis when asked), the
// experimental variogram of the values or of their OLS-trend residuals, the variogram model fitted with
// a fixed exponent or chosen by leave-one-out, and the predictions, variances and reliabilities at
// query points with optional leave-one-out cross validation. Nothing is printed.
// Errors: IoError / ParseError from the CSV (csv_table.hpp); InvalidArgument for fewer than 2 rows and
// from the kriging and fitting steps. Threads: no shared state.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "mocapdb/kriging/kriging.hpp"
#include "mocapdb/kriging/trend.hpp"
#include "mocapdb/kriging/variogram.hpp"
#include "mocapdb/kriging/variogram_fit.hpp"

namespace mocapdb::kriging {

/// A table's coordinates (N by P, normalized when asked) and values (N).
struct ScalarTable {
    Eigen::MatrixXd coords;
    Eigen::VectorXd values;
    std::optional<ControlScaling> scaling;  ///< set when normalized: queries go through it too
};

/// The columns `coords` and `value` of the CSV file; `normalize` scales every coordinate axis to zero
/// mean and unit standard deviation.
ScalarTable read_scalar_table(const std::filesystem::path& csv, const std::vector<std::string>& coords,
                              const std::string& value, bool normalize);

/// Experimental variogram of the values, or with TrendKind::Linear of their OLS-trend residuals.
ExperimentalVariogram table_variogram(const ScalarTable& table, TrendKind trend, const VariogramOptions& options);

/// A variogram fit: a fixed exponent (paper convention, 0 = spherical), or the exponent of `grid`
/// chosen by leave-one-out.
struct VariogramFitRequest {
    bool by_loo = false;
    std::vector<double> grid;  ///< candidates when by_loo
    double p = 0.0;            ///< when !by_loo
};

struct VariogramChoice {
    VariogramFit fit;
    std::optional<ExponentSelection> selection;  ///< when chosen by leave-one-out
};

/// Fits the request to `ev`; leave-one-out selection krige the table with `kriging`.
VariogramChoice fit_table_variogram(const VariogramFitRequest& request, const ExperimentalVariogram& ev,
                                    const ScalarTable& table, const KrigingOptions& kriging,
                                    const VariogramFitOptions& fit);

struct TableKriging {
    KrigingBatch batch;            ///< weights, variances, reliabilities at the queries
    Eigen::VectorXd prediction;    ///< per query
    std::optional<LooResult> loo;  ///< leave-one-out of the table's values, when asked
    KrigingStatus status;
};

/// Kriging of the table's values with `model` at `queries` (rows in the table's own units; scaled like
/// the table when it is normalized).
TableKriging krige_table(const ScalarTable& table, const VariogramModel& model, const KrigingOptions& options,
                         const Eigen::MatrixXd& queries, bool leave_one_out);

}  // namespace mocapdb::kriging
