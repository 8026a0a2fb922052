#pragma once
// Shared pieces of the `variogram` and `krige` commands: option parsing into the library's table
// kriging (mocapdb/kriging/table_kriging.hpp), and the text rendering of a fit (JSON: kriging_json.hpp).
#include <optional>
#include <string>

#include <CLI/CLI.hpp>
#include <Eigen/Core>

#include "json_writer.hpp"
#include "mocapdb_json/kriging_json.hpp"
#include "mocapdb/kriging/kriging.hpp"
#include "mocapdb/kriging/table_kriging.hpp"
#include "mocapdb/kriging/variogram.hpp"
#include "mocapdb/kriging/variogram_fit.hpp"

namespace mocapdb::cli {

/// Options common to both commands (filled by CLI11).
struct TableKrigingArgs {
    std::string data;
    std::string coords;
    std::string value;
    std::string trend = "none";     ///< none | linear
    std::string trend_fit = "gls";  ///< gls | ols
    int bins = 10;
    double cutoff = 0.0;  ///< 0 = h_max / 2
    std::string estimator = "cressie";
    std::string weights = "cressie";  ///< cressie | npairs | unweighted
    bool normalize = false;
    bool json = false;
};

/// The table's coordinates (N by P, normalized with --normalize) and values (N).
using TableData = kriging::ScalarTable;

/// Registers --data --coords --value --trend --trend-fit --bins --cutoff --estimator --weights --normalize --json.
void add_table_options(CLI::App& cmd, TableKrigingArgs& t);

TableData load_table(const TableKrigingArgs& args);
kriging::KrigingOptions kriging_options(const TableKrigingArgs& args);
kriging::VariogramOptions variogram_options(const TableKrigingArgs& args);
kriging::VariogramFitOptions fit_options(const TableKrigingArgs& args);

/// kriging::table_variogram with the options of `args` (OLS-trend residuals with --trend linear).
kriging::ExperimentalVariogram table_variogram(const TableKrigingArgs& args, const TableData& data);

/// A fit request: "sph", "stable" (p chosen by LOO over 0.2..2.0), "stable:P", or "auto" (0.0..2.0).
using FitRequest = kriging::VariogramFitRequest;
FitRequest parse_fit(const std::string& spec);

using FitOutcome = kriging::VariogramChoice;
/// kriging::fit_table_variogram with the options of `args`.
FitOutcome run_fit(const FitRequest& request, const kriging::ExperimentalVariogram& ev, const TableData& data,
                   const TableKrigingArgs& args);

/// --model sph | stable:P plus --nugget/--sill/--range.
kriging::VariogramModel parse_model(const std::string& spec, double nugget, double sill, double range);

/// The options the --json documents echo.
json::TableSettings table_settings(const TableKrigingArgs& args);
std::string describe_fit(const FitOutcome& f, const TableKrigingArgs& args);

}  // namespace mocapdb::cli
