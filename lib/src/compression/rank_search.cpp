#include "mocapdb/compression/rank_search.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <string>

#include "mocapdb/core/error.hpp"
#include "mocapdb/tensor/rank_selection.hpp"
#include "truncation_reconstruction.hpp"

namespace mocapdb::compression {
namespace {

// The bisection's grid: log e over [log 1e-7, 0], halved until the interval is 0.01 wide (at most
// 28 steps); its number of steps is known up front.
double log_error_low() { return std::log(1e-7); }
constexpr double kLogErrorResolution = 0.01;

std::uint64_t bisection_steps() {
    return static_cast<std::uint64_t>(
        std::min(28.0, std::ceil(std::log2((0.0 - log_error_low()) / kLogErrorResolution))));
}

// One bisection over log e: decide(ranks) says whether the model at ranks_for_error_bound(e) counts
// as meeting the target. Returns the passing triple with the fewest parameters (of equal ones, the
// later), or nothing when no probe passed. step(i) is called before step i.
template <class Decide, class Step>
std::optional<tensor::Ranks> bisection(const tensor::ModeSpectra& spectra, Decide decide, Step step) {
    std::optional<tensor::Ranks> best;
    Eigen::Index best_parameters = 0;
    double lo = log_error_low(), hi = 0.0;  // lo: known to meet (or assumed: finer than full-rank rounding)
    tensor::Ranks last{-1, -1, -1};
    bool last_ok = false;
    for (int i = 0; i < 28 && hi - lo > kLogErrorResolution; ++i) {
        step(static_cast<std::uint64_t>(i));
        const double mid = 0.5 * (lo + hi);
        const tensor::Ranks ranks = tensor::ranks_for_error_bound(spectra, std::exp(mid));
        if (ranks == last) {  // same triple as the previous probe: its answer is known
            (last_ok ? lo : hi) = mid;
            continue;
        }
        last = ranks;
        last_ok = decide(ranks);
        if (last_ok) {
            lo = mid;
            const Eigen::Index parameters = tensor::tucker_parameter_count(spectra.dims, ranks);
            if (!best || parameters <= best_parameters) {
                best = ranks;
                best_parameters = parameters;
            }
        } else {
            hi = mid;
        }
    }
    return best;
}

// The HOSVD model at ranks from the core at the bases' full ranks (projected once): a block of it,
// or a projection of X for sample ranks beyond the sample basis' columns.
SetModel model_at(const PreparedSet& p, const Tensor3& full_core, const tensor::Ranks& ranks) {
    SetModel m;
    m.mean = p.mean;
    m.weight = p.weight;
    m.tucker = ranks[2] <= full_core.dimension(2) ? tensor::hosvd_from_core(p.bases, full_core, ranks)
                                                  : tensor::hosvd_from_bases(p.weighted(), p.bases, ranks);
    return m;
}

// The core at the bases' full ranks: the bases' factored core when the projected path made one, else
// projected into `computed`.
const Tensor3& core_at_full_ranks(const PreparedSet& p, Tensor3& computed) {
    if (p.bases.factored_core.size() > 0) return p.bases.factored_core;
    computed = tensor::hosvd_full_core(p.weighted(), p.bases);
    return computed;
}

template <class Reconstruction>
SampleApproximation samples_of(const Reconstruction& approx) {
    return [&approx](const std::vector<Eigen::Index>& ids, MatX& out) { approx(ids, out); };
}

// The chosen model's errors, sample by sample (no D x T x N reconstruction).
JointErrorStats measure_model(const JointErrorMeter& meter, const SetModel& m) {
    const SampleReconstruction approx(m);
    return *meter.measure_within(samples_of(approx), std::numeric_limits<double>::infinity());
}

// The reconstruction of the model at ranks: from a block of the full core and the bases' leading
// columns (no copy of the core block, nor of the N x R3 sample basis: 0.29 GB at 11 070 windows),
// or from a model of its own (`holder`) for sample ranks beyond the full core.
const SampleReconstruction& reconstruction_at(const PreparedSet& p, const Tensor3& full_core,
                                              const tensor::Ranks& ranks, std::optional<SetModel>& holder,
                                              std::optional<SampleReconstruction>& reconstruction) {
    if (ranks[2] <= full_core.dimension(2)) {
        reconstruction.emplace(full_core, ranks, p.bases.U[0], p.bases.U[1], p.bases.U[2], p.mean, p.weight);
    } else {
        holder = model_at(p, full_core, ranks);
        reconstruction.emplace(*holder);
    }
    return *reconstruction;
}

// What the search chose: the model is made from it afterwards, from the prepared set or by taking it.
struct Choice {
    tensor::Ranks ranks{};
    JointErrorStats stats;
    bool target_met = false;
    int evaluations = 0, full_checks = 0, truncation_checks = 0;
};

RankSearchResult result_of(const Choice& c, SetModel model) {
    RankSearchResult r;
    r.model = std::move(model);
    r.stats = c.stats;
    r.target_met = c.target_met;
    r.evaluations = c.evaluations;
    r.full_checks = c.full_checks;
    r.truncation_checks = c.truncation_checks;
    return r;
}

// Full ranks reproduce the data (up to rounding), so the target is reachable: the bisection assumes
// it and measures them only when no probe met the target (they are the largest model, so any probe
// that meets the target is preferred to them). The sample rank of a D x T x N tensor is at most D T,
// so min(N, D T) sample columns are already full.
tensor::Ranks full_ranks(const PreparedSet& p) {
    const tensor::Dims3 dims = tensor::dims_of(p.weighted());
    return {dims[0], dims[1], std::min(dims[2], dims[0] * dims[1])};
}

// Screened rounds before every probe is checked on every sample (see search_ranks_for_max_error).
constexpr int kScreenedRounds = 3;
// Samples most changed by a probe's sample-mode truncation that join its screen.
constexpr Eigen::Index kTruncationScreen = 32;
// Samples farthest from the mean (largest weighted, centred energy) that join every screen: at 10 000
// windows the one sample a 512-sample screen missed was the 44th farthest of them.
constexpr Eigen::Index kOutlierScreen = 128;
// At most this many of the samples found beyond the target by failed full checks join every screen.
constexpr std::size_t kFoundScreen = 256;

// The indices of the `count` largest entries of `energy` (ties to the smaller index), largest first.
std::vector<Eigen::Index> largest_entries(const VecX& energy, Eigen::Index count) {
    std::vector<Eigen::Index> order(static_cast<std::size_t>(energy.size()));
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<Eigen::Index>(i);
    const auto top = std::min(count, energy.size());
    std::partial_sort(order.begin(), order.begin() + top, order.end(), [&](Eigen::Index a, Eigen::Index b) {
        return energy(a) > energy(b) || (energy(a) == energy(b) && a < b);
    });
    order.resize(static_cast<std::size_t>(top));
    return order;
}

// `spread` evenly spread samples of X and the kOutlierScreen samples with the largest energy, increasing.
std::vector<Eigen::Index> fixed_screen(const Tensor3& x, Eigen::Index spread) {
    const Eigen::Index samples = x.dimension(2);
    std::vector<Eigen::Index> ids;
    for (Eigen::Index i = 0; i < spread; ++i) ids.push_back(i * samples / spread);
    const VecX energy =
        Eigen::Map<const MatX>(x.data(), x.dimension(0) * x.dimension(1), samples).colwise().squaredNorm().transpose();
    const std::vector<Eigen::Index> outliers = largest_entries(energy, kOutlierScreen);
    ids.insert(ids.end(), outliers.begin(), outliers.end());
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
    return ids;
}

// The samples a probe at `ranks` is screened on, increasing: `fixed` (fixed_screen), the samples found beyond the
// target by earlier full checks, and the kTruncationScreen samples with the largest energy in the
// sample-basis columns the probe leaves out (sum over k >= R3 of lambda_k U_sample(n, k)^2: where
// dropping sample columns moves a sample most). Depends only on the bases, the ranks and the earlier
// checks' results, never on the number of threads.
std::vector<Eigen::Index> screen_for(const tensor::HosvdBases& bases, const tensor::Ranks& ranks,
                                     const std::vector<Eigen::Index>& fixed, const std::vector<Eigen::Index>& found) {
    std::vector<Eigen::Index> ids = fixed;
    ids.insert(ids.end(), found.begin(),
               found.begin() + static_cast<std::ptrdiff_t>(std::min(found.size(), kFoundScreen)));
    const MatX& u = bases.U[2];
    const VecX& lambda = bases.spectra.squared_sv[2];
    const Eigen::Index columns = std::min(u.cols(), lambda.size());
    if (ranks[2] < columns) {
        const auto dropped = columns - ranks[2];
        const VecX energy =
            u.middleCols(ranks[2], dropped).array().square().matrix() * lambda.segment(ranks[2], dropped);
        const std::vector<Eigen::Index> moved = largest_entries(energy, kTruncationScreen);
        ids.insert(ids.end(), moved.begin(), moved.end());
    }
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
    return ids;
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

PreparedSet prepare_set_in_place(Tensor3& poses, const VecX& weight) {
    tensor::check_tensor(poses, "prepare_set");
    PreparedSet p;
    p.mean = dof_means(poses);
    p.weight = weight;
    weighted_centred_in_place(poses, p.mean, p.weight);
    p.in_place = &poses;
    p.bases = tensor::hosvd_bases(poses);
    return p;
}

SetModel hosvd_model(const PreparedSet& p, const tensor::Ranks& ranks) {
    SetModel m;
    m.mean = p.mean;
    m.weight = p.weight;
    m.tucker = tensor::hosvd_from_bases(p.weighted(), p.bases, ranks);
    return m;
}

namespace {

void check_max_error_arguments(double max_cm, Eigen::Index screen_samples) {
    if (!(max_cm > 0.0) || !std::isfinite(max_cm))
        throw InvalidArgument("search_ranks_for_max_error: the target must be a finite number of cm > 0, got " +
                              std::to_string(max_cm));
    if (screen_samples < 0)
        throw InvalidArgument("search_ranks_for_max_error: screen_samples must be >= 0, got " +
                              std::to_string(screen_samples));
}

// The search of search_ranks_for_max_error, up to (not including) making the chosen model.
Choice choose_for_max_error(const PreparedSet& p, const Tensor3& full_core, const compression::JointErrorMeter& meter,
                            double max_cm, const ProgressCallback& progress, Eigen::Index screen_samples) {
    const Eigen::Index samples = p.weighted().dimension(2);
    const std::uint64_t steps = bisection_steps();
    std::uint64_t reported = 0;
    const auto report = [&](std::uint64_t done) {
        reported = std::max(reported, done);
        if (progress) progress({reported, steps + 1, "rank search"});
    };
    // Screening pays when the screen is a small part of the set.
    const bool screening = screen_samples > 0 && 4 * screen_samples < samples;
    const std::vector<Eigen::Index> fixed =
        screening ? fixed_screen(p.weighted(), screen_samples) : std::vector<Eigen::Index>{};

    std::set<tensor::Ranks> failed;                     // a joint beyond the target was found
    std::map<tensor::Ranks, JointErrorStats> passed;    // every pose checked: within the target
    std::vector<Eigen::Index> suspects, found, beyond;  // suspects: order only; found: joins screens
    int evaluations = 0, full_checks = 0, truncation_checks = 0;
    for (int round = 0;; ++round) {
        const bool screened = screening && round < kScreenedRounds;
        // Same decision as measure(...).max_cm <= max_cm, sample by sample: a failing probe stops at
        // the first chunk with a joint beyond the target (the samples that failed earlier probes
        // first), a passing one has measured every error of its model on the way. A screened probe
        // only looks at its screen: failing there is failing; passing there is provisional.
        const auto decide = [&](const tensor::Ranks& ranks) {
            if (failed.count(ranks)) return false;
            if (passed.count(ranks)) return true;
            ++evaluations;
            if (screened && detail::TruncationReconstruction::cheaper_than_direct(p.bases, ranks)) {
                ++truncation_checks;
                const detail::TruncationReconstruction approx(p.weighted(), p.bases, ranks, p.mean, p.weight);
                const bool over =
                    meter.exceeds_on(samples_of(approx), screen_for(p.bases, ranks, fixed, found), max_cm, &suspects);
                if (over) failed.insert(ranks);
                return !over;
            }
            std::optional<SetModel> holder;
            std::optional<SampleReconstruction> reconstruction;
            const SampleReconstruction& approx = reconstruction_at(p, full_core, ranks, holder, reconstruction);
            if (screened) {
                const bool over =
                    meter.exceeds_on(samples_of(approx), screen_for(p.bases, ranks, fixed, found), max_cm, &suspects);
                if (over) failed.insert(ranks);
                return !over;
            }
            ++full_checks;
            std::optional<JointErrorStats> stats = meter.measure_within(samples_of(approx), max_cm, &suspects);
            if (!stats) {
                failed.insert(ranks);
                return false;
            }
            passed.emplace(ranks, std::move(*stats));
            return true;
        };
        const std::optional<tensor::Ranks> candidate = bisection(p.bases.spectra, decide, [&](std::uint64_t i) {
            if (round == 0) report(i);
        });
        Choice best;
        if (!candidate) {
            best.ranks = full_ranks(p);
            std::optional<SetModel> holder;
            std::optional<SampleReconstruction> reconstruction;
            best.stats =
                *meter.measure_within(samples_of(reconstruction_at(p, full_core, best.ranks, holder, reconstruction)),
                                      std::numeric_limits<double>::infinity());
            ++evaluations;
        } else {
            best.ranks = *candidate;
            best.target_met = true;
            const auto known = passed.find(*candidate);
            if (known != passed.end()) {
                best.stats = known->second;
            } else {
                // The screen's answer confirmed on every pose; where it was wrong, the samples beyond the
                // target join every screen and the bisection runs again. In the first round, decided
                // first on the cheaper reconstruction where there is one (collecting every sample beyond
                // the target is a full pass either way); the model returned is measured on its own
                // values. A later round's candidate has passed the samples the earlier candidates failed
                // on, and usually holds: a pre-check would be a second full pass (#16: 4.7 s of the
                // 11 070-window set's 30 s search).
                report(steps);
                const auto fail_candidate = [&] {
                    failed.insert(*candidate);
                    for (const Eigen::Index n : beyond)
                        if (std::find(found.begin(), found.end(), n) == found.end()) found.push_back(n);
                };
                ++full_checks;
                if (round == 0 && detail::TruncationReconstruction::cheaper_than_direct(p.bases, *candidate)) {
                    ++truncation_checks;
                    const detail::TruncationReconstruction approx(p.weighted(), p.bases, *candidate, p.mean, p.weight);
                    if (!meter.measure_within(samples_of(approx), max_cm, &suspects, &beyond)) {
                        fail_candidate();
                        continue;
                    }
                }
                std::optional<SetModel> holder;
                std::optional<SampleReconstruction> reconstruction;
                std::optional<JointErrorStats> stats = meter.measure_within(
                    samples_of(reconstruction_at(p, full_core, *candidate, holder, reconstruction)), max_cm, &suspects,
                    &beyond);
                if (!stats) {
                    fail_candidate();
                    continue;
                }
                best.stats = std::move(*stats);
            }
        }
        report(steps);
        best.evaluations = evaluations;
        best.full_checks = full_checks;
        best.truncation_checks = truncation_checks;
        return best;
    }
}

}  // namespace

RankSearchResult search_ranks_for_max_error(const PreparedSet& p, const compression::JointErrorMeter& meter,
                                            double max_cm, const ProgressCallback& progress,
                                            Eigen::Index screen_samples) {
    check_max_error_arguments(max_cm, screen_samples);
    Tensor3 computed_core;
    const Tensor3& full_core = core_at_full_ranks(p, computed_core);
    const Choice c = choose_for_max_error(p, full_core, meter, max_cm, progress, screen_samples);
    RankSearchResult r = result_of(c, model_at(p, full_core, c.ranks));
    if (progress) progress({bisection_steps() + 1, bisection_steps() + 1, "rank search"});
    return r;
}

RankSearchResult search_ranks_for_max_error(PreparedSet&& p, const compression::JointErrorMeter& meter, double max_cm,
                                            const ProgressCallback& progress, Eigen::Index screen_samples) {
    check_max_error_arguments(max_cm, screen_samples);
    Tensor3 computed_core;
    const Tensor3& full_core = core_at_full_ranks(p, computed_core);
    const Choice c = choose_for_max_error(p, full_core, meter, max_cm, progress, screen_samples);
    SetModel m;
    if (c.ranks[2] <= full_core.dimension(2)) {
        m.mean = std::move(p.mean);
        m.weight = std::move(p.weight);
        p.x = Tensor3();
        m.tucker = tensor::hosvd_from_core(std::move(p.bases), full_core, c.ranks);  // full_core is read first
    } else {
        m = model_at(p, full_core, c.ranks);
    }
    p = PreparedSet{};
    RankSearchResult r = result_of(c, std::move(m));
    if (progress) progress({bisection_steps() + 1, bisection_steps() + 1, "rank search"});
    return r;
}

RankSearchResult search_ranks_for_rmse(const PreparedSet& p, const compression::JointErrorMeter& meter, double rmse,
                                       const ProgressCallback& progress) {
    if (!(rmse >= 0.0) || !std::isfinite(rmse))
        throw InvalidArgument("search_ranks_for_rmse: the target must be finite and >= 0, got " + std::to_string(rmse));
    const double count = static_cast<double>(p.weighted().size());
    Tensor3 computed_core;
    const Tensor3& full_core = core_at_full_ranks(p, computed_core);
    int evaluations = 0;
    const std::uint64_t steps = bisection_steps();
    const auto report = [&](std::uint64_t done) {
        if (progress) progress({done, steps + 1, "rank search"});
    };
    const std::optional<tensor::Ranks> candidate = bisection(
        p.bases.spectra,
        [&](const tensor::Ranks& ranks) {
            ++evaluations;
            // ||X - X_hat||^2 = ||X||^2 - ||G||^2 for HOSVD-type models; measured from the fit.
            const tensor::TuckerModel t = model_at(p, full_core, ranks).tucker;
            return t.data_norm * (1.0 - t.fit) / std::sqrt(count) <= rmse;
        },
        report);
    RankSearchResult best;
    if (candidate) {
        best.model = model_at(p, full_core, *candidate);
        best.target_met = true;
        report(steps);
        best.stats = measure_model(meter, best.model);
    } else {
        best.model = model_at(p, full_core, full_ranks(p));
        best.stats = measure_model(meter, best.model);
        ++evaluations;
    }
    best.evaluations = evaluations;
    best.full_checks = 1;
    report(steps + 1);
    return best;
}

RankSearchResult ranks_for_ratio(const PreparedSet& p, const compression::JointErrorMeter& meter, double ratio) {
    if (!(ratio > 0.0) || !std::isfinite(ratio))
        throw InvalidArgument("ranks_for_ratio: the target ratio must be finite and > 0, got " + std::to_string(ratio));
    RankSearchResult r;
    r.model = hosvd_model(p, tensor::ranks_for_compression(p.bases.spectra, ratio));
    r.stats = measure_model(meter, r.model);
    r.target_met = r.model.tucker.compression_ratio() >= ratio;
    r.evaluations = 1;
    r.full_checks = 1;
    return r;
}

}  // namespace mocapdb::compression
