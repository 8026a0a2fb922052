#include "mocapdb/kriging/reduction.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "mocapdb/core/error.hpp"

namespace mocapdb::kriging {

ReductionResult reduce_samples(const Eigen::Ref<const Eigen::MatrixXd>& coords, const VariogramModel& model,
                               const ReductionOptions& options) {
    if (!(options.tau >= 0.0 && options.tau <= 1.0)) {
        throw InvalidArgument("reduce_samples: tau must be in [0, 1], got " + std::to_string(options.tau));
    }
    if (options.min_samples < 0) throw InvalidArgument("reduce_samples: min_samples must be >= 0");
    KrigingOptions ko = options.kriging;
    ko.duplicates = DuplicatePolicy::Merge;
    ko.reliability = ReliabilityVariance::Paper;  // the downdates below compute the paper's sigma^2
    const Kriging k = Kriging::build(coords, model, ko);
    ReductionResult out;
    out.status = k.status();
    const Eigen::Index n = coords.rows();
    const Eigen::VectorXi& group = k.unique_index();
    const Eigen::Index trend_size =
        (ko.trend == TrendKind::Linear && ko.trend_fit == TrendFit::GLS) ? k.trend_basis().size() : 1;
    const Eigen::Index min_keep =
        std::max<Eigen::Index>(options.min_samples > 0 ? options.min_samples : trend_size + 1, 1);

    std::vector<bool> alive(static_cast<std::size_t>(n), true);
    Eigen::Index remaining = n;
    // 1. Duplicates: every member of a group but the first has reliability 1 while its twin remains.
    std::vector<Eigen::Index> representative(static_cast<std::size_t>(k.unique_points().rows()), -1);
    for (Eigen::Index i = 0; i < n; ++i) {
        auto& r = representative[static_cast<std::size_t>(group(i))];
        if (r < 0) {
            r = i;
            continue;
        }
        if (remaining <= min_keep) break;
        out.max_reliability.push_back(1.0);
        if (1.0 < options.tau) {
            out.stopped_on_threshold = true;
            break;
        }
        out.removed.push_back(i);
        out.removed_reliability.push_back(1.0);
        alive[static_cast<std::size_t>(i)] = false;
        --remaining;
    }
    // 2. Unique points: closed-form LOO reliabilities and rank-one downdates of Wc.
    if (!out.stopped_on_threshold && remaining > min_keep) {
        Eigen::MatrixXd w = k.data_block_inverse();
        const Eigen::MatrixXd& gamma = k.gamma_matrix();
        const double sill = model.total_sill();
        std::vector<Eigen::Index> idx;  // unique index -> original sample index, alive ones
        for (Eigen::Index u = 0; u < static_cast<Eigen::Index>(representative.size()); ++u) {
            idx.push_back(representative[static_cast<std::size_t>(u)]);
        }
        std::vector<Eigen::Index> active(idx.size());
        for (std::size_t a = 0; a < idx.size(); ++a) active[a] = static_cast<Eigen::Index>(a);
        while (true) {
            const auto m = static_cast<Eigen::Index>(active.size());
            double best = -1.0;
            Eigen::Index best_a = -1;
            for (Eigen::Index a = 0; a < m; ++a) {
                const double dii = w(a, a);
                double rho = 0.0;
                if (dii > 0.0 && std::isfinite(dii)) {
                    double gw = 0.0;
                    const Eigen::Index ua = active[static_cast<std::size_t>(a)];
                    for (Eigen::Index b = 0; b < m; ++b) gw += gamma(active[static_cast<std::size_t>(b)], ua) * w(b, a);
                    const double sigma2 = std::max(-gw / dii, 0.0);
                    rho = std::clamp(1.0 - sigma2 / sill, 0.0, 1.0);
                }
                // Ties: the lower original index first, for order invariance up to ties.
                if (rho > best ||
                    (rho == best && idx[static_cast<std::size_t>(active[static_cast<std::size_t>(a)])] <
                                        idx[static_cast<std::size_t>(active[static_cast<std::size_t>(best_a)])])) {
                    best = rho;
                    best_a = a;
                }
            }
            if (remaining <= min_keep || m <= 1) break;
            out.max_reliability.push_back(best);
            if (best < options.tau) {
                out.stopped_on_threshold = true;
                break;
            }
            const Eigen::Index orig = idx[static_cast<std::size_t>(active[static_cast<std::size_t>(best_a)])];
            out.removed.push_back(orig);
            out.removed_reliability.push_back(best);
            alive[static_cast<std::size_t>(orig)] = false;
            --remaining;
            // Downdate: W' = W_{-a,-a} - W_{-a,a} W_{a,-a} / W_aa.
            const double daa = w(best_a, best_a);
            const Eigen::VectorXd col = w.col(best_a);
            Eigen::MatrixXd next(m - 1, m - 1);
            for (Eigen::Index j = 0, jj = 0; j < m; ++j) {
                if (j == best_a) continue;
                for (Eigen::Index i = 0, ii = 0; i < m; ++i) {
                    if (i == best_a) continue;
                    next(ii, jj) = w(i, j) - col(i) * col(j) / daa;
                    ++ii;
                }
                ++jj;
            }
            w = std::move(next);
            active.erase(active.begin() + best_a);
        }
    }
    for (Eigen::Index i = 0; i < n; ++i) {
        if (alive[static_cast<std::size_t>(i)]) out.kept.push_back(i);
    }
    return out;
}

}  // namespace mocapdb::kriging
