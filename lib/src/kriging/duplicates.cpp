#include "duplicates.hpp"

#include <algorithm>
#include <numeric>
#include <vector>

namespace mocapdb::kriging::detail {
namespace {

Eigen::Index find_root(std::vector<Eigen::Index>& parent, Eigen::Index i) {
    while (parent[static_cast<std::size_t>(i)] != i) {
        const auto k = static_cast<std::size_t>(i);
        parent[k] = parent[static_cast<std::size_t>(parent[k])];
        i = parent[k];
    }
    return i;
}

}  // namespace

DuplicateGroups group_duplicates(const Eigen::Ref<const Eigen::MatrixXd>& coords, double tolerance, bool merge) {
    const Eigen::Index n = coords.rows();
    std::vector<Eigen::Index> parent(static_cast<std::size_t>(n));
    std::iota(parent.begin(), parent.end(), Eigen::Index{0});
    const double tol2 = tolerance * tolerance;
    DuplicateGroups g;
    for (Eigen::Index j = 0; j < n; ++j) {
        for (Eigen::Index i = j + 1; i < n; ++i) {
            if ((coords.row(i) - coords.row(j)).squaredNorm() <= tol2) {
                ++g.pairs;
                const Eigen::Index a = find_root(parent, i);
                const Eigen::Index b = find_root(parent, j);
                if (a != b) parent[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
            }
        }
    }
    g.group.resize(n);
    if (merge && g.pairs > 0) {
        std::vector<Eigen::Index> unique_of_root(static_cast<std::size_t>(n), -1);
        std::vector<Eigen::Index> first_member;
        for (Eigen::Index i = 0; i < n; ++i) {
            const Eigen::Index r = find_root(parent, i);
            auto& u = unique_of_root[static_cast<std::size_t>(r)];
            if (u < 0) {
                u = static_cast<Eigen::Index>(first_member.size());
                first_member.push_back(i);
            }
            g.group(i) = static_cast<int>(u);
        }
        const auto m = static_cast<Eigen::Index>(first_member.size());
        g.points.resize(m, coords.cols());
        for (Eigen::Index u = 0; u < m; ++u) g.points.row(u) = coords.row(first_member[static_cast<std::size_t>(u)]);
        g.merged = m < n;
    } else {
        g.points = coords;
        for (Eigen::Index i = 0; i < n; ++i) g.group(i) = static_cast<int>(i);
    }
    g.group_size = Eigen::VectorXd::Zero(g.points.rows());
    for (Eigen::Index i = 0; i < n; ++i) g.group_size(g.group(i)) += 1.0;
    return g;
}

}  // namespace mocapdb::kriging::detail
