#pragma once
// The evaluation's verdicts ("Where our kriging loses"): for every set and metric, the best
// method overall against the best of the kriging methods, judged a kriging win, a tie (within 5 % or
// the metric's resolution) or a loss to a baseline; per compression target, the best ratio against
// plain Tucker; at the largest runtime size, the fastest preprocessing and synthesis; and the totals.
// Also the measurements the report derives from the results (reliability bins, gain over the trend,
// errors split by samples at the edge of the parameter range). Lower is better for every metric.
// Pure functions of EvalResults (evaluation.hpp); nothing is printed. Threads: no shared state.
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "mocapdb/eval/evaluation.hpp"

namespace mocapdb::eval {

enum class Metric {
    LooPoseMean,             ///< leave-one-out mean pose error (cm)
    LooPoseMax,              ///< leave-one-out max pose error (cm)
    LooMotionMean,           ///< leave-one-out mean motion error (cm)
    LooMotionMax,            ///< leave-one-out max motion error (cm)
    LooDuration,             ///< mean leave-one-out duration error (s)
    FootSkating,             ///< mean foot skating of the synthesized motions (cm/s)
    ConstraintReliableRmse,  ///< constraint RMSE where rho >= the lowest threshold (normalized)
    ConstraintRmse,          ///< constraint RMSE over the whole grid (normalized)
};

/// The resolution below which two values of `metric` tie (0.1 cm, 0.01 s, 0.2 cm/s, 0.01 normalized).
double tie_floor(Metric metric);

enum class Outcome { KrigingWins, Tie, Loses };

struct MethodValue {
    std::string method;
    double value = 0.0;
    bool kriging = false;
};

/// Where a baseline's better leave-one-out mean comes from, by the position of the left-out sample.
enum class LossLocation {
    None,              ///< kriging is not worse on either group
    BothMoreAtEdge,    ///< worse on both, by more on the edge samples
    BothMoreInterior,  ///< worse on both, by more (or as much) on the interior samples
    InteriorOnly,
    EdgeOnly,
};

/// Mean of the per-sample errors over the left-out samples at the edge of the parameter range (a value
/// equal to an axis's min or max) and over the interior ones, for the best method and the best
/// kriging method.
struct EdgeSplit {
    int edge_samples = 0;
    int interior_samples = 0;
    double best_edge = 0.0, best_interior = 0.0;
    double kriging_edge = 0.0, kriging_interior = 0.0;
    LossLocation location = LossLocation::None;
};

struct MetricVerdict {
    Metric metric = Metric::LooPoseMean;
    MethodValue best;          ///< lowest over all methods
    MethodValue best_kriging;  ///< lowest over the kriging methods
    Outcome outcome = Outcome::KrigingWins;
    /// LooPoseMean / LooMotionMean when a baseline is best: the split by sample position.
    std::optional<EdgeSplit> split;
    double threshold = 0.0;  ///< ConstraintReliableRmse: the rho threshold
    /// How much worse the best kriging method is than the best method, in % of the best (empty when the
    /// best value is not positive).
    std::optional<double> kriging_worse_percent;
};

struct CompressionVerdict {
    double target_cm = 0.0;
    compression::RateRow tucker;  ///< plain Tucker's row at the target
    compression::RateRow best;    ///< the highest ratio meeting the target
    bool tucker_wins = false;     ///< the best is a Tucker variant
};

struct SetVerdicts {
    const SetResults* results = nullptr;
    std::vector<MetricVerdict> metrics;           ///< in the order of Metric, the ones that apply
    std::vector<CompressionVerdict> compression;  ///< per target with both rows
};

/// At the largest training size of the runtime study.
struct RuntimeVerdicts {
    Eigen::Index samples = 0;
    std::optional<RuntimeRow> fastest_build, fastest_kriging_build, slowest_kriging_build, fastest_synthesis;
    bool build_loses = false;      ///< the fastest build is a baseline's (judged when a kriging build exists)
    bool synthesis_loses = false;  ///< the fastest synthesis is a baseline's
};

struct Verdicts {
    std::vector<SetVerdicts> sets;
    std::optional<RuntimeVerdicts> runtime;  ///< when the runtime study has rows
    int comparisons = 0;
    int losses = 0;
    int ties = 0;
};

Verdicts judge(const EvalResults& results);

/// Samples on the edge of the parameter range (a value equal to the min or max of some axis).
std::vector<bool> edge_samples(const EvalSet& set);

/// Mean of the per-sample errors `values` (one per left-out sample of `loo`) over the edge (`edge`) or
/// interior samples; `count` is set to how many; 0 without any.
double split_mean(const LooResult& loo, const VecX& values, const std::vector<bool>& edge, bool on_edge, int& count);

/// Per method of `results.loo`, 1 - its pose mean / the trend-only method's pose mean; empty without a
/// trend-only method with a positive pose mean.
std::vector<std::optional<double>> gain_over_trend(const SetResults& results);

/// The mean error of the valid grid points per reliability bin [b/bins, (b+1)/bins) (rho = 1 in the
/// last): (bin centre, mean error) for the bins holding points.
std::vector<std::pair<double, double>> error_by_reliability(const ConstraintMethodResult& method, int bins = 10);

/// Min and max of every parameter of the set, in order.
std::vector<std::pair<double, double>> parameter_ranges(const EvalSet& set);

/// Shortest and longest sample duration (s).
std::pair<double, double> duration_range(const EvalSet& set);

/// A Tucker method whose sample rank needs every sample direction (R3 >= N - 1).
bool keeps_full_sample_rank(const MethodSpec& method, const EvalSet& set);

/// Whether the greedy reduction removes anything at tau: no curve, nothing removed (already the first
/// sample's leave-one-out reliability is below tau), or some samples removed.
enum class ReductionAtTau { NoCurve, NothingRemoved, SomeRemoved };
ReductionAtTau reduction_at_tau(const SetResults& results);

/// Mean of a per-sample vector, empty when it has no values (for the duration and skating columns).
std::optional<double> mean_if_any(const VecX& values);

}  // namespace mocapdb::eval
