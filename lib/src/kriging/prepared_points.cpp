#include "prepared_points.hpp"

#include <algorithm>
#include <numeric>
#include <string>
#include <vector>

#include "mocapdb/core/error.hpp"

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

// Transitive groups of points within `tolerance` (union-find); fills points, group, duplicate_pairs
// and merged of `out`.
void group_duplicates(const Eigen::Ref<const Eigen::MatrixXd>& coords, double tolerance, bool merge,
                      PreparedPoints& out) {
    const Eigen::Index n = coords.rows();
    std::vector<Eigen::Index> parent(static_cast<std::size_t>(n));
    std::iota(parent.begin(), parent.end(), Eigen::Index{0});
    const double tol2 = tolerance * tolerance;
    out.duplicate_pairs = 0;
    for (Eigen::Index j = 0; j < n; ++j) {
        for (Eigen::Index i = j + 1; i < n; ++i) {
            if ((coords.row(i) - coords.row(j)).squaredNorm() <= tol2) {
                ++out.duplicate_pairs;
                const Eigen::Index a = find_root(parent, i);
                const Eigen::Index b = find_root(parent, j);
                if (a != b) parent[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
            }
        }
    }
    out.group.resize(n);
    out.merged = false;
    if (merge && out.duplicate_pairs > 0) {
        std::vector<Eigen::Index> unique_of_root(static_cast<std::size_t>(n), -1);
        std::vector<Eigen::Index> first_member;
        for (Eigen::Index i = 0; i < n; ++i) {
            const Eigen::Index r = find_root(parent, i);
            auto& u = unique_of_root[static_cast<std::size_t>(r)];
            if (u < 0) {
                u = static_cast<Eigen::Index>(first_member.size());
                first_member.push_back(i);
            }
            out.group(i) = static_cast<int>(u);
        }
        const auto m = static_cast<Eigen::Index>(first_member.size());
        out.points.resize(m, coords.cols());
        for (Eigen::Index u = 0; u < m; ++u) out.points.row(u) = coords.row(first_member[static_cast<std::size_t>(u)]);
        out.merged = m < n;
    } else {
        out.points = coords;
        for (Eigen::Index i = 0; i < n; ++i) out.group(i) = static_cast<int>(i);
    }
    out.group_size = Eigen::VectorXd::Zero(out.points.rows());
    for (Eigen::Index i = 0; i < n; ++i) out.group_size(out.group(i)) += 1.0;
}

}  // namespace

void validate_coords(const char* caller, const Eigen::Ref<const Eigen::MatrixXd>& coords) {
    if (coords.rows() < 1 || coords.cols() < 1) {
        throw InvalidArgument(std::string(caller) + ": coords must be N by P with N >= 1 and P >= 1, got " +
                              std::to_string(coords.rows()) + "x" + std::to_string(coords.cols()));
    }
    if (!coords.allFinite()) throw InvalidArgument(std::string(caller) + ": coords must be finite");
}

PreparedPoints prepare_points(const Eigen::Ref<const Eigen::MatrixXd>& coords, double duplicate_tolerance, bool merge,
                              TrendKind trend, double trend_rank_tolerance) {
    PreparedPoints prepared;
    group_duplicates(coords, duplicate_tolerance, merge, prepared);
    prepared.basis = TrendBasis::build(prepared.points, trend, trend_rank_tolerance);
    return prepared;
}

void expand_to_samples(const Eigen::VectorXi& group, const Eigen::VectorXd& group_size,
                       const Eigen::Ref<const Eigen::MatrixXd>& unique, Eigen::Ref<Eigen::MatrixXd> out) {
    for (Eigen::Index i = 0; i < group.size(); ++i) {
        const Eigen::Index u = group(i);
        out.row(i) = unique.row(u) / group_size(u);
    }
}

}  // namespace mocapdb::kriging::detail
