#include "mocapdb/eval/verdicts.hpp"

#include <algorithm>

namespace mocapdb::eval {
namespace {

const MethodSpec* spec_of(const SetResults& r, const std::string& name) {
    for (const auto& m : r.methods)
        if (m.name == name) return &m;
    return nullptr;
}

const LooMethodResult* loo_method(const LooResult& loo, const std::string& name) {
    for (const auto& m : loo.methods)
        if (m.method == name) return &m;
    return nullptr;
}

const ConstraintMethodResult* constraint_method(const ConstraintResult& c, const std::string& name) {
    for (const auto& m : c.methods)
        if (m.method == name) return &m;
    return nullptr;
}

// The lowest value over all methods and over the kriging methods only (the first of equals); `value`
// gives a method's value, empty when it has none. Empty when either has no value.
template <typename F>
std::optional<std::pair<MethodValue, MethodValue>> best_of(const SetResults& r, F value) {
    std::optional<MethodValue> all, kr;
    for (const MethodSpec& spec : r.methods) {
        const std::optional<double> v = value(spec.name);
        if (!v) continue;
        const bool k = spec.is_kriging();
        if (!all || *v < all->value) all = MethodValue{spec.name, *v, k};
        if (k && (!kr || *v < kr->value)) kr = MethodValue{spec.name, *v, true};
    }
    if (!all || !kr) return std::nullopt;
    return std::make_pair(*all, *kr);
}

// Differences within 5 % (or below the metric's resolution) are ties, not losses.
Outcome outcome_of(Metric metric, const MethodValue& best, const MethodValue& kriging) {
    if (!best.kriging &&
        (kriging.value - best.value <= 0.05 * kriging.value || kriging.value - best.value <= tie_floor(metric)))
        return Outcome::Tie;
    return best.kriging ? Outcome::KrigingWins : Outcome::Loses;
}

EdgeSplit split_of(const SetResults& r, const MethodValue& best, const MethodValue& kriging, bool pose) {
    const LooMethodResult* base = loo_method(r.loo, best.method);
    const LooMethodResult* kr = loo_method(r.loo, kriging.method);
    const std::vector<bool> edge = edge_samples(*r.set);
    const VecX& bv = pose ? base->sample_pose_mean_cm : base->sample_mean_cm;
    const VecX& kv = pose ? kr->sample_pose_mean_cm : kr->sample_mean_cm;
    EdgeSplit s;
    s.best_edge = split_mean(r.loo, bv, edge, true, s.edge_samples);
    s.best_interior = split_mean(r.loo, bv, edge, false, s.interior_samples);
    s.kriging_edge = split_mean(r.loo, kv, edge, true, s.edge_samples);
    s.kriging_interior = split_mean(r.loo, kv, edge, false, s.interior_samples);
    const bool edge_loss = s.edge_samples > 0 && s.kriging_edge > s.best_edge;
    const bool interior_loss = s.interior_samples > 0 && s.kriging_interior > s.best_interior;
    if (edge_loss && interior_loss)
        s.location = s.kriging_edge - s.best_edge > s.kriging_interior - s.best_interior
                         ? LossLocation::BothMoreAtEdge
                         : LossLocation::BothMoreInterior;
    else if (interior_loss) s.location = LossLocation::InteriorOnly;
    else if (edge_loss) s.location = LossLocation::EdgeOnly;
    return s;
}

SetVerdicts judge_set(const SetResults& r, Verdicts& totals) {
    SetVerdicts out;
    out.results = &r;
    auto add = [&](Metric metric, const std::optional<std::pair<MethodValue, MethodValue>>& b) -> MetricVerdict* {
        if (!b) return nullptr;
        MetricVerdict v;
        v.metric = metric;
        v.best = b->first;
        v.best_kriging = b->second;
        v.outcome = outcome_of(metric, v.best, v.best_kriging);
        if (v.best.value > 0.0) v.kriging_worse_percent = 100.0 * (v.best_kriging.value - v.best.value) / v.best.value;
        ++totals.comparisons;
        if (v.outcome == Outcome::Tie) ++totals.ties;
        if (v.outcome == Outcome::Loses) ++totals.losses;
        out.metrics.push_back(v);
        return &out.metrics.back();
    };
    if (r.has_loo) {
        const LooResult& loo = r.loo;
        auto loo_value = [&](auto field) {
            return [&loo, field](const std::string& n) -> std::optional<double> {
                const LooMethodResult* m = loo_method(loo, n);
                if (!m) return std::nullopt;
                return field(*m);
            };
        };
        if (MetricVerdict* v = add(Metric::LooPoseMean,
                                   best_of(r, loo_value([](const LooMethodResult& m) { return m.pose_mean_cm; }))))
            if (!v->best.kriging) v->split = split_of(r, v->best, v->best_kriging, true);
        add(Metric::LooPoseMax, best_of(r, loo_value([](const LooMethodResult& m) { return m.pose_max_cm; })));
        if (MetricVerdict* v =
                add(Metric::LooMotionMean, best_of(r, loo_value([](const LooMethodResult& m) { return m.mean_cm; }))))
            if (!v->best.kriging) v->split = split_of(r, v->best, v->best_kriging, false);
        add(Metric::LooMotionMax, best_of(r, loo_value([](const LooMethodResult& m) { return m.max_cm; })));
        add(Metric::LooDuration,
            best_of(r, loo_value([](const LooMethodResult& m) { return mean_if_any(m.duration_error_s); })));
        if (loo.original_skating_cm_per_s.size())
            add(Metric::FootSkating,
                best_of(r, loo_value([](const LooMethodResult& m) { return mean_if_any(m.skating_cm_per_s); })));
    }
    if (r.has_constraint && !r.constraint_options.thresholds.empty()) {
        const ConstraintResult& c = r.constraint;
        const double lowest = r.constraint_options.thresholds.back();
        if (MetricVerdict* v =
                add(Metric::ConstraintReliableRmse, best_of(r, [&](const std::string& n) -> std::optional<double> {
                        const ConstraintMethodResult* m = constraint_method(c, n);
                        if (!m || m->regions.empty() || m->regions.back().points == 0) return std::nullopt;
                        return m->regions.back().rmse;
                    })))
            v->threshold = lowest;
        add(Metric::ConstraintRmse, best_of(r, [&](const std::string& n) -> std::optional<double> {
                const ConstraintMethodResult* m = constraint_method(c, n);
                if (!m) return std::nullopt;
                return m->all.rmse;
            }));
    }
    if (r.has_compression) {
        for (double t : r.compression_targets) {
            const compression::RateRow* tucker = nullptr;
            const compression::RateRow* best = nullptr;
            for (const auto& row : r.compression.rows) {
                if (row.target_cm != t || !row.target_met) continue;
                if (row.method == "tucker") tucker = &row;
                if (!best || row.ratio > best->ratio) best = &row;
            }
            if (!tucker || !best) continue;
            ++totals.comparisons;
            CompressionVerdict v{t, *tucker, *best, best->method.rfind("tucker", 0) == 0};
            if (!v.tucker_wins) ++totals.losses;
            out.compression.push_back(v);
        }
    }
    return out;
}

}  // namespace

double tie_floor(Metric metric) {
    switch (metric) {
        case Metric::LooPoseMean:
        case Metric::LooPoseMax:
        case Metric::LooMotionMean:
        case Metric::LooMotionMax: return 0.1;
        case Metric::LooDuration: return 0.01;
        case Metric::FootSkating: return 0.2;
        case Metric::ConstraintReliableRmse:
        case Metric::ConstraintRmse: return 0.01;
    }
    return 0.01;
}

Verdicts judge(const EvalResults& e) {
    Verdicts out;
    for (const SetResults& r : e.sets) out.sets.push_back(judge_set(r, out));
    if (e.runtime.empty()) return out;
    RuntimeVerdicts v;
    for (const auto& row : e.runtime) v.samples = std::max(v.samples, row.samples);
    const SetResults* rs = nullptr;
    for (const auto& r : e.sets)
        if (r.set->spec.name == e.runtime_set) rs = &r;
    auto kriging = [&](const std::string& method) {
        const MethodSpec* spec = rs ? spec_of(*rs, method) : nullptr;
        return spec && spec->is_kriging();
    };
    auto baseline = [&](const std::string& method) {
        const MethodSpec* spec = rs ? spec_of(*rs, method) : nullptr;
        return spec && !spec->is_kriging();
    };
    for (const auto& row : e.runtime) {
        if (row.samples != v.samples) continue;
        if (!v.fastest_build || row.build_seconds < v.fastest_build->build_seconds) v.fastest_build = row;
        if (!v.fastest_synthesis || row.synth_us_per_frame < v.fastest_synthesis->synth_us_per_frame)
            v.fastest_synthesis = row;
        if (kriging(row.method) &&
            (!v.slowest_kriging_build || row.build_seconds > v.slowest_kriging_build->build_seconds))
            v.slowest_kriging_build = row;
        if (kriging(row.method) &&
            (!v.fastest_kriging_build || row.build_seconds < v.fastest_kriging_build->build_seconds))
            v.fastest_kriging_build = row;
    }
    if (v.fastest_build && v.slowest_kriging_build) {
        ++out.comparisons;
        v.build_loses = baseline(v.fastest_build->method);
        if (v.build_loses) ++out.losses;
    }
    if (v.fastest_synthesis) {
        ++out.comparisons;
        v.synthesis_loses = baseline(v.fastest_synthesis->method);
        if (v.synthesis_loses) ++out.losses;
    }
    out.runtime = v;
    return out;
}

std::vector<bool> edge_samples(const EvalSet& s) {
    const MatX& p = s.set.parameters;
    std::vector<bool> out(static_cast<std::size_t>(p.rows()), false);
    for (Eigen::Index c = 0; c < p.cols(); ++c) {
        const double lo = p.col(c).minCoeff(), hi = p.col(c).maxCoeff();
        for (Eigen::Index i = 0; i < p.rows(); ++i)
            if (p(i, c) == lo || p(i, c) == hi) out[static_cast<std::size_t>(i)] = true;
    }
    return out;
}

double split_mean(const LooResult& loo, const VecX& v, const std::vector<bool>& edge, bool on_edge, int& count) {
    double sum = 0.0;
    count = 0;
    for (std::size_t k = 0; k < loo.samples.size(); ++k)
        if (edge[static_cast<std::size_t>(loo.samples[k])] == on_edge) {
            sum += v(static_cast<Eigen::Index>(k));
            ++count;
        }
    return count ? sum / count : 0.0;
}

std::vector<std::optional<double>> gain_over_trend(const SetResults& r) {
    double trend_pose = 0.0;
    for (std::size_t k = 0; k < r.loo.methods.size() && k < r.methods.size(); ++k)
        if (r.methods[k].kind == MethodKind::TrendOnly) trend_pose = r.loo.methods[k].pose_mean_cm;
    std::vector<std::optional<double>> out(r.loo.methods.size());
    if (trend_pose > 0.0)
        for (std::size_t k = 0; k < out.size(); ++k) out[k] = 1.0 - r.loo.methods[k].pose_mean_cm / trend_pose;
    return out;
}

std::vector<std::pair<double, double>> error_by_reliability(const ConstraintMethodResult& m, int bins) {
    std::vector<std::pair<double, double>> out;
    const double width = 1.0 / bins;
    for (int b = 0; b < bins; ++b) {
        double sum = 0.0;
        int n = 0;
        for (Eigen::Index q = 0; q < m.reliability.size(); ++q) {
            const int bin = std::min(bins - 1, static_cast<int>(m.reliability(q) * static_cast<double>(bins)));
            if (bin == b && m.valid[static_cast<std::size_t>(q)]) {
                sum += m.error(q);
                ++n;
            }
        }
        if (n > 0) out.emplace_back(width * b + 0.5 * width, sum / n);
    }
    return out;
}

std::vector<std::pair<double, double>> parameter_ranges(const EvalSet& s) {
    std::vector<std::pair<double, double>> out;
    const MatX& p = s.set.parameters;
    for (Eigen::Index c = 0; c < p.cols(); ++c) out.emplace_back(p.col(c).minCoeff(), p.col(c).maxCoeff());
    return out;
}

std::pair<double, double> duration_range(const EvalSet& s) {
    VecX durations(s.size());
    for (Eigen::Index i = 0; i < s.size(); ++i) durations(i) = s.samples[static_cast<std::size_t>(i)].duration();
    return {durations.minCoeff(), durations.maxCoeff()};
}

bool keeps_full_sample_rank(const MethodSpec& m, const EvalSet& s) {
    return m.kind == MethodKind::TuckerKriging && m.ranks[2] >= s.size() - 1;
}

ReductionAtTau reduction_at_tau(const SetResults& r) {
    if (r.reduction.max_reliability.empty()) return ReductionAtTau::NoCurve;
    return r.reduction.max_reliability.front() < r.reduction_options.tau ? ReductionAtTau::NothingRemoved
                                                                         : ReductionAtTau::SomeRemoved;
}

std::optional<double> mean_if_any(const VecX& values) {
    if (values.size() == 0) return std::nullopt;
    return values.mean();
}

}  // namespace mocapdb::eval
