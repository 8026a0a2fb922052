#include "mocapdb/synthesis/kernel_fit.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <string>

#include <Eigen/QR>

#include "mocapdb/compression/set_model.hpp"
#include "mocapdb/core/error.hpp"
#include "mocapdb/dataset/aligned_set.hpp"
#include "mocapdb/dataset/motion_set.hpp"
#include "mocapdb/dataset/sample_twins.hpp"
#include "mocapdb/kriging/variogram.hpp"
#include "mocapdb/kriging/kriging.hpp"
#include "mocapdb/kriging/trend.hpp"
#include "mocapdb/kriging/variogram_fit.hpp"
#include "mocapdb/synthesis/synthesis_model.hpp"

namespace mocapdb::synthesis {
namespace {

// The digest of kernel_key (header comment): a bijection of h for every word x, so two inputs that
// differ in one word always give different digests.
struct Digest {
    std::uint64_t h = 0xcbf29ce484222325ULL;
    void word(std::uint64_t x) {
        h = (h ^ x) * 0x100000001b3ULL;
        h ^= h >> 29;
    }
    void number(double v) {
        std::uint64_t bits = 0;
        std::memcpy(&bits, &v, sizeof bits);
        word(bits);
    }
    // Row after row (C order of the file's (rows, cols) array).
    void rows(const MatX& m) {
        for (Eigen::Index i = 0; i < m.rows(); ++i)
            for (Eigen::Index j = 0; j < m.cols(); ++j) number(m(i, j));
    }
};

std::string number_text(double v) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return buf;
}

std::string model_text(const kriging::VariogramModel& m) {
    return std::string(kriging::to_string(m.family)) + "," + number_text(m.exponent) + "," + number_text(m.nugget) +
           "," + number_text(m.sill) + "," + number_text(m.range);
}

// Values with the same per-sample leave-one-out residual norms, in at most N columns: V = C Q^T with Q's
// columns orthonormal (thin QR of V^T), so (M V) row i has the norm of (M C) row i for any N x N matrix M,
// and leave-one-out kriging predicts every column by such a row mixing. For S = R1 R2 >> N values per
// sample this turns the grid's N^2 S products into N^3 (one QR, N^2 S, up front).
MatX same_residual_norms(const Eigen::Ref<const MatX>& values) {
    if (values.cols() <= values.rows()) return values;
    const Eigen::HouseholderQR<MatX> qr(values.transpose());
    const MatX r = qr.matrixQR().topRows(values.rows()).triangularView<Eigen::Upper>();
    return r.transpose();
}

// m rows of a evenly spread in row order (rows round(i (N - 1) / (m - 1)), m >= 2): the subset of data the
// variogram of a big set is fitted on.
MatX spread_rows(const Eigen::Ref<const MatX>& a, Eigen::Index m) {
    const double step = static_cast<double>(a.rows() - 1) / static_cast<double>(m - 1);
    MatX out(m, a.cols());
    for (Eigen::Index i = 0; i < m; ++i)
        out.row(i) = a.row(static_cast<Eigen::Index>(std::lround(step * static_cast<double>(i))));
    return out;
}

// The core slices (rows of core_slice_values) as values whose distances are the posture metric of the
// choice (predictor_choice.hpp posture_values): sample i's weighted poses are U_dof S_i U_time^T with
// orthonormal U_time, so with L = U_dof without the root-path rows and L = Q R, the norm of their posture
// part is |R S_i|_F. At most R1 R2 values per sample.
MatX posture_slice_values(const compression::SetModel& model, const Eigen::Ref<const MatX>& slices) {
    const tensor::Ranks& r = model.tucker.ranks;
    MatX l = model.tucker.U[0];
    for (const Eigen::Index k : kRootPathDofs)
        if (k < l.rows()) l.row(k).setZero();
    const Eigen::HouseholderQR<MatX> qr(l);
    const Eigen::Index m = std::min(l.rows(), r[0]);
    const MatX rr = qr.matrixQR().topRows(m).triangularView<Eigen::Upper>();
    MatX out(slices.rows(), m * r[1]);
    for (Eigen::Index i = 0; i < slices.rows(); ++i) {
        const VecX row = slices.row(i).transpose();
        const MatX t = rr * Eigen::Map<const MatX>(row.data(), r[0], r[1]);
        out.row(i) = Eigen::Map<const VecX>(t.data(), t.size()).transpose();
    }
    return out;
}

}  // namespace

