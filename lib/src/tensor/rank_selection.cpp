#include "mocapdb/tensor/rank_selection.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "hosvd_internal.hpp"
#include "mocapdb/core/error.hpp"
#include "mocapdb/tensor/mode_product.hpp"

namespace mocapdb::tensor {

using detail::fit_from;

namespace {

// tail[r] = sum_{i >= r} s(i), r = 0..size.
std::vector<double> tail_sums(const VecX& s) {
    std::vector<double> t(static_cast<std::size_t>(s.size()) + 1, 0.0);
    for (Eigen::Index i = s.size() - 1; i >= 0; --i)
        t[static_cast<std::size_t>(i)] = t[static_cast<std::size_t>(i) + 1] + s(i);
    return t;
}

void check_spectra(const ModeSpectra& sp, const char* where) {
    for (std::size_t n = 0; n < 3; ++n) {
        if (sp.dims[n] < 1 || sp.squared_sv[n].size() != sp.dims[n]) {
            throw InvalidArgument(std::string(where) +
                                  ": the spectra must hold dims[n] >= 1 values for every mode (mode " +
                                  std::to_string(n) + " has dims " + std::to_string(sp.dims[n]) + " and " +
                                  std::to_string(sp.squared_sv[n].size()) + " values)");
        }
    }
}

Eigen::Index ceil_div(Eigen::Index a, Eigen::Index b) { return (a + b - 1) / b; }

// Every rank <= the product of the other two.
bool consistent(const Ranks& r) { return r[0] <= r[1] * r[2] && r[1] <= r[0] * r[2] && r[2] <= r[0] * r[1]; }

// Largest useful rank of each mode: min(I_n, I_p I_q).
Ranks caps(const Dims3& d) {
    return {std::min(d[0], d[1] * d[2]), std::min(d[1], d[0] * d[2]), std::min(d[2], d[0] * d[1])};
}

RankSelection finish(const Tensor3& a, const HosvdBases& bases, TuckerModel model, RankCriterion criterion,
                     double target) {
    RankSelection s;
    s.ranks = model.ranks;
    s.criterion = criterion;
    s.target = target;
    const double norm = std::sqrt(bases.spectra.squared_norm);
    s.bound_relative = norm > 0.0 ? hosvd_error_bound(bases.spectra, s.ranks) / norm : 0.0;
    s.measured_relative = relative_error(a, model);
    s.parameters = tucker_parameter_count(bases.spectra.dims, s.ranks);
    s.compression_ratio = tucker_compression_ratio(bases.spectra.dims, s.ranks);
    s.model = std::move(model);
    return s;
}

}  // namespace

Ranks ranks_for_error_bound(const ModeSpectra& spectra, double target_relative) {
    check_spectra(spectra, "ranks_for_error_bound");
    if (!(target_relative >= 0.0) || !std::isfinite(target_relative)) {
        throw InvalidArgument("ranks_for_error_bound: target_relative must be finite and >= 0, got " +
                              std::to_string(target_relative));
    }
    const Dims3& d = spectra.dims;
    const double budget = target_relative * target_relative * spectra.squared_norm;
    const auto t0 = tail_sums(spectra.squared_sv[0]);
    const auto t1 = tail_sums(spectra.squared_sv[1]);
    const auto t2 = tail_sums(spectra.squared_sv[2]);
    const Ranks cap = caps(d);
    Ranks best = cap;
    Eigen::Index best_params = std::numeric_limits<Eigen::Index>::max();
    double best_bound = std::numeric_limits<double>::infinity();
    for (Eigen::Index r1 = 1; r1 <= cap[0]; ++r1) {
        for (Eigen::Index r2 = 1; r2 <= cap[1]; ++r2) {
            const double rem = budget - t0[static_cast<std::size_t>(r1)] - t1[static_cast<std::size_t>(r2)];
            if (rem < 0.0) continue;
            // Smallest r3 with t2[r3] <= rem (t2 is non-increasing).
            Eigen::Index lo = 1, hi = d[2] + 1;
            while (lo < hi) {
                const Eigen::Index mid = (lo + hi) / 2;
                if (t2[static_cast<std::size_t>(mid)] <= rem) hi = mid;
                else lo = mid + 1;
            }
            Eigen::Index r3 = std::max({lo, ceil_div(r1, r2), ceil_div(r2, r1)});
            if (r3 > cap[2] || r3 > r1 * r2) continue;
            const Ranks r{r1, r2, r3};
            const Eigen::Index p = tucker_parameter_count(d, r);
            const double b =
                t0[static_cast<std::size_t>(r1)] + t1[static_cast<std::size_t>(r2)] + t2[static_cast<std::size_t>(r3)];
            if (p < best_params || (p == best_params && b < best_bound)) {
                best = r;
                best_params = p;
                best_bound = b;
            }
        }
    }
    return best;
}

Ranks ranks_for_compression(const ModeSpectra& spectra, double target_ratio) {
    check_spectra(spectra, "ranks_for_compression");
    if (!(target_ratio > 0.0) || !std::isfinite(target_ratio)) {
        throw InvalidArgument("ranks_for_compression: target_ratio must be finite and > 0, got " +
                              std::to_string(target_ratio));
    }
    const Dims3& d = spectra.dims;
    const double max_params = static_cast<double>(d[0] * d[1] * d[2]) / target_ratio;
    const auto t0 = tail_sums(spectra.squared_sv[0]);
    const auto t1 = tail_sums(spectra.squared_sv[1]);
    const auto t2 = tail_sums(spectra.squared_sv[2]);
    const Ranks cap = caps(d);
    Ranks best{1, 1, 1};
    double best_bound = std::numeric_limits<double>::infinity();
    Eigen::Index best_params = std::numeric_limits<Eigen::Index>::max();
    for (Eigen::Index r1 = 1; r1 <= cap[0]; ++r1) {
        for (Eigen::Index r2 = 1; r2 <= cap[1]; ++r2) {
            const double room = max_params - static_cast<double>(d[0] * r1 + d[1] * r2);
            if (room <= 0.0) continue;
            const double r3_max_real = std::floor(room / static_cast<double>(r1 * r2 + d[2]));
            Eigen::Index r3 =
                static_cast<Eigen::Index>(std::min(r3_max_real, static_cast<double>(std::min(cap[2], r1 * r2))));
            if (r3 < 1 || r3 < ceil_div(r1, r2) || r3 < ceil_div(r2, r1)) continue;
            const Ranks r{r1, r2, r3};
            const Eigen::Index p = tucker_parameter_count(d, r);
            if (static_cast<double>(p) > max_params) continue;
            const double b =
                t0[static_cast<std::size_t>(r1)] + t1[static_cast<std::size_t>(r2)] + t2[static_cast<std::size_t>(r3)];
            if (b < best_bound || (b == best_bound && p < best_params)) {
                best = r;
                best_bound = b;
                best_params = p;
            }
        }
    }
    return best;
}

Ranks ranks_for_tolerance(const ModeSpectra& spectra, double tolerance) {
    check_spectra(spectra, "ranks_for_tolerance");
    if (!(tolerance >= 0.0 && tolerance < 1.0)) {
        throw InvalidArgument("ranks_for_tolerance: tolerance must be in [0, 1), got " + std::to_string(tolerance));
    }
    Ranks r{1, 1, 1};
    for (std::size_t n = 0; n < 3; ++n) {
        const VecX& s = spectra.squared_sv[n];
        const double threshold = tolerance * tolerance * s(0);
        Eigen::Index count = 0;
        for (Eigen::Index i = 0; i < s.size(); ++i) {
            if (s(i) > threshold) ++count;
        }
        r[n] = std::max<Eigen::Index>(1, count);
    }
    return r;
}

RankSelection select_ranks(const Tensor3& a, const Ranks& ranks) {
    check_tensor(a, "select_ranks");
    check_ranks(dims_of(a), ranks, "select_ranks");
    const HosvdBases b = hosvd_bases(a);
    return finish(a, b, hosvd_from_bases(a, b, ranks), RankCriterion::Explicit, 0.0);
}

RankSelection select_ranks_for_error(const Tensor3& a, double target_relative, bool refine_by_measurement) {
    check_tensor(a, "select_ranks_for_error");
    const HosvdBases b = hosvd_bases(a);
    const Ranks rb = ranks_for_error_bound(b.spectra, target_relative);
    TuckerModel model = hosvd_from_bases(a, b, rb);
    const double norm2 = b.spectra.squared_norm;
    const double budget = target_relative * target_relative * norm2;
    if (refine_by_measurement) {
        // P(i, j, k): energy of the core block [0, i) x [0, j) x [0, k); the HOSVD at a prefix (i, j, k)
        // has squared error norm2 - P(i, j, k).
        const Eigen::Index n0 = rb[0] + 1, n1 = rb[1] + 1, n2 = rb[2] + 1;
        std::vector<double> p(static_cast<std::size_t>(n0 * n1 * n2), 0.0);
        auto at = [&](Eigen::Index i, Eigen::Index j, Eigen::Index k) -> double& {
            return p[static_cast<std::size_t>(i + n0 * (j + n1 * k))];
        };
        for (Eigen::Index k = 1; k < n2; ++k) {
            for (Eigen::Index j = 1; j < n1; ++j) {
                for (Eigen::Index i = 1; i < n0; ++i) {
                    const double g = model.core(i - 1, j - 1, k - 1);
                    at(i, j, k) = g * g + at(i - 1, j, k) + at(i, j - 1, k) + at(i, j, k - 1) - at(i - 1, j - 1, k) -
                                  at(i - 1, j, k - 1) - at(i, j - 1, k - 1) + at(i - 1, j - 1, k - 1);
                }
            }
        }
        Ranks best = rb;
        Eigen::Index best_params = tucker_parameter_count(b.spectra.dims, rb);
        for (Eigen::Index k = 1; k < n2; ++k) {
            for (Eigen::Index j = 1; j < n1; ++j) {
                for (Eigen::Index i = 1; i < n0; ++i) {
                    const Ranks r{i, j, k};
                    if (!consistent(r) || norm2 - at(i, j, k) > budget) continue;
                    const Eigen::Index pc = tucker_parameter_count(b.spectra.dims, r);
                    if (pc < best_params) {
                        best = r;
                        best_params = pc;
                    }
                }
            }
        }
        if (best != rb) {
            model = truncate(model, best);
            model.fit = fit_from(norm2, squared_norm(model.core));
            model.fit_history = {model.fit};
            model.error_bound = hosvd_error_bound(b.spectra, best);
        }
    }
    RankSelection s = finish(a, b, std::move(model), RankCriterion::TargetError, target_relative);
    s.target_met = s.measured_relative <= target_relative + 1e-12;
    return s;
}

RankSelection select_ranks_for_compression(const Tensor3& a, double target_ratio) {
    check_tensor(a, "select_ranks_for_compression");
    const HosvdBases b = hosvd_bases(a);
    const Ranks r = ranks_for_compression(b.spectra, target_ratio);
    RankSelection s = finish(a, b, hosvd_from_bases(a, b, r), RankCriterion::TargetCompression, target_ratio);
    s.target_met = s.compression_ratio >= target_ratio;
    return s;
}

RankSelection select_ranks_for_tolerance(const Tensor3& a, double tolerance) {
    check_tensor(a, "select_ranks_for_tolerance");
    const HosvdBases b = hosvd_bases(a);
    const Ranks r = ranks_for_tolerance(b.spectra, tolerance);
    return finish(a, b, hosvd_from_bases(a, b, r), RankCriterion::Tolerance, tolerance);
}

}  // namespace mocapdb::tensor
