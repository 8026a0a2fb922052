#include "mocapdb/eval/kernel_headroom.hpp"

#include <algorithm>

#include "mocapdb/core/error.hpp"
#include "mocapdb/eval/loo_prediction.hpp"
#include "mocapdb/eval/synthesis_method.hpp"
#include "mocapdb/kriging/kriging.hpp"
#include "mocapdb/kriging/trend.hpp"

namespace mocapdb::eval {
namespace {

void check(const KernelHeadroomOptions& o, Eigen::Index n) {
    if (n < 4) throw InvalidArgument("kernel headroom: the set needs at least 4 samples");
    if (o.exponents.empty() || o.ranges.empty() || o.nugget_shares.empty() || o.anisotropy.empty())
        throw InvalidArgument("kernel headroom: every grid axis needs at least one value");
    for (double p : o.exponents)
        if (!(p >= 0.0 && p <= 2.0)) throw InvalidArgument("kernel headroom: exponents must be in [0, 2]");
    for (double r : o.ranges)
        if (!(r > 0.0 && r < 1e6)) throw InvalidArgument("kernel headroom: ranges must be > 0");
    for (double s : o.nugget_shares)
        if (!(s >= 0.0 && s < 1.0)) throw InvalidArgument("kernel headroom: nugget shares must be in [0, 1)");
    for (double a : o.anisotropy)
        if (!(a > 0.0 && a < 1e6)) throw InvalidArgument("kernel headroom: anisotropy factors must be > 0");
    for (Eigen::Index i : o.samples)
        if (i < 0 || i >= n) throw InvalidArgument("kernel headroom: left-out sample index out of range");
}

// One fold: the training samples' scaled parameters, the left-out one's, and the poses to blend.
struct Fold {
    MatX coords;              // (N - 1) by embedded P
    VecX query;               // embedded P
    std::vector<MatX> poses;  // N - 1 aligned samples, D by T
    MatX truth;               // D by T
};

}  // namespace

KernelHeadroom kernel_headroom(const EvalSet& set, const KernelHeadroomOptions& options,
                               const ProgressCallback& progress) {
    const Eigen::Index n = set.size();
    check(options, n);
    std::vector<Eigen::Index> left_out = options.samples;
    if (left_out.empty())
        for (Eigen::Index i = 0; i < n; ++i) left_out.push_back(i);
    const MatX& params = set.set.parameters;
    const VecX periods = set.set.parameter_periods;
    const bool embedded = (periods.size() > 0 && (periods.array() > 0.0).any()) ||
                          !parameter_level_counts(set.set).empty();  // (no anisotropy over indicator axes)
    std::vector<double> anisotropy = {1.0};
    if (params.cols() >= 2 && !embedded) anisotropy = options.anisotropy;

    std::vector<Fold> folds;
    for (Eigen::Index i : left_out) {
        Fold f;
        MatX train(n - 1, params.cols());
        for (Eigen::Index j = 0, k = 0; j < n; ++j) {
            if (j == i) continue;
            train.row(k++) = params.row(j);
            f.poses.push_back(aligned_sample(set.aligned, j));
        }
        const kriging::ControlScaling scaling =
            kriging::ControlScaling::from_data(train, periods, parameter_level_counts(set.set));
        f.coords = scaling.apply(train);
        scaling.apply_point(params.row(i).transpose(), f.query);
        f.truth = aligned_sample(set.aligned, i);
        folds.push_back(std::move(f));
    }

    kriging::KrigingOptions ko;  // the synthesis models' kriging: linear OLS trend, nugget filtered
    ko.filter_nugget = true;
    const auto total = static_cast<std::uint64_t>(anisotropy.size() * options.exponents.size() * options.ranges.size() *
                                                  options.nugget_shares.size());
    std::uint64_t done = 0;
    KernelHeadroom out;
    std::vector<double> means;
    MatX blend(set.aligned.dofs(), set.aligned.frames());
    for (double a : anisotropy)
        for (double p : options.exponents)
            for (double range : options.ranges)
                for (double share : options.nugget_shares) {
                    if (progress) progress({++done, total, ""});
                    if (p == 2.0 && share == 0.0) continue;  // a Gaussian model needs a nugget
                    const kriging::VariogramModel model =
                        kriging::VariogramModel::from_paper_p(p, share, 1.0 - share, range);
                    double sum = 0.0;
                    for (const Fold& f : folds) {
                        MatX coords = f.coords;
                        VecX query = f.query;
                        coords.rightCols(coords.cols() - 1) *= a;
                        query.tail(query.size() - 1) *= a;
                        const VecX w = kriging::Kriging::build(coords, model, ko).estimate(query).weights;
                        blend.setZero();
                        for (std::size_t k = 0; k < f.poses.size(); ++k)
                            blend += w(static_cast<Eigen::Index>(k)) * f.poses[k];
                        sum += frame_joint_errors(*set.skeleton, f.truth, blend, true).col(0).mean();
                    }
                    const double mean = sum / static_cast<double>(folds.size());
                    means.push_back(mean);
                    if (out.kernels == 0 || mean < out.best_pose_mean_cm) {
                        out.best = model;
                        out.best_anisotropy = a;
                        out.best_pose_mean_cm = mean;
                    }
                    ++out.kernels;
                }
    std::nth_element(means.begin(), means.begin() + static_cast<std::ptrdiff_t>(means.size() / 2), means.end());
    out.median_pose_mean_cm = means[means.size() / 2];
    return out;
}

}  // namespace mocapdb::eval
