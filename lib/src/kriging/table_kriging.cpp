#include "mocapdb/kriging/table_kriging.hpp"

#include "mocapdb/core/error.hpp"
#include "mocapdb/io/csv_table.hpp"

namespace mocapdb::kriging {

ScalarTable read_scalar_table(const std::filesystem::path& csv_path, const std::vector<std::string>& coords,
                              const std::string& value, bool normalize) {
    const CsvTable csv = CsvTable::read(csv_path);
    csv.require_data_rows();
    ScalarTable d;
    d.coords = csv.columns(coords);
    d.values = csv.columns({value}).col(0);
    if (d.coords.rows() < 2) throw InvalidArgument(csv_path.string() + ": need at least 2 data rows for kriging");
    if (normalize) {
        d.scaling = ControlScaling::from_data(d.coords);
        d.coords = d.scaling->apply(d.coords);
    }
    return d;
}

ExperimentalVariogram table_variogram(const ScalarTable& table, TrendKind trend, const VariogramOptions& options) {
    Eigen::VectorXd r = table.values;
    if (trend == TrendKind::Linear) {
        const TrendBasis basis = TrendBasis::build(table.coords, TrendKind::Linear);
        r = fit_trend_ols(basis, table.values).residuals.col(0);
    }
    return experimental_variogram_scalar(table.coords, r, options);
}

VariogramChoice fit_table_variogram(const VariogramFitRequest& request, const ExperimentalVariogram& ev,
                                    const ScalarTable& table, const KrigingOptions& kriging,
                                    const VariogramFitOptions& fit) {
    VariogramChoice out;
    if (request.by_loo) {
        out.selection = select_exponent(ev, table.coords, table.values, kriging, fit, request.grid);
        out.fit = out.selection->fits[out.selection->best];
    } else {
        const VariogramFamily fam = request.p == 0.0 ? VariogramFamily::Spherical : VariogramFamily::Stable;
        out.fit = fit_variogram(ev, fam, request.p == 0.0 ? 1.0 : request.p, fit);
    }
    return out;
}

TableKriging krige_table(const ScalarTable& table, const VariogramModel& model, const KrigingOptions& options,
                         const Eigen::MatrixXd& queries, bool leave_one_out) {
    const Eigen::MatrixXd q = table.scaling ? table.scaling->apply(queries) : queries;
    const Kriging k = Kriging::build(table.coords, model, options);
    TableKriging out;
    out.batch = k.estimate_batch(q);
    out.prediction = out.batch.weights.transpose() * table.values;
    if (leave_one_out) out.loo = k.leave_one_out(table.values);
    out.status = k.status();
    return out;
}

}  // namespace mocapdb::kriging
