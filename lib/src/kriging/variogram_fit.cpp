#include "mocapdb/kriging/variogram_fit.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>

#include <Eigen/Cholesky>

#include "mocapdb/core/error.hpp"

namespace mocapdb::kriging {

const char* to_string(FitWeighting weighting) {
    switch (weighting) {
        case FitWeighting::Cressie: return "cressie";
        case FitWeighting::CressieFixed: return "cressie-fixed-start";
        case FitWeighting::Npairs: return "npairs";
        case FitWeighting::Unweighted: return "unweighted";
    }
    return "unknown";
}

const char* to_string(FitStatus status) {
    switch (status) {
        case FitStatus::Ok: return "ok";
        case FitStatus::RangeAtBound: return "range at bound";
        case FitStatus::SillAtBound: return "sill at bound";
        case FitStatus::PureNugget: return "pure nugget";
        case FitStatus::Degenerate: return "degenerate";
    }
    return "unknown";
}

std::vector<double> paper_exponent_grid() {
    std::vector<double> g;
    for (int k = 0; k <= 10; ++k) g.push_back(0.2 * k);
    g.back() = 2.0;
    return g;
}

namespace {

struct Bins {
    Eigen::VectorXd h;  // abscissa
    Eigen::VectorXd y;  // gammabar
    Eigen::VectorXd n;  // pair counts
};

Bins usable_bins(const ExperimentalVariogram& ev, FitAbscissa abscissa) {
    std::vector<Eigen::Index> keep;
    for (Eigen::Index u = 0; u < ev.gamma.size(); ++u) {
        const double h = abscissa == FitAbscissa::MeanDistance ? ev.dist(u) : ev.center(u);
        if (ev.npairs[static_cast<std::size_t>(u)] > 0 && h > 0.0 && std::isfinite(ev.gamma(u))) keep.push_back(u);
    }
    Bins b;
    const auto m = static_cast<Eigen::Index>(keep.size());
    b.h.resize(m);
    b.y.resize(m);
    b.n.resize(m);
    for (Eigen::Index k = 0; k < m; ++k) {
        const Eigen::Index u = keep[static_cast<std::size_t>(k)];
        b.h(k) = abscissa == FitAbscissa::MeanDistance ? ev.dist(u) : ev.center(u);
        b.y(k) = ev.gamma(u);
        b.n(k) = static_cast<double>(ev.npairs[static_cast<std::size_t>(u)]);
    }
    return b;
}

// Shape value and its derivative with respect to log(range).
void shape_and_derivative(VariogramFamily family, double p, double h, double range, double& f, double& df_dtau) {
    const double x = h / range;
    if (family == VariogramFamily::Spherical) {
        if (x >= 1.0) {
            f = 1.0;
            df_dtau = 0.0;
        } else {
            f = x * (1.5 - 0.5 * x * x);
            df_dtau = -1.5 * x * (1.0 - x * x);
        }
        return;
    }
    const double t = p == 1.0 ? x : (p == 2.0 ? x * x : std::pow(x, p));
    const double e = std::exp(-t);
    f = -std::expm1(-t);
    df_dtau = -p * t * e;
}

struct Problem {
    Bins bins;
    VariogramFamily family;
    double p;
    FitWeighting weighting;
    Eigen::VectorXd fixed_w;  // for the fixed-weight modes
    double floor_value;
    bool fit_nugget;
    double min_nugget = 0.0;
    double max_total = 0.0;  // 0: none
    double tau_min, tau_max;

    // Projection of (theta0, theta1) onto the feasible set.
    Eigen::Vector2d project(double a, double b) const {
        a = fit_nugget ? std::max(a, min_nugget) : min_nugget;
        b = std::max(b, 0.0);
        if (max_total > 0.0) {
            a = std::min(a, max_total);
            b = std::min(b, max_total - a);
        }
        return {a, b};
    }

