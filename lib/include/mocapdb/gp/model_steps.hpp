#pragma once
// The steps of `mocapdb gp` as library functions on prepared replicate data
// (motion_data.hpp): fit a model, interpolate a partially observed child from its siblings, sample new
// children around the fitted trend, split data into training children and real motions and run the
// thesis's replicate experiment (experiment.hpp) on them, and the summary of a fitted model that the
// CLI prints. Nothing is printed; progress goes to FitOptions::progress / ExperimentOptions::progress.
// Errors: InvalidArgument on bad indices and counts (stated per function), plus what fit,
// predict_child and sample_children throw. Threads: no shared state.
#include <optional>
#include <vector>

#include "mocapdb/gp/experiment.hpp"
#include "mocapdb/gp/hierarchical_gp.hpp"
#include "mocapdb/gp/optimize.hpp"

namespace mocapdb::gp {

/// initial_model(data, spec) fitted to `data`.
FitResult fit_model(const HgpData& data, const ModelSpec& spec, const FitOptions& options);

struct ChildInterpolation {
    FitResult fit;                  ///< on the other children
    std::vector<bool> observed;     ///< T flags: the child's frames that condition its posterior
    InterpolationScores scores;     ///< at the unobserved frames
    GaussianPrediction prediction;  ///< at every frame, normalized units
};

/// Fits the model to every child but `child`, observes `observed` of the child's frames (chosen by
/// random_observed_frames with `mask_seed`) and predicts the child. InvalidArgument for fewer than 2
/// children, `child` out of range or fewer than 2 frames left to predict.
ChildInterpolation interpolate_child(const HgpData& data, std::size_t child, std::size_t observed,
                                     const ModelSpec& spec, const FitOptions& fit_options, std::uint64_t mask_seed);

struct NewChildren {
    FitResult fit;
    std::vector<MatX> samples;  ///< D by T each, normalized units, at the data's times
    MatX trend;                 ///< synthesis_trend at the data's times
};

/// Fits the model to `data` and draws `count` new children (sample_children with `sample_options`)
/// and the trend they are drawn around.
NewChildren sample_new_children(const HgpData& data, const ModelSpec& spec, const FitOptions& fit_options,
                                std::size_t count, const SampleOptions& sample_options);

/// The first `training` children of `all` as complete training data (its times, no groups) and the
/// rest as the real motions synthesized samples are scored against. InvalidArgument when training
/// exceeds the children.
struct ReplicateSplit {
    HgpData training;
    std::vector<MatX> real;
};
ReplicateSplit split_replicates(const HgpData& all, std::size_t training);

struct ReplicateExperiment {
    ReplicateInterpolation interpolation;
    std::optional<SynthesisResult> synthesis;  ///< when there are real motions
};

/// run_replicate_interpolation of `test_child` for each observed count, and with real motions
/// run_synthesis of `samples` children per model against them (the control: the real motions against
/// each other).
ReplicateExperiment run_replicate_experiment(const HgpData& training, const std::vector<MatX>& real,
                                             std::size_t test_child, const std::vector<std::size_t>& observed_counts,
                                             std::size_t samples, const ExperimentOptions& options);

/// What a fitted model looks like, per layer and term, and its noise.
struct TermSummary {
    KernelType kernel = KernelType::Rbf;
    double lengthscale_s = 0.0;    ///< exp(log_lengthscale)
    double mean_b_diagonal = 0.0;  ///< mean of the coregionalization matrix's diagonal
};
struct ModelSummary {
    std::vector<TermSummary> parent;  ///< empty unless hierarchical
    std::vector<TermSummary> group;   ///< empty unless grouped
    std::vector<TermSummary> child;   ///< the child layer (MOA: the only one)
    double noise_mean = 0.0, noise_min = 0.0, noise_max = 0.0;
};
ModelSummary summarize_model(const HgpModel& model);

}  // namespace mocapdb::gp
