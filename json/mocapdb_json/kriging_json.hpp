#pragma once
// The documents of kriging a plain table: `mocapdb variogram --json` (the experimental variogram and
// an optional fit) and `mocapdb krige --json` (predictions, status, leave-one-out). Formatting only;
// no I/O. Keys: docs/json.md.
#include <optional>
#include <string>

#include "mocapdb/kriging/table_kriging.hpp"
#include "mocapdb/kriging/variogram.hpp"
#include "mocapdb/kriging/variogram_fit.hpp"
#include "mocapdb_json/json_writer.hpp"

namespace mocapdb::json {

/// The options of the table the documents echo (as given on the command line).
struct TableSettings {
    std::string trend;      ///< none | linear
    std::string trend_fit;  ///< gls | ols
    bool normalized = false;
    std::string weights;  ///< of the fit: cressie | npairs | unweighted
};

/// {model, p, nugget, sill, range} (an object; no key).
void write_variogram_model(JsonWriter& j, const kriging::VariogramModel& m);
/// The model's members, weights, objective, converged, degenerate[, selection] (an object; no key).
void write_variogram_fit(JsonWriter& j, const kriging::VariogramChoice& f, const std::string& weights);

void write_table_variogram(JsonWriter& j, const TableSettings& t, const kriging::ExperimentalVariogram& ev,
                           const std::optional<kriging::VariogramChoice>& fit);
/// `model`: the variogram krigged with (fixed or `fit`'s); `table`: the data (observed values for loo).
void write_table_kriging(JsonWriter& j, const TableSettings& t, const kriging::VariogramModel& model,
                         const std::optional<kriging::VariogramChoice>& fit, const kriging::ScalarTable& table,
                         const kriging::TableKriging& result);

}  // namespace mocapdb::json