    // Residuals r (m) and Jacobian J (m by 3) at x = (theta0, theta1, tau).
    double evaluate(const Eigen::Vector3d& x, Eigen::VectorXd& r, Eigen::MatrixXd* jac) const {
        const Eigen::Index m = bins.h.size();
        r.resize(m);
        if (jac) jac->resize(m, 3);
        const double range = std::exp(x(2));
        for (Eigen::Index u = 0; u < m; ++u) {
            double f = 0.0, df = 0.0;
            shape_and_derivative(family, p, bins.h(u), range, f, df);
            const double g = x(0) + x(1) * f;
            const Eigen::Vector3d dg(1.0, f, x(1) * df);
            if (weighting == FitWeighting::Cressie) {
                const double gf = std::max(g, floor_value);
                const double sn = std::sqrt(bins.n(u));
                r(u) = sn * (bins.y(u) / gf - 1.0);
                if (jac) {
                    const double c = g > floor_value ? -sn * bins.y(u) / (gf * gf) : 0.0;
                    jac->row(u) = c * dg.transpose();
                }
            } else {
                const double sw = std::sqrt(fixed_w(u));
                r(u) = sw * (bins.y(u) - g);
                if (jac) jac->row(u) = -sw * dg.transpose();
            }
        }
        return r.squaredNorm();
    }

    // Exact non-negative 2-variable weighted least squares for (theta0, theta1) at a fixed range.
    Eigen::Vector2d inner(double range, const Eigen::VectorXd& w) const {
        const Eigen::Index m = bins.h.size();
        Eigen::VectorXd f(m);
        for (Eigen::Index u = 0; u < m; ++u) {
            double df = 0.0;
            shape_and_derivative(family, p, bins.h(u), range, f(u), df);
        }
        const double sw = w.sum();
        const double swf = w.dot(f);
        const double swff = (w.array() * f.array().square()).sum();
        const double swy = w.dot(bins.y);
        const double swfy = (w.array() * f.array() * bins.y.array()).sum();
        auto cost = [&](double a, double b) {
            return (w.array() * (bins.y.array() - a - b * f.array()).square()).sum();
        };
        std::vector<Eigen::Vector2d> cands;
        cands.push_back(project(0.0, 0.0));
        if (swff > 0.0) cands.push_back(project(min_nugget, (swfy - min_nugget * swf) / swff));
        if (fit_nugget) {
            if (sw > 0.0) cands.push_back(project(swy / sw, 0.0));
            const double det = sw * swff - swf * swf;
            if (std::abs(det) > 1e-14 * sw * swff) {
                const double a = (swff * swy - swf * swfy) / det;
                const double b = (sw * swfy - swf * swy) / det;
                if (a >= min_nugget && b >= 0.0) cands.push_back(project(a, b));
            }
        }
        if (max_total > 0.0) {
            // On the cap a + b = max_total: one-variable least squares in a.
            const double den = sw - 2.0 * swf + swff;  // sum w (1 - f)^2
            if (den > 0.0) {
                const double a = (swy - swfy - max_total * (swf - swff)) / den;
                cands.push_back(project(a, max_total - std::max(a, min_nugget)));
            }
            cands.push_back(project(min_nugget, max_total));
        }
        Eigen::Vector2d best = cands.front();
        double bc = cost(best(0), best(1));
        for (const auto& c : cands) {
            const double v = cost(c(0), c(1));
            if (v < bc) {
                bc = v;
                best = c;
            }
        }
        return best;
    }

    Eigen::Vector3d clip(Eigen::Vector3d x) const {
        const Eigen::Vector2d ab = project(x(0), x(1));
        x(0) = ab(0);
        x(1) = ab(1);
        x(2) = std::clamp(x(2), tau_min, tau_max);
        return x;
    }