std::string kernel_options_text(const SynthesisOptions& o) {
    std::string s = "coefficient-kernel-2";
    s += ";exponent=" + (o.exponent ? number_text(*o.exponent) : std::string("loo"));
    s += ";scaling=";
    if (o.scaling) {
        for (Eigen::Index k = 0; k < o.scaling->offset.size(); ++k) s += number_text(o.scaling->offset(k)) + ",";
        s += "/";
        for (Eigen::Index k = 0; k < o.scaling->scale.size(); ++k) s += number_text(o.scaling->scale(k)) + ",";
        if (o.scaling->period.size() != 0) {
            s += "/";
            for (Eigen::Index k = 0; k < o.scaling->period.size(); ++k) s += number_text(o.scaling->period(k)) + ",";
        }
    } else {
        s += "data";
    }
    s += ";variogram=" + std::to_string(o.variogram.bins) + "," + number_text(o.variogram.cutoff) + "," +
         std::to_string(static_cast<int>(o.variogram.estimator));
    const kriging::VariogramFitOptions& f = o.fit;
    s += ";fit=" + std::to_string(static_cast<int>(f.weighting)) + "," + std::to_string(static_cast<int>(f.abscissa)) +
         "," + (f.start ? model_text(*f.start) : std::string("none")) + "," + (f.fit_nugget ? "1" : "0") + "," +
         number_text(f.gamma_floor) + "," + number_text(f.range_min_factor) + "," + number_text(f.range_max_factor) +
         "," + std::to_string(f.max_iterations);
    const kriging::KrigingOptions& k = o.kriging;
    s += "," + number_text(f.min_nugget) + "," + number_text(f.max_total_sill);
    s += ";kriging=" + std::to_string(static_cast<int>(k.trend)) + "," + std::to_string(static_cast<int>(k.trend_fit)) +
         "," + std::to_string(static_cast<int>(k.duplicates)) + "," + number_text(k.duplicate_tolerance) + "," +
         number_text(k.min_rcond) + "," + number_text(k.max_jitter) + "," + number_text(k.trend_rank_tolerance) + "," +
         (k.filter_nugget ? "1" : "0") + "," + std::to_string(static_cast<int>(k.reliability));
    s += ";grid=";
    for (const double p : o.exponent_grid) s += number_text(p) + ",";
    s += ";bounds=" + number_text(o.max_range_factor) + "," + number_text(o.max_sill_factor) + "," +
         number_text(o.gaussian_nugget_fraction);
    if (o.shape_selection == SynthesisOptions::ShapeSelection::LeaveOneOut) {
        s += ";shape=loo,";
        for (const double fraction : o.range_fractions) s += number_text(fraction) + ",";
        s += "/";
        for (const double a : o.nugget_shares) s += number_text(a) + ",";
    }
    return s;
}

std::uint64_t kernel_key(const compression::SetModel& model, const MotionSet& set, const SynthesisOptions& options) {
    Digest d;
    for (const char c : kernel_options_text(options)) d.word(static_cast<unsigned char>(c));
    const tensor::TuckerModel& t = model.tucker;
    d.word(static_cast<std::uint64_t>(set.parameters.rows()));
    d.word(static_cast<std::uint64_t>(set.parameters.cols()));
    for (const Eigen::Index r : t.ranks) d.word(static_cast<std::uint64_t>(r));
    d.rows(set.parameters);
    d.rows(t.U[2]);
    const double* core = t.core.data();
    for (Eigen::Index i = 0; i < t.core.size(); ++i) d.number(core[i]);
    // Periodic parameters change the control-space distances (sets without them keep their keys).
    for (Eigen::Index k = 0; k < set.parameter_periods.size(); ++k) d.number(set.parameter_periods(k));
    // So do categorical ones (level counts; sets without them keep their keys).
    for (const int levels : parameter_level_counts(set)) d.word(static_cast<std::uint64_t>(levels));
    // A subset fit depends on the subset's size (smaller sets, fitted on all samples, keep their keys).
    if (static_cast<std::size_t>(set.parameters.rows()) > options.max_fit_samples) d.word(options.max_fit_samples);
    return d.h == 0 ? 1 : d.h;
}

MatX core_slice_values(const compression::SetModel& model) {
    const tensor::Ranks& r = model.tucker.ranks;
    const Eigen::Map<const MatX> c3(model.tucker.core.data(), r[0] * r[1], r[2]);
    return model.tucker.U[2] * c3.transpose();
}

