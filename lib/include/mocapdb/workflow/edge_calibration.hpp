#pragma once
// rho calibrated on one set so that it warns where a synthesis misses its parameters: requests inside the samples' parameter box and in a shell beyond it are synthesized
// (synthesis_step.hpp), their parameters measured back, and a request misses when a measured parameter
// lies further from the request than tolerance_share x that parameter's SD over the samples, or cannot
// be measured. Three rules flag a request: the prediction variance ratio (SynthesisModel::
// variance_ratio; rho = clamp(1 - ratio, 0, 1)) above a level, enough misses among its nearest
// calibration requests (kept with the thresholds), together flagging at most `false_alarms` of the hits
// inside the box; or a distance beyond the samples' range (in SDs) above the level that then flags
// `detection` of the misses.
// Details: docs/synthesis.md, "When rho warns".
// Errors: InvalidArgument when no parameter of the set is measured back by an extractor (nothing to tell
// a miss by), or for options out of range. Threads: reads the model only. Cost: one synthesis and its
// extractors per probe.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "mocapdb/core/progress.hpp"
#include "mocapdb/dataset/motion_set.hpp"
#include "mocapdb/synthesis/edge_warning.hpp"
#include "mocapdb/synthesis/synthesis_model.hpp"
#include "mocapdb/workflow/synthesis_step.hpp"

namespace mocapdb::workflow {

struct EdgeCalibrationOptions {
    std::size_t inside = 200;       ///< probes drawn uniformly in the samples' box
    std::size_t beyond = 400;       ///< probes moved out of the box along one axis by up to shell_sd SDs
    double shell_sd = 1.0;          ///< > 0
    double tolerance_share = 0.25;  ///< > 0 (the evaluation's hit rule, eval/set_evaluation.hpp)
    /// Share of the probes' misses to flag; in (0, 1]. Above the 90 % asked of the warning, so that it
    /// holds on requests the calibration did not see (measured: docs/synthesis.md).
    double detection = 0.95;
    /// Share of the hits inside the box the variance rule may flag; in [0, 1).
    double false_alarms = 0.05;
    /// k of the vote rule (>= 1): a request's nearest calibration requests whose misses are counted.
    std::size_t neighbours = 5;
    std::uint64_t seed = 1;
};

struct EdgeProbe {
    VecX requested;
    bool inside = false;  ///< within the samples' range on every numeric axis
    double rho = 0.0;
    double variance_ratio = 0.0;  ///< SynthesisModel::variance_ratio
    double beyond_sd = 0.0;       ///< beyond_samples_sd
    bool miss = false;
};

/// Per column of `parameters` (N by P): share x its sample SD (N - 1), none for a constant column.
std::vector<std::optional<double>> sd_tolerance(const MatX& parameters, double share);

/// Per parameter: sd_tolerance of the set's parameters for those an extractor of the set's source
/// measures back; none for the others (a CSV column, a category).
std::vector<std::optional<double>> parameter_tolerance(const MotionSet& set, double tolerance_share);

/// How far c lies beyond the samples' range: the largest over numeric, varying axes of the distance
/// outside [min, max] of the samples in that axis's SD; 0 inside the box. c: P values.
double beyond_samples_sd(const MotionSet& set, const VecX& c);

/// Misses among the warning's `neighbours` calibration requests nearest to c (P values; distance over the
/// numeric, varying axes in the samples' SDs, around the circle on periodic ones; a request of another
/// level of a categorical parameter counts as further than any of the same level). `skip`: a probe row
/// to leave out (a calibration request judged by the others). 0 without stored requests.
std::size_t nearby_misses(const synthesis::EdgeWarning& warning, const MotionSet& set, const VecX& c,
                          std::optional<std::size_t> skip = std::nullopt);

/// |a - b|, around the circle for a periodic parameter (period > 0).
double parameter_distance(double a, double b, double period);

/// The parameters (indices) of `outcome` that miss the request: measured further than their tolerance
/// (on a periodic axis, around the circle), or not measured although they have one.
std::vector<std::size_t> missed_parameters(const SynthOutcome& outcome, const MotionSet& set,
                                           const std::vector<std::optional<double>>& tolerance);

/// options.inside + options.beyond requests (seeded), each synthesized with `model` (the model of `set`)
/// and judged. Categorical axes take a random level. progress (may be empty): after each request, item
/// "reliability calibration".
std::vector<EdgeProbe> edge_probes(const synthesis::SynthesisModel& model, const MotionSet& set,
                                   const EdgeCalibrationOptions& options = {}, const ProgressCallback& progress = {});

struct FlagRates {
    std::size_t misses = 0, flagged_misses = 0;            ///< over every probe
    std::size_t inside_hits = 0, flagged_inside_hits = 0;  ///< probes inside the box that hit
    double detection = 1.0;                                ///< flagged_misses / misses (1 without misses)
    double false_alarms = 0.0;                             ///< flagged_inside_hits / inside_hits
};

/// The probes of `set` a warning flags (EdgeWarning::flags, misses nearby by nearby_misses), counted.
FlagRates flag_rates(const std::vector<EdgeProbe>& probes, const synthesis::EdgeWarning& warning, const MotionSet& set);

/// Keeps the probes' requests and misses in the warning and, for each vote count m of
/// options.neighbours (and for no vote rule): the votes flag the probes at least m of whose nearest other
/// probes missed, within floor(false_alarms x inside hits); the variance ratio then takes what is left of
/// that budget (the smallest ratio above all but that many of the inside hits the votes leave; without
/// inside hits: the largest probed); the distance beyond the samples is just below the one that flags
/// ceil(detection x misses) of the misses together with the other two (at most options.shell_sd: nothing
/// is known beyond the probed shell; 0 when too many inside misses are left). The m flagging the most
/// misses wins (ties: fewer false alarms, then the larger m). detection and false_alarms: those of the
/// probes, each judged by the others.
synthesis::EdgeWarning calibrate_edge_warning(const std::vector<EdgeProbe>& probes, const MotionSet& set,
                                              const EdgeCalibrationOptions& options = {});

}  // namespace mocapdb::workflow
