#pragma once
// The thesis's experiments (Gil López 2017, §5) as library functions, shared by the CLI, the tests and
// the benchmark:
//  - artificial interpolation (§5.1.1): a random generative MOHGP with 3 ICMs per layer, children drawn
//    at 50 inputs on [0, 2π]; one test child observed at 5 random inputs; MOHGP and MOA trained on the
//    other (complete) children; MSE / SMSE / MSLL at the test child's unobserved inputs; 5 validation runs;
//  - interpolation of a held-out replicate of real data (§5.1.2) for several numbers of observed frames;
//  - synthesis (§5.2): new children from each fitted model scored by MCC / MLC against real motions, with
//    a control (artificial: samples of an unrelated generative model; real data: the real motions
//    against each other).
// Training always uses the complete children only (structured likelihood); the test child's observed
// frames enter its posterior, not the fit. Every random choice is seeded: results are reproducible.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "mocapdb/core/progress.hpp"
#include "mocapdb/gp/gp_metrics.hpp"
#include "mocapdb/gp/optimize.hpp"

namespace mocapdb::gp {

/// One row of the thesis's Table 1–3.
struct ArtificialConfig {
    double noise = 0.001;  ///< white-noise variance of the children
    std::size_t outputs = 3;
    std::size_t children = 5;         ///< including the test child
    std::size_t inputs = 50;          ///< on [0, 2π]
    std::size_t observed = 5;         ///< observed inputs of the test child
    std::size_t generator_terms = 3;  ///< ICMs per layer of the generating model
};

/// The nine configurations of the thesis's Tables 1–3 (noise 0.001/0.01/0.1 × (3 outputs, 5 children),
/// (6, 6), (3, 10)).
std::vector<ArtificialConfig> thesis_artificial_configs();

struct ExperimentOptions {
    std::size_t runs = 5;  ///< validation runs
    std::uint64_t seed = 1;
    ModelSpec spec;  ///< model fitted (hierarchical is set per model: MOHGP and MOA)
    FitOptions fit;
    ProgressCallback progress;  ///< done = fits finished
};

/// A random generative MOHGP as in §5.1.1 (RBF ICMs; the child layer's variance below the parent's).
HgpModel artificial_generator(const ArtificialConfig& config, std::uint64_t seed);

/// Draws children from a hierarchical model: g ~ GP(0, K_g), f_r = g + GP(0, K_f), y_r = f_r + noise.
/// Also returns the parent draw when out_parent is given. D by T each.
std::vector<MatX> sample_hierarchy(const HgpModel& truth, const VecX& times, std::size_t children, std::uint64_t seed,
                                   MatX* out_parent = nullptr);

struct ModelRuns {
    std::vector<InterpolationScores> runs;
    MeanStd mse, msll;            ///< over the runs
    std::optional<MeanStd> smse;  ///< over the runs; empty when some run's SMSE is undefined
    double fit_seconds = 0.0;     ///< total
    std::vector<std::string> fit_status;
    void summarize();
};

struct ArtificialResult {
    ArtificialConfig config;
    ModelRuns mohgp, moa;
};

ArtificialResult run_artificial(const ArtificialConfig& config, const ExperimentOptions& options);

/// Interpolation of child `test_child` of complete replicate data for several observed-frame counts.
struct InterpolationRow {
    std::size_t observed = 0;
    ModelRuns mohgp, moa;
};
struct ReplicateInterpolation {
    FitResult mohgp_fit, moa_fit;  ///< fitted once on the children other than the test child
    std::vector<InterpolationRow> rows;
};
ReplicateInterpolation run_replicate_interpolation(const HgpData& data, std::size_t test_child,
                                                   const std::vector<std::size_t>& observed_counts,
                                                   const ExperimentOptions& options);

/// Scores of one model's interpolation of `test_child` given a mask (its observed frames); the truth
/// is the child's values at the unobserved frames.
InterpolationScores score_interpolation(const HgpModel& model, const HgpData& data, std::size_t test_child,
                                        const std::vector<bool>& observed);
/// The same for several masks of one test child (its siblings' share of the posterior computed once when
/// they are complete).
std::vector<InterpolationScores> score_interpolations(const HgpModel& model, const HgpData& data,
                                                      std::size_t test_child,
                                                      const std::vector<std::vector<bool>>& masks);

struct SynthesisResult {
    SynthesisScores mohgp, moa, control;
    FitResult mohgp_fit, moa_fit;
};
/// Fits both models to `training` (complete), draws `samples` children from each and scores them
/// against `real` (D by T each). `control` are motions of an unrelated process (may be empty: then the
/// control scores each real motion against the other real ones, the thesis's Table 18/19 comparison;
/// needs ≥ 2 real motions).
SynthesisResult run_synthesis(const HgpData& training, const std::vector<MatX>& real, const std::vector<MatX>& control,
                              std::size_t samples, const ExperimentOptions& options);

/// §5.2.1: a generator as in §5.1.1 with `config.inputs` inputs (the thesis uses 30); the models are fitted
/// to `config.children` children, scored against 5 further children of the same generator; the control
/// is 5 children of an independently drawn generator.
SynthesisResult run_artificial_synthesis(const ArtificialConfig& config, std::size_t samples,
                                         const ExperimentOptions& options);

}  // namespace mocapdb::gp