std::string fit_status_warning(const KernelFit& fit) {
    switch (fit.status) {
        case kriging::FitStatus::Ok: return "";
        case kriging::FitStatus::RangeAtBound:
            return "variogram range at its bound (the largest lag): the residual variogram has not levelled off "
                   "within the samples' spread";
        case kriging::FitStatus::SillAtBound:
            return "variogram sill at its bound (twice the residual variance): the residual variogram still rises "
                   "at the largest lag";
        case kriging::FitStatus::PureNugget:
            return "pure-nugget variogram: the trend residuals show no spatial correlation (kriging reduces to "
                   "the linear trend)";
        case kriging::FitStatus::Degenerate:
            return "degenerate variogram: the samples do not vary about their trend (placeholder kernel)";
    }
    return "";
}

KernelFit fit_coefficient_kernel(const Eigen::Ref<const MatX>& xc, const Eigen::Ref<const MatX>& sample_values,
                                 const SynthesisOptions& options, const char* where) {
    if (options.exponent_grid.empty()) throw InvalidArgument(std::string(where) + ": the exponent grid is empty");
    for (const double p : options.exponent_grid)
        if (!(p >= 0.0 && p <= 2.0)) throw InvalidArgument(std::string(where) + ": grid exponents must be in [0, 2]");
    if (!(options.max_range_factor > 0.0) || !(options.max_sill_factor > 0.0) ||
        !(options.gaussian_nugget_fraction >= 0.0 && options.gaussian_nugget_fraction < 1.0))
        throw InvalidArgument(std::string(where) +
                              ": need max_range_factor > 0, max_sill_factor > 0 and "
                              "gaussian_nugget_fraction in [0, 1)");
    const bool shape_search = options.shape_selection == SynthesisOptions::ShapeSelection::LeaveOneOut;
    if (shape_search) {
        if (options.range_fractions.empty() || options.nugget_shares.empty())
            throw InvalidArgument(std::string(where) + ": the shape search needs range fractions and nugget shares");
        for (const double f : options.range_fractions)
            if (!(f > 0.0 && f <= 1.0))
                throw InvalidArgument(std::string(where) + ": range fractions must be in (0, 1]");
        for (const double a : options.nugget_shares)
            if (!(a >= 0.0 && a < 1.0)) throw InvalidArgument(std::string(where) + ": nugget shares must be in [0, 1)");
    }
    if (options.exponent && !(*options.exponent >= 0.0 && *options.exponent <= 2.0))
        throw InvalidArgument(std::string(where) + ": exponent p must be in [0, 2]");
    if (options.max_fit_samples < 2) throw InvalidArgument(std::string(where) + ": max_fit_samples must be >= 2");
    if (static_cast<std::size_t>(xc.rows()) > options.max_fit_samples) {
        // Subset of data: evenly spread rows (sample order follows the clips, so every clip is represented).
        const auto m = static_cast<Eigen::Index>(options.max_fit_samples);
        return fit_coefficient_kernel(spread_rows(xc, m), spread_rows(sample_values, m), options, where);
    }
    // Residuals of the trend the kriging will remove (gstat: variogram(z ~ x + y)), so that a variogram
    // rising as h^2 because of the drift is not taken for spatial correlation.
    const kriging::TrendBasis basis =
        kriging::TrendBasis::build(xc, options.kriging.trend, options.kriging.trend_rank_tolerance);
    const MatX residuals = kriging::fit_trend_ols(basis, sample_values).residuals;
    const Eigen::Index n = xc.rows();
    const double dof = static_cast<double>(std::max<Eigen::Index>(n - basis.size(), 1));
    const double residual_variance = residuals.squaredNorm() / dof;

    const MatX h = kriging::pairwise_distances(xc);
    const MatX d = kriging::pairwise_distances(residuals);
    const kriging::ExperimentalVariogram ev = kriging::experimental_variogram(h, d, options.variogram);
    const double h_half = std::max(0.5 * h.maxCoeff(), 1e-12);
    KernelFit out;
    out.residual_variance = residual_variance;
    out.fit_samples = static_cast<std::size_t>(n);
    kriging::VariogramModel model;
    bool degenerate = !(d.maxCoeff() > 0.0) || !(residual_variance > 0.0);
    kriging::FitStatus status = kriging::FitStatus::Ok;
    kriging::VariogramFitOptions fo = options.fit;
    fo.range_max_factor = std::min(fo.range_max_factor, options.max_range_factor);
    if (!(fo.range_min_factor < fo.range_max_factor)) fo.range_min_factor = 1e-3 * fo.range_max_factor;
    fo.max_total_sill = options.max_sill_factor * residual_variance;
    const auto fit_one = [&](double p) {
        kriging::VariogramFitOptions f = fo;
        if (p == 2.0) f.min_nugget = std::max(f.min_nugget, options.gaussian_nugget_fraction * residual_variance);
        return kriging::fit_variogram(ev,
                                      p == 0.0 ? kriging::VariogramFamily::Spherical : kriging::VariogramFamily::Stable,
                                      p == 0.0 ? 1.0 : p, f);
    };
    // The range bound of the fit: the largest lag (mean distance of the last non-empty bin) times the factor.
    double h_ref = 0.0;
    for (Eigen::Index u = 0; u < ev.dist.size(); ++u)
        if (ev.npairs[static_cast<std::size_t>(u)] > 0) h_ref = std::max(h_ref, ev.dist(u));
    const double range_bound = fo.range_max_factor * h_ref;

    // Candidates are scored by the closed-form leave-one-out MSE of the values, reduced to at most N columns
    // with the same per-sample residual norms. The prediction weights, and hence the score, depend on the
    // shape only: p, range and the nugget's share of nugget + sill. (The mean over samples of the residual
    // norm, closer to a mean joint error, chose kernels that predicted slightly worse in mocapdb eval's
    // leave-one-out on 3 of its 5 CMU sets.)
    const MatX compact = same_residual_norms(sample_values);
    const double scale = static_cast<double>(compact.cols()) / static_cast<double>(sample_values.cols());
    const auto loo_error = [&](const kriging::VariogramModel& m) {
        if (!(m.total_sill() > 0.0)) return std::numeric_limits<double>::infinity();
        const double e = kriging::Kriging::build(xc, m, options.kriging).leave_one_out(compact).mse * scale;
        return std::isfinite(e) ? e : std::numeric_limits<double>::infinity();
    };
    const std::vector<double> exponents =
        options.exponent ? std::vector<double>{*options.exponent} : options.exponent_grid;
    // Per exponent: the smallest error of the candidates tried with it.
    Eigen::VectorXd mse =
        Eigen::VectorXd::Constant(static_cast<Eigen::Index>(exponents.size()), std::numeric_limits<double>::infinity());
    double best = std::numeric_limits<double>::infinity();
    std::size_t best_k = 0;
    bool grid_chosen = false;  // the best candidate is a grid shape (not a least-squares fit)
    // Candidates: the exponents' fits, the shape grid, the exponents again at the grid's best (at most).
    const std::uint64_t candidates =
        2 * exponents.size() + (shape_search ? options.range_fractions.size() * options.nugget_shares.size() : 0);
    std::uint64_t scored = 0;
    const auto consider = [&](const kriging::VariogramModel& m, kriging::FitStatus s, std::size_t k) {
        const double e = loo_error(m);
        if (options.fit_progress) options.fit_progress({++scored, candidates, "kernel"});
        double& slot = mse(static_cast<Eigen::Index>(k));
        slot = std::min(slot, e);
        if (e < best) {
            best = e;
            model = m;
            status = s;
            best_k = k;
            return true;
        }
        return false;
    };
    // A grid shape's model: total sill tied to the residual variance (the bound's half), nugget share a.
    const auto grid_model = [&](double p, double fraction, double share) {
        if (p == 2.0) share = std::max(share, options.gaussian_nugget_fraction);
        const double total = std::min(residual_variance, 0.5 * options.max_sill_factor * residual_variance);
        return kriging::VariogramModel::from_paper_p(p, share * total, (1.0 - share) * total, fraction * range_bound);
    };
    const auto grid_status = [&](const kriging::VariogramModel& m) {
        return m.range >= range_bound * (1.0 - 1e-6) ? kriging::FitStatus::RangeAtBound : kriging::FitStatus::Ok;
    };
    if (!degenerate) {
        // 1. The least-squares fit of every candidate exponent (the paper's choice of p by leave-one-out).
        for (std::size_t k = 0; k < exponents.size(); ++k) {
            const kriging::VariogramFit fit = fit_one(exponents[k]);
            if (fit.status == kriging::FitStatus::Degenerate || !(fit.model.total_sill() > 0.0)) continue;
            consider(fit.model, fit.status, k);
        }
        // 2. A fitted variogram can miss the shape that predicts best: with few, noisy bins the weighted fit
        //    may take the spatial correlation for noise (a pure nugget: kriging collapses to the trend) or
        //    put the range beyond the sample spacing. At the best exponent, try the grid of ranges and
        //    nugget shares; 3. at the best grid shape, the other exponents again. Bounded: at most
        //    |grid| + |ranges| |shares| + |grid| kriging systems, O(N^3) each.
        if (shape_search && range_bound > 0.0 && std::isfinite(best)) {
            const std::size_t k_fit = best_k;
            double best_fraction = 0.0, best_share = 0.0;
            bool grid_won = false;
            for (const double fraction : options.range_fractions)
                for (const double share : options.nugget_shares) {
                    const kriging::VariogramModel m = grid_model(exponents[k_fit], fraction, share);
                    if (consider(m, grid_status(m), k_fit)) {
                        grid_chosen = true;
                        best_fraction = fraction;
                        best_share = share;
                        grid_won = true;
                    }
                }
            if (grid_won)
                for (std::size_t k = 0; k < exponents.size(); ++k) {
                    if (k == k_fit) continue;
                    const kriging::VariogramModel m = grid_model(exponents[k], best_fraction, best_share);
                    if (consider(m, grid_status(m), k)) grid_chosen = true;
                }
        }
        degenerate = !std::isfinite(best);
        if (!options.exponent) out.exponent_loo_mse = mse;
        if (options.fit_progress) options.fit_progress({candidates, candidates, "kernel"});
    }
    if (degenerate || !(model.total_sill() > 0.0)) {
        // Samples without variation about the trend: any valid kernel gives the same (trend-only) prediction.
        model = kriging::VariogramModel::from_paper_p(options.exponent.value_or(1.0), 0.0, 1.0, h_half);
        status = kriging::FitStatus::Degenerate;
    } else {
        const kriging::LooResult loo = kriging::Kriging::build(xc, model, options.kriging).leave_one_out(sample_values);
        double z2 = loo.zscore.squaredNorm() / static_cast<double>(loo.zscore.rows());
        // A grid shape's sill is only a placeholder (the weights and rho do not depend on its scale): scale
        // nugget and sill so that the prediction variance is calibrated (mean z^2 = 1), within the bound.
        if (grid_chosen && std::isfinite(z2) && z2 > 0.0) {
            const double factor = std::min(z2, fo.max_total_sill / model.total_sill());
            model.nugget *= factor;
            model.sill *= factor;
            z2 /= factor;
            if (model.total_sill() >= fo.max_total_sill * (1.0 - 1e-6)) status = kriging::FitStatus::SillAtBound;
        }
        out.loo_mean_z2 = z2;
    }
    out.variogram = model;
    out.status = status;
    return out;
}

