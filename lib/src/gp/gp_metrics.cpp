#include "mocapdb/gp/gp_metrics.hpp"

#include <cmath>
#include <limits>
#include <string>

#include "mocapdb/core/error.hpp"

namespace mocapdb::gp {

InterpolationScores interpolation_scores(const MatX& truth, const MatX& mean, const MatX& variance,
                                         const VecX& train_mean, const VecX& train_variance) {
    const Eigen::Index d = truth.rows(), t = truth.cols();
    if (mean.rows() != d || mean.cols() != t || variance.rows() != d || variance.cols() != t ||
        train_mean.size() != d || train_variance.size() != d)
        throw InvalidArgument(
            "interpolation_scores: truth, mean, variance must be D by T and the training moments D values");
    if (t < 2) throw InvalidArgument("interpolation_scores: need ≥ 2 test frames");
    if (!(variance.array() > 0.0).all() || !(train_variance.array() > 0.0).all())
        throw InvalidArgument("interpolation_scores: predictive and training variances must be > 0");
    if (!truth.allFinite() || !mean.allFinite() || !variance.allFinite())
        throw InvalidArgument("interpolation_scores: non-finite input");
    InterpolationScores s;
    s.points = static_cast<std::size_t>(d * t);
    const MatX err2 = (truth - mean).cwiseAbs2();
    s.mse = err2.mean();
    double smse = 0.0;
    Eigen::Index smse_outputs = 0;
    double sll = 0.0;
    for (Eigen::Index i = 0; i < d; ++i) {
        const double mu = truth.row(i).mean();
        const double v = (truth.row(i).array() - mu).square().mean();
        if (v > 0.0) {
            smse += err2.row(i).mean() / v;
            ++smse_outputs;
        }
        for (Eigen::Index f = 0; f < t; ++f) {
            const double s2 = variance(i, f);
            const double model = 0.5 * std::log(2.0 * kPi * s2) + err2(i, f) / (2.0 * s2);
            const double dev = truth(i, f) - train_mean[i];
            const double trivial =
                0.5 * std::log(2.0 * kPi * train_variance[i]) + dev * dev / (2.0 * train_variance[i]);
            sll += model - trivial;
        }
    }
    if (smse_outputs > 0) s.smse = smse / static_cast<double>(smse_outputs);
    s.msll = sll / static_cast<double>(d * t);
    return s;
}

MatX minmax_rows(const MatX& signals) {
    MatX out(signals.rows(), signals.cols());
    for (Eigen::Index i = 0; i < signals.rows(); ++i) {
        const double lo = signals.row(i).minCoeff(), hi = signals.row(i).maxCoeff();
        if (hi > lo) out.row(i) = (signals.row(i).array() - lo) / (hi - lo);
        else out.row(i).setZero();
    }
    return out;
}

double max_cross_correlation(const VecX& a, const VecX& b) {
    if (a.size() == 0 || b.size() == 0) throw InvalidArgument("max_cross_correlation: empty sequence");
    double best = -std::numeric_limits<double>::infinity();
    // lag from −(|a| − 1) to |b| − 1: Σ_m a[m] b[m + lag] over the overlap.
    for (Eigen::Index lag = -(a.size() - 1); lag <= b.size() - 1; ++lag) {
        const Eigen::Index m0 = std::max<Eigen::Index>(0, -lag), m1 = std::min<Eigen::Index>(a.size(), b.size() - lag);
        double s = 0.0;
        for (Eigen::Index m = m0; m < m1; ++m) s += a[m] * b[m + lag];
        best = std::max(best, s);
    }
    return best;
}

std::optional<double> pearson(const VecX& a, const VecX& b) {
    if (a.size() != b.size() || a.size() < 2)
        throw InvalidArgument("pearson: need two sequences of the same length ≥ 2");
    const VecX ca = a.array() - a.mean(), cb = b.array() - b.mean();
    const double na = ca.norm(), nb = cb.norm();
    if (!(na > 0.0) || !(nb > 0.0)) return std::nullopt;
    return ca.dot(cb) / (na * nb);
}

double mean_cross_correlation(const MatX& generated, const MatX& real) {
    if (generated.rows() != real.rows() || generated.rows() == 0)
        throw InvalidArgument("mean_cross_correlation: generated and real must have the same outputs");
    const MatX g = minmax_rows(generated), r = minmax_rows(real);
    double s = 0.0;
    for (Eigen::Index i = 0; i < g.rows(); ++i) s += max_cross_correlation(r.row(i).transpose(), g.row(i).transpose());
    return s / static_cast<double>(g.rows());
}

std::optional<double> mean_linear_correlation(const MatX& generated, const MatX& real) {
    if (generated.rows() != real.rows() || generated.cols() != real.cols() || generated.rows() == 0)
        throw InvalidArgument("mean_linear_correlation: generated and real must have the same shape");
    const MatX g = minmax_rows(generated), r = minmax_rows(real);
    double s = 0.0;
    int n = 0;
    for (Eigen::Index i = 0; i < g.rows(); ++i) {
        if (const std::optional<double> p = pearson(r.row(i).transpose(), g.row(i).transpose())) {
            s += *p;
            ++n;
        }
    }
    if (n == 0) return std::nullopt;
    return s / n;
}

MeanStd mean_std(const std::vector<double>& values) {
    MeanStd m;
    if (values.empty()) return m;
    for (double v : values) m.mean += v;
    m.mean /= static_cast<double>(values.size());
    for (double v : values) m.std += (v - m.mean) * (v - m.mean);
    m.std = std::sqrt(m.std / static_cast<double>(values.size()));
    return m;
}

std::optional<MeanStd> mean_std_of_all(const std::vector<std::optional<double>>& values) {
    std::vector<double> defined;
    for (const std::optional<double>& v : values) {
        if (!v) return std::nullopt;
        defined.push_back(*v);
    }
    return mean_std(defined);
}

SynthesisScores synthesis_scores(const std::vector<MatX>& generated, const std::vector<MatX>& real) {
    if (generated.empty() || real.empty()) throw InvalidArgument("synthesis_scores: need generated and real motions");
    SynthesisScores s;
    for (const MatX& r : real) {
        std::vector<double> mcc;
        std::vector<std::optional<double>> mlc;
        for (const MatX& g : generated) {
            mcc.push_back(mean_cross_correlation(g, r));
            if (g.cols() == r.cols()) mlc.push_back(mean_linear_correlation(g, r));
        }
        s.mcc.push_back(mean_std(mcc));
        s.mlc.push_back(mean_std_of_all(mlc));
    }
    return s;
}

}  // namespace mocapdb::gp
