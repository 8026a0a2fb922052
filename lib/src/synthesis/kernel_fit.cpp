#include "mocapdb/synthesis/kernel_fit.hpp"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <string>

#include "mocapdb/compression/set_model.hpp"
#include "mocapdb/core/error.hpp"
#include "mocapdb/dataset/aligned_set.hpp"
#include "mocapdb/dataset/motion_set.hpp"
#include "mocapdb/kriging/variogram.hpp"
#include "mocapdb/kriging/variogram_fit.hpp"
#include "mocapdb/synthesis/synthesis_model.hpp"

namespace mocapdb::synthesis {
namespace {

std::string idx(Eigen::Index i) { return std::to_string(static_cast<long long>(i)); }

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

}  // namespace

std::string kernel_options_text(const SynthesisOptions& o) {
    std::string s = "coefficient-kernel-1";
    s += ";exponent=" + (o.exponent ? number_text(*o.exponent) : std::string("loo"));
    s += ";scaling=";
    if (o.scaling) {
        for (Eigen::Index k = 0; k < o.scaling->offset.size(); ++k) s += number_text(o.scaling->offset(k)) + ",";
        s += "/";
        for (Eigen::Index k = 0; k < o.scaling->scale.size(); ++k) s += number_text(o.scaling->scale(k)) + ",";
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
    s += ";kriging=" + std::to_string(static_cast<int>(k.trend)) + "," + std::to_string(static_cast<int>(k.trend_fit)) +
         "," + std::to_string(static_cast<int>(k.duplicates)) + "," + number_text(k.duplicate_tolerance) + "," +
         number_text(k.min_rcond) + "," + number_text(k.max_jitter) + "," + number_text(k.trend_rank_tolerance);
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
    return d.h == 0 ? 1 : d.h;
}

MatX core_slice_values(const compression::SetModel& model) {
    const tensor::Ranks& r = model.tucker.ranks;
    const Eigen::Map<const MatX> c3(model.tucker.core.data(), r[0] * r[1], r[2]);
    return model.tucker.U[2] * c3.transpose();
}

KernelFit fit_coefficient_kernel(const Eigen::Ref<const MatX>& xc, const Eigen::Ref<const MatX>& sample_values,
                                 const SynthesisOptions& options, const char* where) {
    const MatX h = kriging::pairwise_distances(xc);
    const MatX d = kriging::pairwise_distances(sample_values);
    const kriging::ExperimentalVariogram ev = kriging::experimental_variogram(h, d, options.variogram);
    const double h_half = std::max(0.5 * h.maxCoeff(), 1e-12);
    KernelFit out;
    kriging::VariogramModel model;
    bool degenerate = !(d.maxCoeff() > 0.0);
    if (!degenerate) {
        if (options.exponent) {
            const double p = *options.exponent;
            if (!(p >= 0.0 && p <= 2.0)) throw InvalidArgument(std::string(where) + ": exponent p must be in [0, 2]");
            const kriging::VariogramFit fit = kriging::fit_variogram(
                ev, p == 0.0 ? kriging::VariogramFamily::Spherical : kriging::VariogramFamily::Stable, p == 0.0 ? 1.0 : p,
                options.fit);
            model = fit.model;
            degenerate = fit.degenerate;
        } else {
            const kriging::ExponentSelection sel =
                kriging::select_exponent(ev, xc, sample_values, options.kriging, options.fit);
            model = sel.model();
            degenerate = sel.fits[sel.best].degenerate;
            out.exponent_loo_mse = sel.loo_mse;
        }
    }
    if (degenerate || !(model.total_sill() > 0.0)) {
        // Samples without variation: any valid kernel gives the same (trend-only) prediction.
        model = kriging::VariogramModel::from_paper_p(options.exponent.value_or(1.0), 0.0, 1.0, h_half);
    }
    out.variogram = model;
    return out;
}

KernelFit fit_kernel(const compression::SetModel& model, const AlignedSet& aligned, const MotionSet& set,
                     const SynthesisOptions& options) {
    const char* where = "kernel fit";
    compression::check(model, where);
    const tensor::Dims3 dims = model.tucker.dims();
    if (dims[0] != aligned.dofs() || dims[1] != aligned.frames() || dims[2] != aligned.samples())
        throw InvalidArgument(std::string(where) + ": the model is " + idx(dims[0]) + "x" + idx(dims[1]) + "x" +
                              idx(dims[2]) + " but the aligned tensor " + idx(aligned.dofs()) + "x" +
                              idx(aligned.frames()) + "x" + idx(aligned.samples()));
    const Eigen::Index n = aligned.samples();
    if (set.parameters.rows() != n)
        throw InvalidArgument(std::string(where) + ": the set '" + set.name + "' has " + idx(set.parameters.rows()) +
                              " samples but the aligned tensor " + idx(n));
    if (n < 2) throw InvalidArgument(std::string(where) + ": synthesis needs at least 2 samples, the set has " + idx(n));
    kriging::ControlScaling scaling;
    if (options.scaling) {
        options.scaling->validate(set.parameters.cols());
        scaling = *options.scaling;
    } else {
        scaling = kriging::ControlScaling::from_data(set.parameters);
    }
    KernelFit fit = fit_coefficient_kernel(scaling.apply(set.parameters), core_slice_values(model), options, where);
    fit.key = kernel_key(model, set, options);
    return fit;
}

}  // namespace mocapdb::synthesis
