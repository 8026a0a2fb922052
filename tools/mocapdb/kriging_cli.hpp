#pragma once
// Shared pieces of the `variogram` and `krige` commands: option parsing, the variogram estimate and
// fit on a table, and the JSON / text rendering of a model.
#include <optional>
#include <string>

#include <CLI/CLI.hpp>
#include <Eigen/Core>

#include "json_writer.hpp"
#include "mocapdb/kriging/kriging.hpp"
#include "mocapdb/kriging/variogram.hpp"
#include "mocapdb/kriging/variogram_fit.hpp"

namespace mocapdb::cli {

/// Options common to both commands (filled by CLI11).
struct TableKrigingArgs {
    std::string data;
    std::string coords;
    std::string value;
    std::string trend = "none";       ///< none | linear
    std::string trend_fit = "gls";    ///< gls | ols
    int bins = 10;
    double cutoff = 0.0;              ///< 0 = h_max / 2
    std::string estimator = "cressie";
    std::string weights = "cressie";  ///< cressie | npairs | unweighted
    bool normalize = false;
    bool json = false;
};

/// The table's coordinates (N by P, normalized when asked) and values (N).
struct TableData {
    Eigen::MatrixXd coords;
    Eigen::VectorXd values;
    std::optional<kriging::ControlScaling> scaling;  ///< set with --normalize
};

/// Registers --data --coords --value --trend --trend-fit --bins --cutoff --estimator --weights --normalize --json.
void add_table_options(CLI::App& cmd, TableKrigingArgs& t);

TableData load_table(const TableKrigingArgs& args);
kriging::KrigingOptions kriging_options(const TableKrigingArgs& args);
kriging::VariogramOptions variogram_options(const TableKrigingArgs& args);
kriging::VariogramFitOptions fit_options(const TableKrigingArgs& args);

/// Experimental variogram of the values (of their OLS-trend residuals with --trend linear).
kriging::ExperimentalVariogram table_variogram(const TableKrigingArgs& args, const TableData& data);

/// A fit request: "sph", "stable" (p chosen by LOO over 0.2..2.0), "stable:P", or "auto" (0.0..2.0).
struct FitRequest {
    bool by_loo = false;
    std::vector<double> grid;  ///< candidates when by_loo
    double p = 0.0;            ///< paper convention (0 = spherical) when !by_loo
};
FitRequest parse_fit(const std::string& spec);

struct FitOutcome {
    kriging::VariogramFit fit;
    std::optional<kriging::ExponentSelection> selection;
};
FitOutcome run_fit(const FitRequest& request, const kriging::ExperimentalVariogram& ev, const TableData& data,
                   const TableKrigingArgs& args);

/// --model sph | stable:P plus --nugget/--sill/--range.
kriging::VariogramModel parse_model(const std::string& spec, double nugget, double sill, double range);

void write_model_json(JsonWriter& j, const kriging::VariogramModel& m);
void write_fit_json(JsonWriter& j, const FitOutcome& f, const TableKrigingArgs& args);
std::string describe_fit(const FitOutcome& f, const TableKrigingArgs& args);

}  // namespace mocapdb::cli
