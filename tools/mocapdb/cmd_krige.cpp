// mocapdb krige: ordinary / universal kriging of a plain table at the rows of a query table.
#include <iomanip>
#include <iostream>
#include <memory>

#include "commands.hpp"
#include "json_writer.hpp"
#include "kriging_cli.hpp"
#include "mocapdb/core/error.hpp"
#include "mocapdb/io/csv_table.hpp"
#include "option_lists.hpp"

namespace mocapdb::cli {
namespace {

struct KrigeArgs {
    TableKrigingArgs table;
    std::string query;
    std::string model;  // sph | stable:P
    double nugget = 0.0;
    double sill = -1.0;
    double range = -1.0;
    std::string fit;  // sph | stable | stable:P | auto
    bool loo = false;
};

}  // namespace

void setup_krige(CLI::App& app) {
    auto args = std::make_shared<KrigeArgs>();
    CLI::App* cmd =
        app.add_subcommand("krige", "Ordinary / universal kriging of a table at query points (geostatistics check)");
    cmd->footer(
        "The variance is the kriging (prediction-error) variance; with --trend-fit gls (default) it is the\n"
        "standard universal-kriging variance that gstat reports. paper_variance = sum_i b_i gamma(|c - c_i|)\n"
        "and reliability = 1 - paper_variance / (nugget + sill) follow Mukai & Kuriyama (Appendix B).\n"
        "With --normalize the model range is in normalized units (each axis: zero mean, unit std).\n"
        "JSON keys: model{model, p, nugget, sill, range}, fit{...} (with --fit), trend, trend_fit,\n"
        "  status{factorization, jitter, rcond, duplicates_merged, trend_rank_deficient},\n"
        "  predictions[{row, prediction, variance, paper_variance, reliability}],\n"
        "  loo{mse, rows[{row, observed, prediction, variance, residual, zscore}]} (with --loo).\n"
        "Examples:\n"
        "  mocapdb krige --data meuse.csv --coords x,y --value logzinc --query grid.csv \\\n"
        "      --model sph --nugget 0.05 --sill 0.55 --range 900 --trend linear\n"
        "  mocapdb krige --data pts.csv --coords x,y,z --value v --query q.csv --fit auto --loo --json");
    add_table_options(*cmd, args->table);
    cmd->add_option("--query", args->query, "CSV with the coordinate columns of the query points")->required();
    auto* model = cmd->add_option("--model", args->model, "fixed model: sph | stable:P (0 < P <= 2)");
    cmd->add_option("--nugget", args->nugget, "nugget (theta0) of --model")->capture_default_str();
    cmd->add_option("--sill", args->sill, "partial sill (theta1) of --model");
    cmd->add_option("--range", args->range, "range (theta2) of --model");
    auto* fit = cmd->add_option("--fit", args->fit, "estimate the model instead: sph | stable | stable:P | auto");
    model->excludes(fit);
    cmd->add_flag("--loo", args->loo, "also print leave-one-out cross validation of the data");
    cmd->callback([args] {
        const TableKrigingArgs& t = args->table;
        if (args->model.empty() == args->fit.empty()) {
            throw InvalidArgument("krige: give either --model (with --sill and --range) or --fit");
        }
        const TableData data = load_table(t);
        std::optional<FitOutcome> fit_outcome;
        kriging::VariogramModel vm;
        if (!args->model.empty()) {
            if (args->sill < 0.0 || args->range <= 0.0) {
                throw InvalidArgument("krige: --model needs --sill >= 0 and --range > 0");
            }
            vm = parse_model(args->model, args->nugget, args->sill, args->range);
        } else {
            fit_outcome = run_fit(parse_fit(args->fit), table_variogram(t, data), data, t);
            if (fit_outcome->fit.status == kriging::FitStatus::Degenerate) {
                throw InvalidArgument("krige: the values do not vary (no variogram to fit); give --model instead");
            }
            vm = fit_outcome->fit.model;
        }
        const CsvTable qcsv = CsvTable::read(args->query);
        qcsv.require_data_rows();
        const Eigen::MatrixXd queries = qcsv.columns(split_names(t.coords, "--coords"));
        const kriging::TableKriging result = kriging::krige_table(data, vm, kriging_options(t), queries, args->loo);
        const kriging::KrigingBatch& b = result.batch;
        const Eigen::VectorXd& pred = result.prediction;
        const std::optional<kriging::LooResult>& loo = result.loo;
        const kriging::KrigingStatus& st = result.status;

        if (t.json) {
            JsonWriter j;
            json::write_table_kriging(j, table_settings(t), vm, fit_outcome, data, result);
            std::cout << j.str();
            return;
        }
        std::cout << std::setprecision(12);
        std::cout << "model: " << vm.to_string() << "; trend " << t.trend << " (" << t.trend_fit << ")"
                  << (t.normalize ? "; normalized coordinates" : "") << "\n";
        if (fit_outcome) std::cout << describe_fit(*fit_outcome, t);
        std::cout << "factorization: " << kriging::to_string(st.factorization) << " (rcond " << st.rcond;
        if (st.jitter > 0.0) std::cout << ", jitter " << st.jitter;
        if (st.duplicates_merged > 0) std::cout << ", " << st.duplicates_merged << " duplicate points merged";
        if (st.trend_rank_deficient) std::cout << ", trend rank deficient";
        std::cout << ")\n";
        std::cout << std::setw(6) << "row" << std::setw(20) << "prediction" << std::setw(20) << "variance"
                  << std::setw(16) << "reliability"
                  << "\n";
        for (Eigen::Index q = 0; q < queries.rows(); ++q) {
            std::cout << std::setw(6) << q + 1 << std::setw(20) << pred(q) << std::setw(20) << b.variance(q)
                      << std::setw(16) << b.reliability(q) << "\n";
        }
        if (loo) {
            std::cout << "leave-one-out: mse " << loo->mse << "\n";
            std::cout << std::setw(6) << "row" << std::setw(20) << "observed" << std::setw(20) << "prediction"
                      << std::setw(20) << "variance" << std::setw(20) << "residual" << std::setw(16) << "zscore"
                      << "\n";
            for (Eigen::Index i = 0; i < data.values.size(); ++i) {
                std::cout << std::setw(6) << i + 1 << std::setw(20) << data.values(i) << std::setw(20)
                          << loo->prediction(i, 0) << std::setw(20) << loo->variance(i) << std::setw(20)
                          << loo->residual(i, 0) << std::setw(16) << loo->zscore(i, 0) << "\n";
            }
        }
    });
}

}  // namespace mocapdb::cli
