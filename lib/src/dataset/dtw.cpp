#include "mocapdb/dataset/dtw.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "mocapdb/core/error.hpp"

namespace mocapdb::align {

DtwPath dtw(const Eigen::Ref<const MatX>& cost, double band) {
    const Eigen::Index n = cost.rows(), m = cost.cols();
    if (n < 1 || m < 1) throw InvalidArgument("dtw: empty cost matrix");
    if (!cost.allFinite()) throw InvalidArgument("dtw: non-finite cost");
    if (!(band > 0.0)) throw InvalidArgument("dtw: band must be positive");
    const double inf = std::numeric_limits<double>::infinity();
    auto inside = [&](Eigen::Index i, Eigen::Index j) {
        if (band >= 1.0 || n == 1 || m == 1) return true;
        const double di = static_cast<double>(i) / static_cast<double>(n - 1);
        const double dj = static_cast<double>(j) / static_cast<double>(m - 1);
        return std::abs(di - dj) <= band;
    };
    MatX acc = MatX::Constant(n, m, inf);
    for (Eigen::Index i = 0; i < n; ++i) {
        for (Eigen::Index j = 0; j < m; ++j) {
            if (!inside(i, j)) continue;
            double best = (i == 0 && j == 0) ? 0.0 : inf;
            if (i > 0) best = std::min(best, acc(i - 1, j));
            if (j > 0) best = std::min(best, acc(i, j - 1));
            if (i > 0 && j > 0) best = std::min(best, acc(i - 1, j - 1));
            acc(i, j) = best + cost(i, j);
        }
    }
    if (!std::isfinite(acc(n - 1, m - 1))) throw InvalidArgument("dtw: the band leaves no path; widen it");
    DtwPath path;
    path.total_cost = acc(n - 1, m - 1);
    Eigen::Index i = n - 1, j = m - 1;
    path.pairs.emplace_back(i, j);
    while (i > 0 || j > 0) {
        // Step back to the cheapest predecessor (diagonal first on ties: fewer, straighter steps).
        Eigen::Index bi = i, bj = j;
        double best = inf;
        if (i > 0 && j > 0 && acc(i - 1, j - 1) <= best) best = acc(bi = i - 1, bj = j - 1);
        if (i > 0 && acc(i - 1, j) < best) best = acc(bi = i - 1, bj = j);
        if (j > 0 && acc(i, j - 1) < best) best = acc(bi = i, bj = j - 1);
        i = bi;
        j = bj;
        path.pairs.emplace_back(i, j);
    }
    std::reverse(path.pairs.begin(), path.pairs.end());
    return path;
}

VecX warp_from_path(const DtwPath& path, Eigen::Index rows, Eigen::Index cols, double min_slope) {
    if (rows < 2 || cols < 2) throw InvalidArgument("warp_from_path: need at least 2 frames on each side");
    if (!(min_slope > 0.0)) throw InvalidArgument("warp_from_path: min_slope must be positive");
    VecX sum = VecX::Zero(cols), count = VecX::Zero(cols);
    for (const auto& [i, j] : path.pairs) {
        if (i < 0 || i >= rows || j < 0 || j >= cols) throw InvalidArgument("warp_from_path: path leaves the matrix");
        sum[j] += static_cast<double>(i);
        count[j] += 1.0;
    }
    if ((count.array() == 0.0).any()) throw InvalidArgument("warp_from_path: path skips a reference frame");
    VecX w = sum.cwiseQuotient(count);
    // Strictly increasing with a minimum slope, pinned at both ends: raise from the left, then pull
    // down from the right so the end stays at rows − 1 (feasible while (cols − 1)·min_slope < rows − 1).
    const double last = static_cast<double>(rows - 1);
    const double slope = std::min(min_slope, 0.5 * last / static_cast<double>(cols - 1));
    w[0] = 0.0;
    for (Eigen::Index j = 1; j < cols; ++j) w[j] = std::max(w[j], w[j - 1] + slope);
    w[cols - 1] = last;
    for (Eigen::Index j = cols - 2; j >= 0; --j) w[j] = std::min(w[j], w[j + 1] - slope);
    return w;
}

VecX interpolate(const Eigen::Ref<const VecX>& curve, const Eigen::Ref<const VecX>& x) {
    const Eigen::Index n = curve.size();
    if (n < 1) throw InvalidArgument("interpolate: empty curve");
    VecX out(x.size());
    for (Eigen::Index k = 0; k < x.size(); ++k) {
        const double t = std::clamp(x[k], 0.0, static_cast<double>(n - 1));
        const auto i = std::min<Eigen::Index>(static_cast<Eigen::Index>(t), n - 1);
        const double a = t - static_cast<double>(i);
        out[k] = i + 1 < n ? (1.0 - a) * curve[i] + a * curve[i + 1] : curve[i];
    }
    return out;
}

}  // namespace mocapdb::align