kriging::FitStatus assess_coefficient_kernel(const Eigen::Ref<const MatX>& xc,
                                             const Eigen::Ref<const MatX>& sample_values,
                                             const kriging::VariogramModel& variogram,
                                             const SynthesisOptions& options) {
    // Sets synthesized by local kriging: on the subset the variogram was fitted on (no N x N distances).
    if (static_cast<std::size_t>(xc.rows()) > options.max_exact_samples &&
        static_cast<std::size_t>(xc.rows()) > options.max_fit_samples && options.max_fit_samples >= 2) {
        const auto m = static_cast<Eigen::Index>(options.max_fit_samples);
        return assess_coefficient_kernel(spread_rows(xc, m), spread_rows(sample_values, m), variogram, options);
    }
    const kriging::TrendBasis basis =
        kriging::TrendBasis::build(xc, options.kriging.trend, options.kriging.trend_rank_tolerance);
    const MatX residuals = kriging::fit_trend_ols(basis, sample_values).residuals;
    const double dof = static_cast<double>(std::max<Eigen::Index>(xc.rows() - basis.size(), 1));
    const double residual_variance = residuals.squaredNorm() / dof;
    const double total = variogram.total_sill();
    if (!(residual_variance > 0.0) || !(total > 0.0)) return kriging::FitStatus::Degenerate;
    if (variogram.sill <= 1e-6 * total) return kriging::FitStatus::PureNugget;
    if (total >= options.max_sill_factor * residual_variance * (1.0 - 1e-6)) return kriging::FitStatus::SillAtBound;
    // The largest lag: the mean distance of the last non-empty bin (the bins depend on the distances only).
    const MatX h = kriging::pairwise_distances(xc);
    const kriging::ExperimentalVariogram ev = kriging::experimental_variogram(h, h, options.variogram);
    double h_ref = 0.0;
    for (Eigen::Index u = 0; u < ev.dist.size(); ++u)
        if (ev.npairs[static_cast<std::size_t>(u)] > 0) h_ref = std::max(h_ref, ev.dist(u));
    const double bound = std::min(options.fit.range_max_factor, options.max_range_factor) * h_ref;
    if (h_ref > 0.0 && variogram.range >= bound * (1.0 - 1e-6)) return kriging::FitStatus::RangeAtBound;
    return kriging::FitStatus::Ok;
}

