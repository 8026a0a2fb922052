#include "mocapdb/kriging/variogram.hpp"

#include <cmath>
#include <string>

#include "mocapdb/core/error.hpp"

namespace mocapdb::kriging {

const char* to_string(VariogramEstimator estimator) {
    return estimator == VariogramEstimator::Cressie ? "cressie" : "matheron";
}

int ExperimentalVariogram::nonempty_bins() const {
    int n = 0;
    for (std::size_t c : npairs) n += c > 0 ? 1 : 0;
    return n;
}

double cressie_denominator(std::size_t npairs) {
    const double n = static_cast<double>(npairs);
    return 0.457 + 0.494 / n + 0.045 / (n * n);
}

double cressie_gstat_to_three_term(double gamma_gstat, std::size_t npairs) {
    const double n = static_cast<double>(npairs);
    return gamma_gstat * (0.457 + 0.494 / n) / cressie_denominator(npairs);
}

Eigen::MatrixXd pairwise_distances(const Eigen::Ref<const Eigen::MatrixXd>& points) {
    const Eigen::Index n = points.rows();
    Eigen::MatrixXd d = Eigen::MatrixXd::Zero(n, n);
    for (Eigen::Index j = 0; j < n; ++j) {
        for (Eigen::Index i = j + 1; i < n; ++i) {
            const double v = (points.row(i) - points.row(j)).norm();
            d(i, j) = v;
            d(j, i) = v;
        }
    }
    return d;
}

ExperimentalVariogram experimental_variogram(const Eigen::Ref<const Eigen::MatrixXd>& distances,
                                             const Eigen::Ref<const Eigen::MatrixXd>& differences,
                                             const VariogramOptions& options) {
    const Eigen::Index n = distances.rows();
    if (distances.cols() != n || differences.rows() != n || differences.cols() != n) {
        throw InvalidArgument("experimental_variogram: distances and differences must both be N by N (got " +
                              std::to_string(distances.rows()) + "x" + std::to_string(distances.cols()) + " and " +
                              std::to_string(differences.rows()) + "x" + std::to_string(differences.cols()) + ")");
    }
    if (n < 2) throw InvalidArgument("experimental_variogram: need at least 2 samples, got " + std::to_string(n));
    if (options.bins < 1) {
        throw InvalidArgument("experimental_variogram: bins must be >= 1, got " + std::to_string(options.bins));
    }
    if (!(std::isfinite(options.cutoff) && options.cutoff >= 0.0)) {
        throw InvalidArgument("experimental_variogram: cutoff must be finite and >= 0 (0 = h_max/2), got " +
                              std::to_string(options.cutoff));
    }
    double hmax = 0.0;
    for (Eigen::Index j = 0; j < n; ++j) {
        for (Eigen::Index i = 0; i < j; ++i) {
            const double h = distances(i, j);
            const double d = differences(i, j);
            if (!(std::isfinite(h) && h >= 0.0)) {
                throw InvalidArgument("experimental_variogram: distance (" + std::to_string(i) + "," +
                                      std::to_string(j) + ") must be finite and >= 0");
            }
            if (!(std::isfinite(d) && d >= 0.0)) {
                throw InvalidArgument("experimental_variogram: difference (" + std::to_string(i) + "," +
                                      std::to_string(j) + ") must be finite and >= 0");
            }
            hmax = std::max(hmax, h);
        }
    }
    ExperimentalVariogram ev;
    ev.estimator = options.estimator;
    ev.max_distance = hmax;
    ev.cutoff = options.cutoff > 0.0 ? options.cutoff : 0.5 * hmax;
    const int nb = options.bins;
    ev.center = Eigen::VectorXd::Zero(nb);
    ev.dist = Eigen::VectorXd::Zero(nb);
    ev.gamma = Eigen::VectorXd::Zero(nb);
    ev.npairs.assign(static_cast<std::size_t>(nb), 0);
    if (!(ev.cutoff > 0.0)) {
        // All control points coincide: everything lands in the first bin at distance 0.
        ev.cutoff = 0.0;
        ev.width = 0.0;
    } else {
        ev.width = ev.cutoff / nb;
    }
    for (int u = 0; u < nb; ++u) ev.center(u) = ev.width * (u + 0.5);

    Eigen::VectorXd acc = Eigen::VectorXd::Zero(nb);
    for (Eigen::Index j = 0; j < n; ++j) {
        for (Eigen::Index i = 0; i < j; ++i) {
            const double h = distances(i, j);
            int u = 0;
            if (h > 0.0) {
                if (h > ev.cutoff) continue;
                // (lower, upper] intervals: an exact multiple of the width closes the lower bin.
                const double frac = h / ev.width;
                double fl = std::floor(frac);
                if (fl == frac) fl -= 1.0;
                u = static_cast<int>(fl);
                if (u >= nb) u = nb - 1;
                if (u < 0) u = 0;
            } else {
                ++ev.zero_distance_pairs;
            }
            const double d = differences(i, j);
            ev.npairs[static_cast<std::size_t>(u)] += 1;
            ev.dist(u) += h;
            acc(u) += options.estimator == VariogramEstimator::Cressie ? std::sqrt(d) : d * d;
        }
    }
    for (int u = 0; u < nb; ++u) {
        const std::size_t c = ev.npairs[static_cast<std::size_t>(u)];
        if (c == 0) continue;
        const double cn = static_cast<double>(c);
        ev.dist(u) /= cn;
        if (options.estimator == VariogramEstimator::Cressie) {
            const double m = acc(u) / cn;
            const double m2 = m * m;
            ev.gamma(u) = 0.5 * m2 * m2 / cressie_denominator(c);
        } else {
            ev.gamma(u) = 0.5 * acc(u) / cn;
        }
    }
    return ev;
}

ExperimentalVariogram experimental_variogram_scalar(const Eigen::Ref<const Eigen::MatrixXd>& coords,
                                                    const Eigen::Ref<const Eigen::VectorXd>& values,
                                                    const VariogramOptions& options) {
    if (values.size() != coords.rows()) {
        throw InvalidArgument("experimental_variogram_scalar: values must have one entry per row of coords (" +
                              std::to_string(coords.rows()) + "), got " + std::to_string(values.size()));
    }
    const Eigen::Index n = values.size();
    Eigen::MatrixXd diff(n, n);
    for (Eigen::Index j = 0; j < n; ++j) {
        for (Eigen::Index i = 0; i < n; ++i) diff(i, j) = std::abs(values(i) - values(j));
    }
    return experimental_variogram(pairwise_distances(coords), diff, options);
}

ExperimentalVariogram experimental_variogram_rows(const Eigen::Ref<const Eigen::MatrixXd>& coords,
                                                  const Eigen::Ref<const Eigen::MatrixXd>& samples,
                                                  const VariogramOptions& options) {
    if (samples.rows() != coords.rows()) {
        throw InvalidArgument("experimental_variogram_rows: samples must have one row per row of coords (" +
                              std::to_string(coords.rows()) + "), got " + std::to_string(samples.rows()));
    }
    return experimental_variogram(pairwise_distances(coords), pairwise_distances(samples), options);
}

}  // namespace mocapdb::kriging
