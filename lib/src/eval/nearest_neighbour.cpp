#include "mocapdb/eval/nearest_neighbour.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

#include "mocapdb/core/error.hpp"

namespace mocapdb::eval {

NearestNeighbourBlend::NearestNeighbourBlend(const Eigen::Ref<const Eigen::MatrixXd>& coords,
                                             const NearestNeighbourOptions& options)
    : points_(coords), options_(options) {
    if (coords.rows() < 1 || coords.cols() < 1 || !coords.allFinite())
        throw InvalidArgument("NearestNeighbourBlend: coords must be N by P with N, P >= 1 and finite");
    if (options.k < 1) throw InvalidArgument("NearestNeighbourBlend: k must be >= 1");
    if (!(options.power > 0.0) || !std::isfinite(options.power))
        throw InvalidArgument("NearestNeighbourBlend: power must be positive and finite");
    options_.k = std::min(options.k, coords.rows());
}

void NearestNeighbourBlend::weights(const Eigen::Ref<const Eigen::VectorXd>& c, Eigen::Ref<Eigen::VectorXd> out_weights,
                                    kriging::QueryWorkspace& workspace) const {
    const Eigen::Index n = points_.rows();
    if (c.size() != points_.cols() || out_weights.size() != n || !c.allFinite())
        throw InvalidArgument("NearestNeighbourBlend::weights: c must have P finite values and out_weights N");
    Eigen::VectorXd& d = workspace.tmp;
    d.resize(n);
    for (Eigen::Index i = 0; i < n; ++i) d(i) = (points_.row(i).transpose() - c).norm();
    std::vector<Eigen::Index> order(static_cast<std::size_t>(n));
    std::iota(order.begin(), order.end(), Eigen::Index{0});
    const auto k = static_cast<std::size_t>(options_.k);
    std::partial_sort(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(k), order.end(),
                      [&](Eigen::Index a, Eigen::Index b) { return d(a) < d(b) || (d(a) == d(b) && a < b); });
    out_weights.setZero();
    const double scale = std::max(1.0, d(order[0]));
    int exact = 0;
    for (std::size_t j = 0; j < k; ++j) exact += d(order[j]) <= 1e-12 * scale ? 1 : 0;
    if (exact > 0) {
        for (std::size_t j = 0; j < k; ++j)
            if (d(order[j]) <= 1e-12 * scale) out_weights(order[j]) = 1.0 / exact;
        return;
    }
    double sum = 0.0;
    for (std::size_t j = 0; j < k; ++j) {
        const double w = std::pow(d(order[j]), -options_.power);
        out_weights(order[j]) = w;
        sum += w;
    }
    out_weights /= sum;
}

void NearestNeighbourBlend::weights_batch(const Eigen::Ref<const Eigen::MatrixXd>& queries,
                                          Eigen::Ref<Eigen::MatrixXd> out_weights) const {
    if (queries.cols() != points_.cols() || out_weights.rows() != points_.rows() ||
        out_weights.cols() != queries.rows())
        throw InvalidArgument("NearestNeighbourBlend::weights_batch: queries Q by P, out_weights N by Q");
    kriging::QueryWorkspace ws;
    for (Eigen::Index q = 0; q < queries.rows(); ++q) weights(queries.row(q).transpose(), out_weights.col(q), ws);
}

}  // namespace mocapdb::eval