KernelFit fit_kernel(const compression::SetModel& model, const AlignedSet& aligned, const MotionSet& set,
                     const SynthesisOptions& options) {
    const char* where = "kernel fit";
    compression::check(model, where);
    const tensor::Dims3 dims = model.tucker.dims();
    if (dims[0] != aligned.dofs() || dims[1] != aligned.frames() || dims[2] != aligned.samples())
        throw InvalidArgument(std::string(where) + ": the model is " + std::to_string(dims[0]) + "x" +
                              std::to_string(dims[1]) + "x" + std::to_string(dims[2]) + " but the aligned tensor " +
                              std::to_string(aligned.dofs()) + "x" + std::to_string(aligned.frames()) + "x" +
                              std::to_string(aligned.samples()));
    const Eigen::Index n = aligned.samples();
    if (set.parameters.rows() != n)
        throw InvalidArgument(std::string(where) + ": the set '" + set.name + "' has " +
                              std::to_string(set.parameters.rows()) + " samples but the aligned tensor " +
                              std::to_string(n));
    if (n < 2)
        throw InvalidArgument(std::string(where) + ": synthesis needs at least 2 samples, the set has " +
                              std::to_string(n));
    kriging::ControlScaling scaling;
    if (options.scaling) {
        options.scaling->validate(set.parameters.cols());
        scaling = *options.scaling;
        if (scaling.period.size() == 0) scaling.period = set.parameter_periods;
        if (scaling.levels.empty()) scaling.levels = parameter_level_counts(set);
    } else {
        scaling =
            kriging::ControlScaling::from_data(set.parameters, set.parameter_periods, parameter_level_counts(set));
    }
    const MatX xc = scaling.apply(set.parameters);
    const MatX values = core_slice_values(model);
    KernelFit fit = fit_coefficient_kernel(xc, values, options, where);
    fit.key = kernel_key(model, set, options);
    // What the model built from this fit reports (SynthesisModel's precomputed path, on the same inputs
    // and hence the same key), so that loading a stored fit need not recompute it.
    if (values.allFinite()) fit.assessed_status = assess_coefficient_kernel(xc, values, fit.variogram, options);
    // The predictor cross-validation picks (predictor_choice.hpp; an average where it cannot tell the best
    // apart from others), leaving out the overlapping windows
    // of a held-out sample's clip with it (twins of different clips need the frames: not here).
    PredictorChoiceOptions choice;
    choice.max_samples = std::max<std::size_t>(options.max_fit_samples, 5);
    choice.elements_per_sample = static_cast<double>(aligned.dofs() * aligned.frames());
    // RBF's system is not stored: every load factorizes it (O(N^3)), so it is a candidate only where that
    // stays cheap (up to max_fit_samples samples: about 0.2 s).
    if (static_cast<std::size_t>(n) > options.max_fit_samples)
        choice.candidates = {Predictor::Kriging, Predictor::Trend};
    if (n >= 5 && values.allFinite()) {
        const auto twins = find_sample_twins(set, SampleFrames{}).partners(static_cast<std::size_t>(n));
        // Scored on the posture, as the evaluation's pose error (the root's path left out).
        const MatX posture = posture_slice_values(model, values);
        PredictorChoice c = choose_predictor(xc, posture, fit.variogram, options.kriging, twins, choice);
        if (c.folds > 0) fit.predictor = std::move(c);
    }
    // Above max_exact_samples the model uses local kriging: no N x N system is built, none stored.
    if (static_cast<std::size_t>(n) <= std::min(options.max_stored_system_samples, options.max_exact_samples))
        fit.system = std::make_shared<const kriging::CovarianceInverse>(
            kriging::Kriging::covariance_inverse(xc, fit.variogram, options.kriging, options.fit_progress));
    return fit;
}

}  // namespace mocapdb::synthesis