    // Bound-constrained Levenberg-Marquardt.
    double minimize(Eigen::Vector3d& x, int max_iterations, int& iterations, bool& converged) const {
        x = clip(x);
        Eigen::VectorXd r;
        Eigen::MatrixXd jac;
        double f = evaluate(x, r, &jac);
        double lambda = 1e-3;
        converged = false;
        iterations = 0;
        for (int it = 0; it < max_iterations; ++it) {
            iterations = it + 1;
            const Eigen::Vector3d g = jac.transpose() * r;
            std::array<bool, 3> free{};
            const double tiny = 1e-12;
            for (int j = 0; j < 3; ++j) {
                bool at_lower = false, at_upper = false;
                const bool capped = max_total > 0.0 && x(0) + x(1) >= max_total * (1.0 - 1e-12);
                if (j == 0) {
                    at_lower = !fit_nugget || x(0) <= min_nugget;
                    at_upper = capped;
                }
                if (j == 1) {
                    at_lower = x(1) <= 0.0;
                    at_upper = capped;
                }
                if (j == 2) {
                    at_lower = x(2) <= tau_min + tiny;
                    at_upper = x(2) >= tau_max - tiny;
                }
                free[static_cast<std::size_t>(j)] =
                    !((j == 0 && !fit_nugget) || (at_lower && g(j) > 0.0) || (at_upper && g(j) < 0.0));
            }
            const Eigen::Matrix3d a = jac.transpose() * jac;
            bool accepted = false;
            double f_new = f;
            Eigen::Vector3d x_new = x;
            for (int tries = 0; tries < 40; ++tries) {
                Eigen::Matrix3d m = Eigen::Matrix3d::Identity();
                Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
                for (int i = 0; i < 3; ++i) {
                    if (!free[static_cast<std::size_t>(i)]) continue;
                    rhs(i) = -g(i);
                    for (int j = 0; j < 3; ++j) {
                        if (free[static_cast<std::size_t>(j)]) m(i, j) = a(i, j);
                    }
                    m(i, i) = a(i, i) * (1.0 + lambda) + 1e-300;
                }
                const Eigen::Vector3d step = m.ldlt().solve(rhs);
                x_new = clip(x + step);
                Eigen::VectorXd r_new;
                f_new = evaluate(x_new, r_new, nullptr);
                if (std::isfinite(f_new) && f_new < f) {
                    accepted = true;
                    break;
                }
                lambda *= 4.0;
                if (lambda > 1e16) break;
            }
            if (!accepted) {
                converged = true;  // no descent possible from here: a (constrained) stationary point
                break;
            }
            const double rel = (f - f_new) / std::max(f, 1e-300);
            const double dx = (x_new - x).cwiseAbs().maxCoeff();
            x = x_new;
            f = evaluate(x, r, &jac);
            lambda = std::max(lambda / 3.0, 1e-12);
            if (rel < 1e-14 || dx < 1e-13 * (1.0 + x.cwiseAbs().maxCoeff())) {
                converged = true;
                break;
            }
        }
        return f;
    }
};

}  // namespace

double fit_objective(const ExperimentalVariogram& ev, const VariogramModel& model, const VariogramFitOptions& options) {
    model.validate();
    const Bins b = usable_bins(ev, options.abscissa);
    const double ymax = b.y.size() > 0 ? b.y.maxCoeff() : 0.0;
    const double floor_value = std::max(options.gamma_floor * ymax, std::numeric_limits<double>::min());
    double r = 0.0;
    for (Eigen::Index u = 0; u < b.h.size(); ++u) {
        const double g = model(b.h(u));
        double w = 1.0;
        switch (options.weighting) {
            case FitWeighting::Cressie: w = b.n(u) / std::pow(std::max(g, floor_value), 2); break;
            case FitWeighting::CressieFixed:
                if (!options.start) throw InvalidArgument("fit_objective: CressieFixed weighting needs options.start");
                w = b.n(u) / std::pow(std::max((*options.start)(b.h(u)), floor_value), 2);
                break;
            case FitWeighting::Npairs: w = b.n(u); break;
            case FitWeighting::Unweighted: w = 1.0; break;
        }
        r += w * (b.y(u) - g) * (b.y(u) - g);
    }
    return r;
}

VariogramFit fit_variogram(const ExperimentalVariogram& ev, VariogramFamily family, double exponent,
                           const VariogramFitOptions& options) {
    if (family == VariogramFamily::Stable && !(exponent > 0.0 && exponent <= 2.0)) {
        throw InvalidArgument("fit_variogram: stable exponent p must satisfy 0 < p <= 2, got " +
                              std::to_string(exponent));
    }
    if (!(options.gamma_floor > 0.0 && options.gamma_floor < 1.0)) {
        throw InvalidArgument("fit_variogram: gamma_floor must be in (0, 1)");
    }
    if (!(options.range_min_factor > 0.0 && options.range_max_factor > options.range_min_factor)) {
        throw InvalidArgument("fit_variogram: need 0 < range_min_factor < range_max_factor");
    }
    if (options.max_iterations < 1) throw InvalidArgument("fit_variogram: max_iterations must be >= 1");
    if (!(options.min_nugget >= 0.0) || !std::isfinite(options.min_nugget) || !(options.max_total_sill >= 0.0) ||
        !std::isfinite(options.max_total_sill) ||
        (options.max_total_sill > 0.0 && options.min_nugget >= options.max_total_sill)) {
        throw InvalidArgument(
            "fit_variogram: need finite min_nugget >= 0, max_total_sill >= 0 and, with a cap, "
            "min_nugget < max_total_sill");
    }
    if (options.weighting == FitWeighting::CressieFixed && !options.start) {
        throw InvalidArgument(
            "fit_variogram: CressieFixed weighting needs options.start (the model the weights come from)");
    }
    if (options.start) options.start->validate();

    Problem pr;
    pr.bins = usable_bins(ev, options.abscissa);
    pr.family = family;
    pr.p = family == VariogramFamily::Stable ? exponent : 1.0;
    pr.weighting = options.weighting;
    pr.fit_nugget = options.fit_nugget;
    pr.min_nugget = options.min_nugget;
    pr.max_total = options.max_total_sill;
    VariogramFit out;
    out.bins_used = static_cast<int>(pr.bins.h.size());
    const double ymax = pr.bins.y.size() > 0 ? pr.bins.y.maxCoeff() : 0.0;
    const double href = pr.bins.h.size() > 0 ? pr.bins.h.maxCoeff() : 0.0;
    auto make_model = [&](double nug, double sill, double range) {
        VariogramModel m;
        m.family = family;
        m.exponent = pr.p;
        m.nugget = nug;
        m.sill = sill;
        m.range = range;
        return m;
    };
    if (!(ymax > 0.0) || !(href > 0.0)) {
        out.status = FitStatus::Degenerate;
        out.model = make_model(0.0, 0.0, href > 0.0 ? href : 1.0);
        out.converged = true;
        return out;
    }
    pr.floor_value = options.gamma_floor * ymax;
    pr.tau_min = std::log(options.range_min_factor * href);
    pr.tau_max = std::log(options.range_max_factor * href);
    const Eigen::Index m = pr.bins.h.size();
    pr.fixed_w = Eigen::VectorXd::Ones(m);
    for (Eigen::Index u = 0; u < m; ++u) {
        switch (options.weighting) {
            case FitWeighting::CressieFixed:
                pr.fixed_w(u) = pr.bins.n(u) / std::pow(std::max((*options.start)(pr.bins.h(u)), pr.floor_value), 2);
                break;
            case FitWeighting::Npairs: pr.fixed_w(u) = pr.bins.n(u); break;
            default: break;
        }
    }
    // Weights for the scan: the fixed ones, or Cressie's evaluated at the data.
    Eigen::VectorXd scan_w = pr.fixed_w;
    if (options.weighting == FitWeighting::Cressie) {
        for (Eigen::Index u = 0; u < m; ++u)
            scan_w(u) = pr.bins.n(u) / std::pow(std::max(pr.bins.y(u), pr.floor_value), 2);
    }
    struct Start {
        double f;
        Eigen::Vector3d x;
    };
    std::vector<Start> starts;
    const int nscan = 60;
    Eigen::VectorXd r;
    for (int k = 0; k < nscan; ++k) {
        const double tau = pr.tau_min + (pr.tau_max - pr.tau_min) * k / (nscan - 1);
        Eigen::Vector2d ab = pr.inner(std::exp(tau), scan_w);
        if (options.weighting == FitWeighting::Cressie) {
            // Two reweighting passes bring the start closer to the true Cressie objective.
            for (int pass = 0; pass < 2; ++pass) {
                Eigen::VectorXd w(m);
                for (Eigen::Index u = 0; u < m; ++u) {
                    double f = 0.0, df = 0.0;
                    shape_and_derivative(family, pr.p, pr.bins.h(u), std::exp(tau), f, df);
                    w(u) = pr.bins.n(u) / std::pow(std::max(ab(0) + ab(1) * f, pr.floor_value), 2);
                }
                ab = pr.inner(std::exp(tau), w);
            }
        }
        const Eigen::Vector3d x(ab(0), ab(1), tau);
        starts.push_back({pr.evaluate(x, r, nullptr), x});
    }
    std::sort(starts.begin(), starts.end(), [](const Start& a, const Start& b) { return a.f < b.f; });
    starts.resize(std::min<std::size_t>(starts.size(), 4));
    if (options.start) {
        starts.push_back({0.0, Eigen::Vector3d(options.fit_nugget ? options.start->nugget : 0.0, options.start->sill,
                                               std::log(options.start->range))});
    }
    double best_f = std::numeric_limits<double>::infinity();
    for (auto& s : starts) {
        Eigen::Vector3d x = s.x;
        int its = 0;
        bool conv = false;
        const double f = pr.minimize(x, options.max_iterations, its, conv);
        if (f < best_f) {
            best_f = f;
            out.model = make_model(x(0), x(1), std::exp(x(2)));
            out.iterations = its;
            out.converged = conv;
        }
    }
    out.objective = best_f;
    const double total = out.model.total_sill();
    if (!(total > 0.0)) {
        out.status = FitStatus::Degenerate;
    } else if (out.model.sill <= 1e-6 * total) {
        out.status = FitStatus::PureNugget;
    } else if (pr.max_total > 0.0 && total >= pr.max_total * (1.0 - 1e-6)) {
        out.status = FitStatus::SillAtBound;
    } else if (std::log(out.model.range) >= pr.tau_max - 1e-6) {
        out.status = FitStatus::RangeAtBound;
    }
    return out;
}

ExponentSelection select_exponent(const ExperimentalVariogram& ev, const Eigen::Ref<const Eigen::MatrixXd>& coords,
                                  const Eigen::Ref<const Eigen::MatrixXd>& values,
                                  const KrigingOptions& kriging_options, const VariogramFitOptions& fit_options,
                                  const std::vector<double>& grid) {
    if (grid.empty()) throw InvalidArgument("select_exponent: the grid of p must not be empty");
    for (double p : grid) {
        if (!(p >= 0.0 && p <= 2.0)) throw InvalidArgument("select_exponent: every p must satisfy 0 <= p <= 2");
    }
    if (values.rows() != coords.rows() || values.cols() < 1) {
        throw InvalidArgument("select_exponent: values must be N by D with N = rows of coords (" +
                              std::to_string(coords.rows()) + ") and D >= 1");
    }
    ExponentSelection sel;
    sel.grid = grid;
    sel.loo_mse.resize(static_cast<Eigen::Index>(grid.size()));
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < grid.size(); ++k) {
        const double p = grid[k];
        const VariogramFamily fam = p == 0.0 ? VariogramFamily::Spherical : VariogramFamily::Stable;
        VariogramFit fit = fit_variogram(ev, fam, p == 0.0 ? 1.0 : p, fit_options);
        double mse = std::numeric_limits<double>::infinity();
        if (fit.status != FitStatus::Degenerate && fit.model.total_sill() > 0.0) {
            const Kriging kr = Kriging::build(coords, fit.model, kriging_options);
            mse = kr.leave_one_out(values).mse;
            if (!std::isfinite(mse)) mse = std::numeric_limits<double>::infinity();
        }
        sel.loo_mse(static_cast<Eigen::Index>(k)) = mse;
        sel.fits.push_back(fit);
        if (mse < best) {
            best = mse;
            sel.best = k;
        }
    }
    return sel;
}

}  // namespace mocapdb::kriging
