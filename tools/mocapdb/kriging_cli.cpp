#include "kriging_cli.hpp"

#include <cstdlib>
#include <sstream>

#include "mocapdb/core/error.hpp"
#include "option_lists.hpp"

namespace mocapdb::cli {

using namespace mocapdb::kriging;

void add_table_options(CLI::App& cmd, TableKrigingArgs& t) {
    cmd.add_option("--data", t.data, "CSV file with a header row")->required();
    cmd.add_option("--coords", t.coords, "comma-separated coordinate columns, e.g. x,y")->required();
    cmd.add_option("--value", t.value, "value column")->required();
    cmd.add_option("--trend", t.trend, "none | linear (variogram of OLS-trend residuals)")->capture_default_str();
    cmd.add_option("--trend-fit", t.trend_fit,
                   "gls (standard universal kriging) | ols (the paper: OLS hyperplane, ordinary kriging of residuals); "
                   "used for leave-one-out")
        ->capture_default_str();
    cmd.add_option("--bins", t.bins, "number of equal-width distance bins")->capture_default_str();
    cmd.add_option("--cutoff", t.cutoff, "largest distance binned (default: half the largest pair distance)");
    cmd.add_option("--estimator", t.estimator, "cressie (robust, 3-term denominator) | matheron")
        ->capture_default_str();
    cmd.add_option("--weights", t.weights, "fit weights: cressie (n/gamma*^2, re-evaluated) | npairs | unweighted")
        ->capture_default_str();
    cmd.add_flag("--normalize", t.normalize,
                 "scale every coordinate axis to zero mean and unit standard deviation before distances");
    cmd.add_flag("--json", t.json, "machine-readable output");
}

TableData load_table(const TableKrigingArgs& args) {
    return read_scalar_table(args.data, split_names(args.coords, "--coords"), args.value, args.normalize);
}

KrigingOptions kriging_options(const TableKrigingArgs& args) {
    KrigingOptions o;
    if (args.trend == "none") {
        o.trend = TrendKind::None;
    } else if (args.trend == "linear") {
        o.trend = TrendKind::Linear;
    } else {
        throw InvalidArgument("--trend must be none or linear, got '" + args.trend + "'");
    }
    if (args.trend_fit == "gls") {
        o.trend_fit = TrendFit::GLS;
    } else if (args.trend_fit == "ols") {
        o.trend_fit = TrendFit::OLS;
    } else {
        throw InvalidArgument("--trend-fit must be gls or ols, got '" + args.trend_fit + "'");
    }
    return o;
}

VariogramOptions variogram_options(const TableKrigingArgs& args) {
    VariogramOptions v;
    if (args.bins < 1) throw InvalidArgument("--bins must be >= 1, got " + std::to_string(args.bins));
    if (!(args.cutoff >= 0.0)) throw InvalidArgument("--cutoff must be > 0 (omit it for h_max / 2)");
    v.bins = args.bins;
    v.cutoff = args.cutoff;
    if (args.estimator == "cressie") {
        v.estimator = VariogramEstimator::Cressie;
    } else if (args.estimator == "matheron") {
        v.estimator = VariogramEstimator::Matheron;
    } else {
        throw InvalidArgument("--estimator must be cressie or matheron, got '" + args.estimator + "'");
    }
    return v;
}

VariogramFitOptions fit_options(const TableKrigingArgs& args) {
    VariogramFitOptions f;
    if (args.weights == "cressie") {
        f.weighting = FitWeighting::Cressie;
    } else if (args.weights == "npairs") {
        f.weighting = FitWeighting::Npairs;
    } else if (args.weights == "unweighted") {
        f.weighting = FitWeighting::Unweighted;
    } else {
        throw InvalidArgument("--weights must be cressie, npairs or unweighted, got '" + args.weights + "'");
    }
    return f;
}

ExperimentalVariogram table_variogram(const TableKrigingArgs& args, const TableData& data) {
    const KrigingOptions ko = kriging_options(args);
    const VariogramOptions vo = variogram_options(args);
    return kriging::table_variogram(data, ko.trend, vo);
}

FitRequest parse_fit(const std::string& spec) {
    FitRequest r;
    if (spec == "sph") {
        r.p = 0.0;
    } else if (spec == "auto") {
        r.by_loo = true;
        r.grid = paper_exponent_grid();
    } else if (spec == "stable") {
        r.by_loo = true;
        r.grid = paper_exponent_grid();
        r.grid.erase(r.grid.begin());
    } else if (spec.rfind("stable:", 0) == 0) {
        const std::string num = spec.substr(7);
        char* end = nullptr;
        r.p = std::strtod(num.c_str(), &end);
        if (num.empty() || end != num.c_str() + num.size() || !(r.p > 0.0 && r.p <= 2.0)) {
            throw InvalidArgument("--fit stable:P needs 0 < P <= 2, got '" + spec + "'");
        }
    } else {
        throw InvalidArgument("--fit must be sph, stable, stable:P or auto, got '" + spec + "'");
    }
    return r;
}

FitOutcome run_fit(const FitRequest& request, const ExperimentalVariogram& ev, const TableData& data,
                   const TableKrigingArgs& args) {
    const VariogramFitOptions fo = fit_options(args);
    const KrigingOptions ko = kriging_options(args);
    return fit_table_variogram(request, ev, data, ko, fo);
}

VariogramModel parse_model(const std::string& spec, double nugget, double sill, double range) {
    if (spec == "sph") return VariogramModel::spherical(nugget, sill, range);
    if (spec.rfind("stable:", 0) == 0) {
        const std::string num = spec.substr(7);
        char* end = nullptr;
        const double p = std::strtod(num.c_str(), &end);
        if (num.empty() || end != num.c_str() + num.size()) {
            throw InvalidArgument("--model stable:P needs a number P, got '" + spec + "'");
        }
        return VariogramModel::stable(p, nugget, sill, range);
    }
    throw InvalidArgument("--model must be sph or stable:P, got '" + spec + "'");
}

json::TableSettings table_settings(const TableKrigingArgs& args) {
    return {args.trend, args.trend_fit, args.normalize, args.weights};
}

std::string describe_fit(const FitOutcome& f, const TableKrigingArgs& args) {
    std::ostringstream os;
    os.precision(10);
    os << "fit: " << f.fit.model.to_string() << "  (weights " << args.weights << ", objective " << f.fit.objective
       << (f.fit.converged ? ", converged" : ", NOT converged")
       << (f.fit.status == kriging::FitStatus::Degenerate ? ", degenerate" : "") << ")\n";
    if (f.selection) {
        os << "p chosen by leave-one-out:\n      p        loo_mse\n";
        for (std::size_t k = 0; k < f.selection->grid.size(); ++k) {
            os << "  " << (k == f.selection->best ? "*" : " ") << " " << f.selection->grid[k] << "  "
               << f.selection->loo_mse(static_cast<Eigen::Index>(k)) << "\n";
        }
    }
    return os.str();
}

}  // namespace mocapdb::cli
