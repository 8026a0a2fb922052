#include "mocapdb/workflow/edge_calibration.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <random>
#include <string>

#include "mocapdb/core/error.hpp"

namespace mocapdb::workflow {

namespace {

double period_of(const MotionSet& set, std::size_t p) {
    return set.parameter_periods.size() == set.parameters.cols() ? set.parameter_periods(static_cast<Eigen::Index>(p))
                                                                 : 0.0;
}

void check(const EdgeCalibrationOptions& o) {
    if (!(o.shell_sd > 0.0) || !std::isfinite(o.shell_sd))
        throw InvalidArgument("edge calibration: the shell beyond the samples must be a positive number of SDs");
    if (!(o.tolerance_share > 0.0) || !std::isfinite(o.tolerance_share))
        throw InvalidArgument("edge calibration: the tolerance share must be positive");
    if (!(o.detection > 0.0 && o.detection <= 1.0))
        throw InvalidArgument("edge calibration: the detection share must be in (0, 1]");
    if (!(o.false_alarms >= 0.0 && o.false_alarms < 1.0))
        throw InvalidArgument("edge calibration: the false alarm share must be in [0, 1)");
    if (o.inside + o.beyond == 0) throw InvalidArgument("edge calibration: no probes asked for");
    if (o.neighbours == 0) throw InvalidArgument("edge calibration: the vote rule needs at least one neighbour");
}

/// The probes `w` flags, counted; nearby[i]: misses near probe i (nearby_misses).
FlagRates count_flags(const std::vector<EdgeProbe>& probes, const synthesis::EdgeWarning& w,
                      const std::vector<std::size_t>& nearby) {
    FlagRates r;
    for (std::size_t i = 0; i < probes.size(); ++i) {
        const EdgeProbe& p = probes[i];
        const bool flagged = w.flags(p.variance_ratio, p.beyond_sd, nearby[i]);
        if (p.miss) {
            ++r.misses;
            r.flagged_misses += flagged ? 1 : 0;
        } else if (p.inside) {
            ++r.inside_hits;
            r.flagged_inside_hits += flagged ? 1 : 0;
        }
    }
    if (r.misses) r.detection = static_cast<double>(r.flagged_misses) / static_cast<double>(r.misses);
    if (r.inside_hits) r.false_alarms = static_cast<double>(r.flagged_inside_hits) / static_cast<double>(r.inside_hits);
    return r;
}

/// `w` (its probes and vote count set) completed by the variance and distance rules of
/// calibrate_edge_warning, the votes counted from `nearby`; false (w unfinished) when the votes alone flag
/// more inside hits than `budget`.
bool fit_thresholds(synthesis::EdgeWarning& w, const std::vector<EdgeProbe>& probes,
                    const std::vector<std::size_t>& nearby, std::size_t budget, const EdgeCalibrationOptions& options) {
    const auto voted = [&](std::size_t i) { return w.votes > 0 && nearby[i] >= w.votes; };
    std::vector<double> hits;  // inside hits the votes leave
    double largest = 0.0;
    std::size_t voted_hits = 0;
    for (std::size_t i = 0; i < probes.size(); ++i) {
        largest = std::max(largest, probes[i].variance_ratio);
        if (probes[i].miss || !probes[i].inside) continue;
        if (voted(i)) ++voted_hits;
        else hits.push_back(probes[i].variance_ratio);
    }
    if (voted_hits > budget) return false;
    std::sort(hits.begin(), hits.end());
    if (hits.empty()) {
        w.variance_ratio = largest;
    } else {
        const std::size_t allowed = std::min(budget - voted_hits, hits.size() - 1);
        w.variance_ratio = hits[hits.size() - 1 - allowed];
    }
    // The distance rule: the misses the other rules leave, furthest first, until `detection` are flagged.
    std::vector<double> left;
    std::size_t flagged = 0;
    for (std::size_t i = 0; i < probes.size(); ++i)
        if (probes[i].miss) {
            if (probes[i].variance_ratio > w.variance_ratio || voted(i)) ++flagged;
            else left.push_back(probes[i].beyond_sd);
        }
    std::sort(left.begin(), left.end(), std::greater<>());
    const auto need = static_cast<std::size_t>(std::ceil(options.detection * static_cast<double>(w.misses)));
    w.beyond_sd = options.shell_sd;
    if (need > flagged) {
        const std::size_t more = need - flagged;  // <= left.size(), since need <= misses
        w.beyond_sd = std::max(0.0, std::nextafter(left[more - 1], -std::numeric_limits<double>::infinity()));
        w.beyond_sd = std::min(w.beyond_sd, options.shell_sd);
    }
    return true;
}

}  // namespace

std::vector<std::optional<double>> sd_tolerance(const MatX& parameters, double share) {
    std::vector<std::optional<double>> out(static_cast<std::size_t>(parameters.cols()));
    for (Eigen::Index p = 0; p < parameters.cols(); ++p) {
        const VecX c = parameters.col(p).array() - parameters.col(p).mean();
        const double sd =
            parameters.rows() > 1 ? std::sqrt(c.squaredNorm() / static_cast<double>(parameters.rows() - 1)) : 0.0;
        if (sd > 0.0) out[static_cast<std::size_t>(p)] = share * sd;
    }
    return out;
}

std::vector<std::optional<double>> parameter_tolerance(const MotionSet& set, double tolerance_share) {
    std::vector<std::optional<double>> out = sd_tolerance(set.parameters, tolerance_share);
    std::vector<std::string> extracted;
    for (const ParameterExtractor& e : source_extractors(set.parameter_source))
        for (const std::string& n : e.names()) extracted.push_back(n);
    for (std::size_t p = 0; p < out.size(); ++p)
        if (is_categorical(set, p) ||
            std::find(extracted.begin(), extracted.end(), set.parameter_names[p]) == extracted.end())
            out[p].reset();
    return out;
}

double beyond_samples_sd(const MotionSet& set, const VecX& c) {
    const MatX& x = set.parameters;
    if (c.size() != x.cols()) throw InvalidArgument("beyond_samples_sd: c must have one value per parameter");
    const std::vector<std::optional<double>> sd = sd_tolerance(x, 1.0);
    double beyond = 0.0;
    for (Eigen::Index p = 0; p < x.cols(); ++p) {
        if (is_categorical(set, static_cast<std::size_t>(p)) || !sd[static_cast<std::size_t>(p)]) continue;
        const double out = std::max({x.col(p).minCoeff() - c(p), c(p) - x.col(p).maxCoeff(), 0.0});
        beyond = std::max(beyond, out / *sd[static_cast<std::size_t>(p)]);
    }
    return beyond;
}

std::size_t nearby_misses(const synthesis::EdgeWarning& warning, const MotionSet& set, const VecX& c,
                          std::optional<std::size_t> skip) {
    const MatX& q = warning.probe_requests;
    if (warning.neighbours == 0 || q.rows() == 0) return 0;
    if (q.cols() != set.parameters.cols() || c.size() != q.cols() ||
        warning.probe_missed.size() != static_cast<std::size_t>(q.rows()))
        throw InvalidArgument(
            "nearby_misses: the request, the set's parameters and the calibration's requests "
            "must have one value per parameter, and every request a miss flag");
    const std::vector<std::optional<double>> sd = sd_tolerance(set.parameters, 1.0);
    struct Near {
        std::size_t other_levels;  // categorical parameters on another level: further than any distance
        double distance2;
        std::uint8_t missed;
        bool operator<(const Near& o) const {
            return other_levels != o.other_levels ? other_levels < o.other_levels : distance2 < o.distance2;
        }
    };
    std::vector<Near> near;
    near.reserve(static_cast<std::size_t>(q.rows()));
    for (Eigen::Index i = 0; i < q.rows(); ++i) {
        if (skip && *skip == static_cast<std::size_t>(i)) continue;
        Near n{0, 0.0, warning.probe_missed[static_cast<std::size_t>(i)]};
        for (Eigen::Index p = 0; p < q.cols(); ++p) {
            const auto at = static_cast<std::size_t>(p);
            if (is_categorical(set, at)) {
                n.other_levels += q(i, p) != c(p) ? 1 : 0;
            } else if (sd[at]) {
                const double d = parameter_distance(q(i, p), c(p), period_of(set, at)) / *sd[at];
                n.distance2 += d * d;
            }
        }
        near.push_back(n);
    }
    const std::size_t k = std::min(warning.neighbours, near.size());
    std::nth_element(near.begin(), near.begin() + static_cast<std::ptrdiff_t>(k == 0 ? 0 : k - 1), near.end());
    std::size_t misses = 0;
    for (std::size_t i = 0; i < k; ++i) misses += near[i].missed;
    return misses;
}

double parameter_distance(double a, double b, double period) {
    double d = std::abs(a - b);
    if (period > 0.0) {
        d = std::fmod(d, period);
        d = std::min(d, period - d);
    }
    return d;
}

std::vector<std::size_t> missed_parameters(const SynthOutcome& outcome, const MotionSet& set,
                                           const std::vector<std::optional<double>>& tolerance) {
    std::vector<std::size_t> missed;
    for (std::size_t p = 0; p < tolerance.size(); ++p) {
        if (!tolerance[p]) continue;
        const std::optional<double> m =
            p < outcome.parameter_measured.size() ? outcome.parameter_measured[p] : std::nullopt;
        if (!m || !(parameter_distance(*m, outcome.requested(static_cast<Eigen::Index>(p)), period_of(set, p)) <=
                    *tolerance[p]))
            missed.push_back(p);
    }
    return missed;
}

std::vector<EdgeProbe> edge_probes(const synthesis::SynthesisModel& model, const MotionSet& set,
                                   const EdgeCalibrationOptions& options, const ProgressCallback& progress) {
    check(options);
    const std::vector<std::optional<double>> tolerance = parameter_tolerance(set, options.tolerance_share);
    if (std::none_of(tolerance.begin(), tolerance.end(), [](const auto& t) { return t.has_value(); }))
        throw InvalidArgument("set '" + set.name +
                              "': no varying parameter is measured back by an extractor, so a miss cannot be told");
    const MatX& x = set.parameters;
    const Eigen::Index params = x.cols();
    const std::vector<std::optional<double>> sd = sd_tolerance(x, 1.0);
    std::vector<Eigen::Index> numeric;  // axes that vary and are not categorical: where "beyond" exists
    for (Eigen::Index p = 0; p < params; ++p)
        if (!is_categorical(set, static_cast<std::size_t>(p)) && sd[static_cast<std::size_t>(p)]) numeric.push_back(p);
    const VecX lo = x.colwise().minCoeff().transpose(), hi = x.colwise().maxCoeff().transpose();

    std::mt19937_64 rng(options.seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<EdgeProbe> probes;
    probes.reserve(options.inside + options.beyond);
    for (std::size_t k = 0; k < options.inside + options.beyond; ++k) {
        VecX c(params);
        for (Eigen::Index p = 0; p < params; ++p) {
            const auto at = static_cast<std::size_t>(p);
            if (is_categorical(set, at)) {  // a sample's level: every level has samples
                c(p) = x(static_cast<Eigen::Index>(unit(rng) * static_cast<double>(x.rows()) * 0.999999), p);
            } else {
                c(p) = lo(p) + unit(rng) * (hi(p) - lo(p));
            }
        }
        const bool beyond = k >= options.inside && !numeric.empty();
        if (beyond) {  // one numeric axis pushed out of the range, up to shell_sd of its SDs
            const Eigen::Index p = numeric[std::min(
                numeric.size() - 1, static_cast<std::size_t>(unit(rng) * static_cast<double>(numeric.size())))];
            const double out = (1.0 - unit(rng)) * options.shell_sd * *sd[static_cast<std::size_t>(p)];
            c(p) = unit(rng) < 0.5 ? lo(p) - out : hi(p) + out;
        }
        EdgeProbe probe;
        probe.requested = c;
        probe.inside = !beyond;
        const SynthOutcome o = synthesize(model, set, c);
        probe.rho = o.reliability;
        probe.variance_ratio = model.variance_ratio(c);
        probe.beyond_sd = beyond_samples_sd(set, c);
        probe.miss = !missed_parameters(o, set, tolerance).empty();
        probes.push_back(std::move(probe));
        if (progress) progress({k + 1, options.inside + options.beyond, "reliability calibration"});
    }
    return probes;
}

FlagRates flag_rates(const std::vector<EdgeProbe>& probes, const synthesis::EdgeWarning& warning,
                     const MotionSet& set) {
    std::vector<std::size_t> nearby(probes.size());
    for (std::size_t i = 0; i < probes.size(); ++i) nearby[i] = nearby_misses(warning, set, probes[i].requested);
    return count_flags(probes, warning, nearby);
}

synthesis::EdgeWarning calibrate_edge_warning(const std::vector<EdgeProbe>& probes, const MotionSet& set,
                                              const EdgeCalibrationOptions& options) {
    check(options);
    if (probes.empty()) throw InvalidArgument("edge calibration: no probes");
    synthesis::EdgeWarning base;
    base.tolerance_share = options.tolerance_share;
    base.probes = probes.size();
    base.neighbours = options.neighbours;
    base.probe_requests.resize(static_cast<Eigen::Index>(probes.size()), set.parameters.cols());
    std::size_t inside_hits = 0;
    for (std::size_t i = 0; i < probes.size(); ++i) {
        if (probes[i].requested.size() != set.parameters.cols())
            throw InvalidArgument("edge calibration: a probe's request must have one value per parameter of the set");
        base.probe_requests.row(static_cast<Eigen::Index>(i)) = probes[i].requested.transpose();
        base.probe_missed.push_back(probes[i].miss ? 1 : 0);
        base.misses += probes[i].miss ? 1 : 0;
        inside_hits += !probes[i].miss && probes[i].inside ? 1 : 0;
    }
    std::vector<std::size_t> nearby(probes.size());  // each probe judged by the others
    for (std::size_t i = 0; i < probes.size(); ++i) nearby[i] = nearby_misses(base, set, probes[i].requested, i);
    const auto budget = static_cast<std::size_t>(std::floor(options.false_alarms * static_cast<double>(inside_hits)));

    // No vote rule first, then the strictest vote count: a later one must flag more misses, or as many
    // with fewer false alarms.
    std::optional<synthesis::EdgeWarning> best;
    FlagRates best_rates;
    std::vector<std::size_t> counts{0};
    for (std::size_t m = options.neighbours; m >= 1; --m) counts.push_back(m);
    for (const std::size_t m : counts) {
        synthesis::EdgeWarning w = base;
        w.votes = m;
        if (!fit_thresholds(w, probes, nearby, budget, options)) continue;
        const FlagRates r = count_flags(probes, w, nearby);
        if (!best || r.flagged_misses > best_rates.flagged_misses ||
            (r.flagged_misses == best_rates.flagged_misses && r.flagged_inside_hits < best_rates.flagged_inside_hits)) {
            best = std::move(w);
            best_rates = r;
        }
    }
    best->detection = best_rates.detection;
    best->false_alarms = best_rates.false_alarms;
    if (best->votes == 0) {  // no vote rule: nothing to keep but the thresholds
        best->neighbours = 0;
        best->probe_requests.resize(0, 0);
        best->probe_missed.clear();
    }
    return *best;
}

}  // namespace mocapdb::workflow
