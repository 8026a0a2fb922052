// mocapdb variogram: experimental variogram (and optionally a fitted model) of a plain table.
#include <iomanip>
#include <iostream>
#include <memory>

#include "commands.hpp"
#include "json_writer.hpp"
#include "kriging_cli.hpp"
#include "mocapdb/kriging/trend.hpp"

namespace mocapdb::cli {
namespace {

struct VariogramArgs {
    TableKrigingArgs table;
    std::string fit;  // empty = no fit
};

}  // namespace

void setup_variogram(CLI::App& app) {
    auto args = std::make_shared<VariogramArgs>();
    CLI::App* cmd =
        app.add_subcommand("variogram", "Experimental variogram and model fit of a table (geostatistics check)");
    cmd->footer(
        "Bins are (lower, upper] of width cutoff/bins; pairs at distance 0 count in bin 1. The Cressie-Hawkins\n"
        "estimate uses the denominator 0.457 + 0.494/n + 0.045/n^2 (gstat omits the last term).\n"
        "JSON keys: estimator, trend, cutoff, width, max_distance, zero_distance_pairs,\n"
        "  bins[{bin, np, dist, center, gamma}], fit{model, p, nugget, sill, range, weights, objective,\n"
        "  converged, degenerate, selection[{p, loo_mse}]}.\n"
        "Examples:\n"
        "  mocapdb variogram --data meuse.csv --coords x,y --value logzinc --cutoff 1600\n"
        "  mocapdb variogram --data pts.csv --coords x,y,z --value v --trend linear --fit auto --json");
    add_table_options(*cmd, args->table);
    cmd->add_option("--fit", args->fit,
                    "fit a model: sph | stable (p by LOO) | stable:P | auto (p in 0,0.2..2 by LOO)");
    cmd->callback([args] {
        const TableKrigingArgs& t = args->table;
        const TableData data = load_table(t);
        const kriging::ExperimentalVariogram ev = table_variogram(t, data);
        std::optional<FitOutcome> fit;
        if (!args->fit.empty()) fit = run_fit(parse_fit(args->fit), ev, data, t);
        if (t.json) {
            JsonWriter j;
            json::write_table_variogram(j, table_settings(t), ev, fit);
            std::cout << j.str();
            return;
        }
        std::cout << "experimental variogram (" << kriging::to_string(ev.estimator) << "), " << ev.bins()
                  << " bins of width " << ev.width << " over [0, " << ev.cutoff << "], largest pair distance "
                  << ev.max_distance << ", trend " << t.trend << (t.normalize ? ", normalized coordinates" : "")
                  << "\n";
        std::cout << std::setw(5) << "bin" << std::setw(9) << "np" << std::setw(20) << "dist" << std::setw(20)
                  << "gamma"
                  << "\n";
        std::cout << std::setprecision(12);
        for (int u = 0; u < ev.bins(); ++u) {
            std::cout << std::setw(5) << u + 1 << std::setw(9) << ev.npairs[static_cast<std::size_t>(u)]
                      << std::setw(20) << ev.dist(u) << std::setw(20) << ev.gamma(u) << "\n";
        }
        if (ev.zero_distance_pairs > 0)
            std::cout << "(" << ev.zero_distance_pairs << " pairs at distance 0 in bin 1)\n";
        if (fit) std::cout << describe_fit(*fit, t);
    });
}

}  // namespace mocapdb::cli
