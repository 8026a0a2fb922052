#include "mocapdb/kriging/motion_kriging.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "mocapdb/core/error.hpp"

namespace mocapdb::kriging {

const char* to_string(KernelScope scope) {
    switch (scope) {
        case KernelScope::PerElement: return "per-element";
        case KernelScope::PerPose: return "per-pose";
        case KernelScope::PerSet: return "per-set";
    }
    return "unknown";
}

namespace {

Eigen::MatrixXd abs_differences(const Eigen::Ref<const Eigen::VectorXd>& r) {
    const Eigen::Index n = r.size();
    Eigen::MatrixXd d(n, n);
    for (Eigen::Index j = 0; j < n; ++j) d.col(j) = (r.array() - r(j)).abs().matrix();
    return d;
}

double variance(const Eigen::Ref<const Eigen::VectorXd>& r) { return (r.array() - r.mean()).square().mean(); }

}  // namespace

MotionKriging MotionKriging::build(const Eigen::Ref<const Eigen::MatrixXd>& coords,
                                   const Eigen::Ref<const Eigen::MatrixXd>& samples,
                                   const Eigen::Ref<const Eigen::MatrixXd>& pose_signal,
                                   const Eigen::Ref<const Eigen::MatrixXd>& dissimilarity,
                                   const MotionKrigingOptions& options) {
    const Eigen::Index n = coords.rows();
    if (n < 2 || coords.cols() < 1) {
        throw InvalidArgument("MotionKriging::build: coords must be N by P with N >= 2 and P >= 1, got " +
                              std::to_string(n) + "x" + std::to_string(coords.cols()));
    }
    if (samples.rows() != n || samples.cols() < 1) {
        throw InvalidArgument("MotionKriging::build: samples must be N by (D*T) with N = " + std::to_string(n) +
                              ", got " + std::to_string(samples.rows()) + "x" + std::to_string(samples.cols()));
    }
    if (!coords.allFinite() || !samples.allFinite()) {
        throw InvalidArgument("MotionKriging::build: coords and samples must be finite");
    }
    const Eigen::Index cols = samples.cols();
    Eigen::Index d = options.dofs_per_frame > 0 ? options.dofs_per_frame : cols;
    if (options.dofs_per_frame < 0 || cols % d != 0) {
        throw InvalidArgument("MotionKriging::build: dofs_per_frame (" + std::to_string(options.dofs_per_frame) +
                              ") must be >= 0 and divide the number of sample columns (" + std::to_string(cols) + ")");
    }
    const Eigen::Index t_frames = cols / d;
    if (options.scope == KernelScope::PerPose) {
        if (pose_signal.rows() != n || pose_signal.cols() != t_frames) {
            throw InvalidArgument("MotionKriging::build: PerPose needs pose_signal N by T = " + std::to_string(n) +
                                  " by " + std::to_string(t_frames) + ", got " + std::to_string(pose_signal.rows()) +
                                  "x" + std::to_string(pose_signal.cols()));
        }
        if (!pose_signal.allFinite()) throw InvalidArgument("MotionKriging::build: pose_signal must be finite");
        for (Eigen::Index k : options.root_dofs) {
            if (k < 0 || k >= d) {
                throw InvalidArgument("MotionKriging::build: root dof " + std::to_string(k) +
                                      " outside [0, D = " + std::to_string(d) + ")");
            }
        }
    }
    if (options.scope == KernelScope::PerSet && dissimilarity.size() > 0 &&
        (dissimilarity.rows() != n || dissimilarity.cols() != n)) {
        throw InvalidArgument("MotionKriging::build: dissimilarity must be N by N (N = " + std::to_string(n) +
                              ") or empty");
    }
    if (options.representative >= 0) {
        const Eigen::Index limit = options.scope == KernelScope::PerElement ? cols : t_frames;
        if (options.scope != KernelScope::PerSet && options.representative >= limit) {
            throw InvalidArgument("MotionKriging::build: representative must be < " + std::to_string(limit));
        }
    }
    if (options.exponent && !(*options.exponent >= 0.0 && *options.exponent <= 2.0)) {
        throw InvalidArgument("MotionKriging::build: exponent p must be in [0, 2]");
    }

    MotionKriging mk;
    if (options.scaling) {
        options.scaling->validate(coords.cols());
        mk.scaling_ = *options.scaling;
    } else if (options.normalize_controls) {
        mk.scaling_ = ControlScaling::from_data(coords);
    } else {
        mk.scaling_ = ControlScaling::identity(coords.cols());
    }
    mk.samples_ = samples;
    const Eigen::MatrixXd xc = mk.scaling_.apply(coords);
    mk.kernel_of_column_.assign(static_cast<std::size_t>(cols), 0);

    if (options.method == InterpolationMethod::Rbf) {
        auto rbf = std::make_shared<RbfInterpolator>(RbfInterpolator::build(xc, options.rbf));
        mk.report_.duplicates_merged = rbf->status().duplicates_merged;
        mk.report_.trend_rank_deficient = rbf->status().trend_rank_deficient;
        mk.kernels_.push_back(std::move(rbf));
        mk.columns_of_kernel_.emplace_back();
        for (Eigen::Index c = 0; c < cols; ++c) mk.columns_of_kernel_[0].push_back(c);
        mk.report_.kernels = 1;
        return mk;
    }

    const TrendBasis basis = TrendBasis::build(xc, options.kriging.trend, options.kriging.trend_rank_tolerance);
    const Eigen::MatrixXd h = pairwise_distances(xc);
    const Eigen::MatrixXd res = fit_trend_ols(basis, samples).residuals;
    Eigen::MatrixXd pose_res;
    if (options.scope == KernelScope::PerPose) pose_res = fit_trend_ols(basis, pose_signal).residuals;

    // One entry per kernel: which signal estimates its variogram, which columns it serves.
    struct KernelSpec {
        enum Kind { SampleColumn, PoseFrame, Set } kind;
        Eigen::Index index;
        std::vector<Eigen::Index> columns;
    };
    std::vector<KernelSpec> specs;
    if (options.scope == KernelScope::PerElement) {
        for (Eigen::Index c = 0; c < cols; ++c) specs.push_back({KernelSpec::SampleColumn, c, {c}});
    } else if (options.scope == KernelScope::PerPose) {
        std::vector<bool> is_root(static_cast<std::size_t>(d), false);
        for (Eigen::Index k : options.root_dofs) is_root[static_cast<std::size_t>(k)] = true;
        for (Eigen::Index t = 0; t < t_frames; ++t) {
            KernelSpec frame{KernelSpec::PoseFrame, t, {}};
            for (Eigen::Index k = 0; k < d; ++k) {
                if (is_root[static_cast<std::size_t>(k)]) {
                    specs.push_back({KernelSpec::SampleColumn, t * d + k, {t * d + k}});
                } else {
                    frame.columns.push_back(t * d + k);
                }
            }
            if (!frame.columns.empty()) specs.push_back(frame);
        }
    } else {
        KernelSpec all{KernelSpec::Set, 0, {}};
        for (Eigen::Index c = 0; c < cols; ++c) all.columns.push_back(c);
        specs.push_back(all);
    }

    const Eigen::MatrixXd set_dissimilarity =
        options.scope == KernelScope::PerSet
            ? (dissimilarity.size() > 0 ? Eigen::MatrixXd(dissimilarity) : pairwise_distances(res))
            : Eigen::MatrixXd();
    auto variogram_of = [&](const KernelSpec& s) {
        switch (s.kind) {
            case KernelSpec::SampleColumn:
                return experimental_variogram(h, abs_differences(res.col(s.index)), options.variogram);
            case KernelSpec::PoseFrame:
                return experimental_variogram(h, abs_differences(pose_res.col(s.index)), options.variogram);
            case KernelSpec::Set: break;
        }
        return experimental_variogram(h, set_dissimilarity, options.variogram);
    };

    // The exponent: fixed, or chosen by LOO on the representative signal.
    double p = 0.0;
    if (options.exponent) {
        p = *options.exponent;
    } else {
        KernelSpec rep{KernelSpec::Set, 0, {}};
        Eigen::MatrixXd values;
        if (options.scope == KernelScope::PerElement) {
            Eigen::Index best = options.representative;
            if (best < 0) {
                best = 0;
                for (Eigen::Index c = 1; c < cols; ++c) {
                    if (variance(res.col(c)) > variance(res.col(best))) best = c;
                }
            }
            rep = {KernelSpec::SampleColumn, best, {}};
            values = samples.col(best);
        } else if (options.scope == KernelScope::PerPose) {
            Eigen::Index best = options.representative;
            if (best < 0) {
                best = 0;
                for (Eigen::Index t = 1; t < t_frames; ++t) {
                    if (variance(pose_res.col(t)) > variance(pose_res.col(best))) best = t;
                }
            }
            rep = {KernelSpec::PoseFrame, best, {}};
            values = pose_signal.col(best);
        } else {
            values = samples;
        }
        const ExponentSelection sel = select_exponent(variogram_of(rep), xc, values, options.kriging, options.fit);
        p = sel.grid[sel.best];
    }
    // PerPose: the root dofs (positions in cm, heading) vary with c quite differently from the pose signal,
    // so their per-element kernels get an exponent of their own, chosen the same way on the root column
    // with the largest residual variance. (With the pose signal's p, a smooth p = 2 model on a root column
    // of the CMU jumps was ill-conditioned enough to put one left-out root 20 m off.)
    double p_root = p;
    if (!options.exponent && options.scope == KernelScope::PerPose) {
        Eigen::Index best = -1;
        for (const auto& s : specs) {
            if (s.kind != KernelSpec::SampleColumn) continue;
            if (best < 0 || variance(res.col(s.index)) > variance(res.col(best))) best = s.index;
        }
        if (best >= 0 && !(res.col(best).cwiseAbs().maxCoeff() <= 1e-12 * samples.col(best).cwiseAbs().maxCoeff())) {
            const KernelSpec rep{KernelSpec::SampleColumn, best, {}};
            const Eigen::MatrixXd values = samples.col(best);
            const ExponentSelection sel = select_exponent(variogram_of(rep), xc, values, options.kriging, options.fit);
            p_root = sel.grid[sel.best];
        }
    }
    mk.report_.exponent = p;
    mk.report_.root_exponent = p_root;
    const double h_half = std::max(0.5 * h.maxCoeff(), 1e-12);

    // A signal whose residuals are at rounding level (exactly linear in c) has no variogram to estimate.
    auto negligible = [](const Eigen::Ref<const Eigen::MatrixXd>& residual,
                         const Eigen::Ref<const Eigen::MatrixXd>& raw) {
        const double scale = raw.cwiseAbs().maxCoeff();
        return residual.cwiseAbs().maxCoeff() <= 1e-12 * scale;
    };
    for (const auto& s : specs) {
        const double p_kernel =
            (options.scope == KernelScope::PerPose && s.kind == KernelSpec::SampleColumn) ? p_root : p;
        const VariogramFamily family = p_kernel == 0.0 ? VariogramFamily::Spherical : VariogramFamily::Stable;
        const double p_fit = p_kernel == 0.0 ? 1.0 : p_kernel;
        bool flat = false;
        switch (s.kind) {
            case KernelSpec::SampleColumn: flat = negligible(res.col(s.index), samples.col(s.index)); break;
            case KernelSpec::PoseFrame: flat = negligible(pose_res.col(s.index), pose_signal.col(s.index)); break;
            case KernelSpec::Set: flat = dissimilarity.size() == 0 && negligible(res, samples); break;
        }
        VariogramFit fit;
        if (!flat) fit = fit_variogram(variogram_of(s), family, p_fit, options.fit);
        VariogramModel model = fit.model;
        if (flat || fit.status == FitStatus::Degenerate || !(model.total_sill() > 0.0)) {
            // No variation: any valid kernel gives the same (trend-only) prediction.
            ++mk.report_.degenerate_kernels;
            model = VariogramModel::from_paper_p(p_kernel, 0.0, 1.0, h_half);
        }
        auto kr = std::make_shared<Kriging>(Kriging::build(xc, model, options.kriging));
        if (!kr->status().exact()) ++mk.report_.inexact_kernels;
        mk.report_.duplicates_merged = kr->status().duplicates_merged;
        mk.report_.trend_rank_deficient = kr->status().trend_rank_deficient;
        const auto kid = static_cast<Eigen::Index>(mk.kernels_.size());
        for (Eigen::Index c : s.columns) mk.kernel_of_column_[static_cast<std::size_t>(c)] = kid;
        mk.columns_of_kernel_.push_back(s.columns);
        mk.models_.push_back(model);
        mk.kernels_.push_back(std::move(kr));
    }
    mk.report_.kernels = static_cast<Eigen::Index>(mk.kernels_.size());
    return mk;
}

void MotionKriging::predict(const Eigen::Ref<const Eigen::VectorXd>& c, Eigen::Ref<Eigen::VectorXd> out_values) const {
    if (c.size() != dimension() || out_values.size() != num_columns()) {
        throw InvalidArgument("MotionKriging::predict: c must have P = " + std::to_string(dimension()) +
                              " entries and out_values " + std::to_string(num_columns()));
    }
    Eigen::VectorXd cn;
    scaling_.apply_point(c, cn);
    QueryWorkspace ws;
    Eigen::VectorXd w(num_samples());
    for (std::size_t k = 0; k < kernels_.size(); ++k) {
        kernels_[k]->weights(cn, w, ws);
        for (Eigen::Index col : columns_of_kernel_[k]) out_values(col) = w.dot(samples_.col(col));
    }
}

Eigen::MatrixXd MotionKriging::predict_batch(const Eigen::Ref<const Eigen::MatrixXd>& queries) const {
    if (queries.cols() != dimension()) {
        throw InvalidArgument("MotionKriging::predict_batch: queries must be Q by P with P = " +
                              std::to_string(dimension()));
    }
    const Eigen::MatrixXd qn = scaling_.apply(queries);
    Eigen::MatrixXd out(queries.rows(), num_columns());
    Eigen::MatrixXd w(num_samples(), queries.rows());
    for (std::size_t k = 0; k < kernels_.size(); ++k) {
        kernels_[k]->weights_batch(qn, w);
        for (Eigen::Index col : columns_of_kernel_[k]) out.col(col).noalias() = w.transpose() * samples_.col(col);
    }
    return out;
}

}  // namespace mocapdb::kriging
