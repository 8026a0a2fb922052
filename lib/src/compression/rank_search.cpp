#include "mocapdb/compression/rank_search.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include "mocapdb/core/error.hpp"
#include "mocapdb/tensor/rank_selection.hpp"

namespace mocapdb::compression {
namespace {

// A probe's measurement: whether the model meets the target, with the model's errors when the
// check measured them on the way (the max-error check does; see measure_model).
struct ProbeCheck {
    bool met = false;
    std::optional<JointErrorStats> stats;
};

// The chosen model's errors, sample by sample (no D x T x N reconstruction).
JointErrorStats measure_model(const JointErrorMeter& meter, const SetModel& m) {
    const SampleReconstruction approx(m);
    return *meter.measure_within([&](const std::vector<Eigen::Index>& ids, MatX& out) { approx(ids, out); },
                                 std::numeric_limits<double>::infinity());
}

// Bisection over log e ∈ [log e_min, 0] for the largest e whose model satisfies `check` (check(model):
// whether it meets the target). Every probe's core is a block of the core at the bases' full ranks,
// projected once (tensor::hosvd_full_core); ranks beyond the sample basis' columns fall back to
// hosvd_from_bases. Only the chosen model's errors are measured in full.
template <class Check>
RankSearchResult bisect(const PreparedSet& p, const compression::JointErrorMeter& meter, Check check,
                        const ProgressCallback& progress) {
    RankSearchResult best;
    const tensor::Dims3 dims = tensor::dims_of(p.x);
    const Tensor3 full_core = tensor::hosvd_full_core(p.x, p.bases);
    std::optional<JointErrorStats> best_stats;
    tensor::Ranks best_ranks{-1, -1, -1};
    Eigen::Index best_parameters = 0;
    const auto evaluate = [&](const tensor::Ranks& ranks) {
        RankSearchResult r;
        r.model.mean = p.mean;
        r.model.weight = p.weight;
        r.model.tucker = ranks[2] <= full_core.dimension(2) ? tensor::hosvd_from_core(p.bases, full_core, ranks)
                                                            : tensor::hosvd_from_bases(p.x, p.bases, ranks);
        return r;
    };
    // Full ranks reproduce the data (up to rounding), so the target is reachable: the bisection
    // assumes it and measures them only when no probe met the target (they are the largest model,
    // so any probe that meets the target is preferred to them). The sample rank of a D x T x N
    // tensor is at most D T, so min(N, D T) sample columns are already full.
    const tensor::Ranks full{dims[0], dims[1], std::min(dims[2], dims[0] * dims[1])};
    bool found = false;
    int evaluations = 0;
    double lo = std::log(1e-7), hi = 0.0;  // lo: known to meet (or assumed: finer than full-rank rounding)
    tensor::Ranks last{-1, -1, -1};
    bool last_ok = false;
    // Progress in bisection steps: the interval halves each step, so their number is known up front
    // (plus one for measuring the chosen model).
    const auto steps = static_cast<std::uint64_t>(std::min(28.0, std::ceil(std::log2((hi - lo) / 0.01))));
    const auto report = [&](std::uint64_t done) {
        if (progress) progress({done, steps + 1, "rank search"});
    };
    for (int i = 0; i < 28 && hi - lo > 0.01; ++i) {
        report(static_cast<std::uint64_t>(i));
        const double mid = 0.5 * (lo + hi);
        const tensor::Ranks ranks = tensor::ranks_for_error_bound(p.bases.spectra, std::exp(mid));
        if (ranks == last) {  // same triple as the previous probe: its answer is known
            (last_ok ? lo : hi) = mid;
            continue;
        }
        last = ranks;
        RankSearchResult r = evaluate(ranks);
        ProbeCheck c = check(r.model);
        r.target_met = c.met;
        ++evaluations;
        last_ok = r.target_met;
        if (r.target_met) {
            lo = mid;
            if (!found || r.model.tucker.parameter_count() <= best_parameters) {
                best_ranks = ranks;
                best_parameters = r.model.tucker.parameter_count();
                best_stats = std::move(c.stats);
            }
            found = true;
        } else {
            hi = mid;
        }
    }
    if (found) {
        // Rebuilt from the same blocks (bit for bit the probe's model): the search holds one model
        // at a time, not the best one beside each probe's (#16: 0.1 GB at 10 000 windows).
        best = evaluate(best_ranks);
        best.target_met = true;
    } else {
        best = evaluate(full);
        ++evaluations;
    }
    report(steps);
    best.stats = best_stats ? *best_stats : measure_model(meter, best.model);
    best.evaluations = evaluations;
    report(steps + 1);
    return best;
}

}  // namespace

PreparedSet prepare_set(const Tensor3& poses, const VecX& weight) {
    tensor::check_tensor(poses, "prepare_set");
    PreparedSet p;
    p.mean = dof_means(poses);
    p.weight = weight;
    p.x = weighted_centred(poses, p.mean, p.weight);
    p.bases = tensor::hosvd_bases(p.x);
    return p;
}

SetModel hosvd_model(const PreparedSet& p, const tensor::Ranks& ranks) {
    SetModel m;
    m.mean = p.mean;
    m.weight = p.weight;
    m.tucker = tensor::hosvd_from_bases(p.x, p.bases, ranks);
    return m;
}

RankSearchResult search_ranks_for_max_error(const PreparedSet& p, const compression::JointErrorMeter& meter, double max_cm,
                                            const ProgressCallback& progress) {
    if (!(max_cm > 0.0) || !std::isfinite(max_cm))
        throw InvalidArgument("search_ranks_for_max_error: the target must be a finite number of cm > 0, got " +
                              std::to_string(max_cm));
    // Same decision as measure(...).max_cm <= max_cm, sample by sample: a failing probe stops at the
    // first chunk with a joint beyond the target (the samples that failed earlier probes first), a
    // passing one has measured every error of its model on the way.
    std::vector<Eigen::Index> suspects;
    return bisect(p, meter, [&](const SetModel& m) {
        const SampleReconstruction approx(m);
        ProbeCheck c;
        c.stats = meter.measure_within([&](const std::vector<Eigen::Index>& ids, MatX& out) { approx(ids, out); },
                                       max_cm, &suspects);
        c.met = c.stats.has_value();
        return c;
    }, progress);
}

RankSearchResult search_ranks_for_rmse(const PreparedSet& p, const compression::JointErrorMeter& meter, double rmse,
                                       const ProgressCallback& progress) {
    if (!(rmse >= 0.0) || !std::isfinite(rmse))
        throw InvalidArgument("search_ranks_for_rmse: the target must be finite and >= 0, got " + std::to_string(rmse));
    const double count = static_cast<double>(p.x.size());
    return bisect(p, meter, [&](const SetModel& m) {
        // ||X - X_hat||^2 = ||X||^2 - ||G||^2 for HOSVD-type models; measured from the fit.
        const double error = m.tucker.data_norm * (1.0 - m.tucker.fit);
        return ProbeCheck{error / std::sqrt(count) <= rmse, std::nullopt};
    }, progress);
}

RankSearchResult ranks_for_ratio(const PreparedSet& p, const compression::JointErrorMeter& meter, double ratio) {
    if (!(ratio > 0.0) || !std::isfinite(ratio))
        throw InvalidArgument("ranks_for_ratio: the target ratio must be finite and > 0, got " + std::to_string(ratio));
    RankSearchResult r;
    r.model = hosvd_model(p, tensor::ranks_for_compression(p.bases.spectra, ratio));
    r.stats = measure_model(meter, r.model);
    r.target_met = r.model.tucker.compression_ratio() >= ratio;
    r.evaluations = 1;
    return r;
}

}  // namespace mocapdb::compression
