#pragma once
// How accurate synthesis is on one set (`mocapdb eval DB --set NAME`): leave-one-out over at most
// max_folds samples (evenly spread), each fold leaving out the sample with its twins
// (dataset/sample_twins.hpp), for naive kriging, RBF, the linear trend alone and, when the set has a
// stored model, Tucker kriging at its ranks; per method the pose / motion error, the parameter hit
// rate (extractor sets) and Pearson(rho, pose error); and the `chosen` predictor of nested
// cross-validation: in each outer fold the choice synthesis makes (synthesis/predictor_choice.hpp, with
// at most inner_folds folds) on that fold's training samples only picks kriging, RBF, the trend or an
// average of them, and the chosen column is the outer error of those picks. Details and definitions: docs/evaluation.md.
// Errors: InvalidArgument naming the set when it has fewer than 5 samples or a fold too few training
// samples; those of load_eval_set. Cost: folds builds of every method, and per fold a kernel fit and inner folds x 3 interpolators.
#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "mocapdb/core/progress.hpp"
#include "mocapdb/dataset/sample_twins.hpp"
#include "mocapdb/eval/loo_prediction.hpp"

namespace mocapdb::eval {

struct SetEvaluationOptions {
    std::size_t max_folds = 40;    ///< outer folds (left-out samples, evenly spread); >= 1
    std::size_t inner_folds = 15;  ///< nested CV: inner folds per outer fold (evenly spread); >= 1
    double hit_share = 0.25;       ///< hit: every |measured - requested| <= hit_share x that parameter's SD
    TwinOptions twins;
    /// Also try the learned-metric kriging (LearnedMetricEvaluation) over the outer folds.
    bool learned_metric = false;
};

/// A kriging whose metric is learned per outer fold from its training samples, as the kernel's shape is:
/// ARD (a length scale per numeric parameter: the normalized axes after the first scaled by a factor of
/// 0.25 .. 4, one axis after the other) or, with one parameter, an input warp (the parameter mapped
/// through sign(u)|u|^a, u its position in the training range on [-1, 1], a = 0.5 .. 2); each candidate
/// metric gets its own kernel fit (synthesis/kernel_fit.hpp) and the lowest closed-form leave-one-out MSE
/// of the weighted sample values wins. An experiment: not a candidate of synthesis's choice.
struct LearnedMetricEvaluation {
    std::string kind;   ///< "ard" or "warp"
    VecX pose_mean_cm;  ///< per outer fold: the left-out sample's pose error (naive model's poses)
    double pose_mean = 0.0;
    std::vector<VecX> factors;  ///< per outer fold: the chosen factor of each axis (ard) or the exponent (warp)
};

struct MethodEvaluation {
    MethodSpec spec;
    LooMethodResult loo;             ///< per outer fold (measured, reliability filled)
    VecX hits;                       ///< per fold 1 / 0 (empty without extractors)
    std::optional<double> hit_rate;  ///< empty without extractors
    /// Pearson(rho, pose error) over the folds; empty without rho, with fewer than 2 folds or when either
    /// is constant.
    std::optional<double> rho_pose_pearson;
};

struct ChosenEvaluation {
    /// Per outer fold: index into methods (kriging, rbf or trend), or methods.size() where the choice averaged
    /// several (synthesis's Average predictor; that fold's errors are then the average's own).
    std::vector<std::size_t> picks;
    std::vector<std::string> pick_names;  ///< per outer fold: the method's name, or "average of kriging+rbf"
    std::vector<std::size_t> counts;      ///< per method: folds that picked it; last (methods.size()): averages
    VecX pose_mean_cm;                    ///< per fold: outer pose error of the pick
    VecX motion_mean_cm;                  ///< per fold: outer motion error of the pick
    double pose_mean = 0.0, motion_mean = 0.0;
    double pose_max = 0.0, motion_max = 0.0;  ///< the largest joint error of the picks' folds (as LooMethodResult)
    std::optional<double> hit_rate;           ///< empty without extractors
    std::size_t best = 0;              ///< the best of kriging, RBF and trend (lowest outer pose mean, in hindsight)
    double diff_mean_cm = 0.0;         ///< mean over folds of (chosen - best) pose error
    std::optional<double> diff_se_cm;  ///< its paired standard error (SD / sqrt(folds)); empty for 1 fold
};

struct SetEvaluation {
    std::string set;
    std::string file;                 ///< the database
    std::vector<std::string> labels;  ///< every sample
    std::vector<Eigen::Index> folds;  ///< left-out samples
    std::size_t inner_folds = 0;      ///< inner folds per outer fold (at most)
    Eigen::Index frames = 0;          ///< aligned frames T
    SampleTwins twins;
    std::vector<std::string> parameter_names;
    std::vector<std::string> parameter_units;
    bool parameters_measured = false;  ///< extractor set: hits measured
    double hit_share = 0.0;            ///< SetEvaluationOptions::hit_share
    /// Per parameter (empty without extractors): hit_share x SD; empty for a constant one or one not
    /// extracted (a CSV column, a category): not checked.
    std::vector<std::optional<double>> hit_tolerance;
    std::vector<MethodEvaluation> methods;
    ChosenEvaluation chosen;
    /// With options.learned_metric, for sets whose parameters are all numeric and linear; empty otherwise.
    std::optional<LearnedMetricEvaluation> learned_metric;
    std::vector<std::string> not_evaluated;  ///< methods left out and why, one line each
};

/// The methods evaluated on a set: naive kriging ("kriging"), "rbf", "trend" and, with ranks (all
/// > 0), Tucker kriging ("tucker").
std::vector<MethodSpec> set_methods(const std::array<std::size_t, 3>& model_ranks);

/// At most `count` of 0 .. n-1, evenly spread (all when count >= n), ascending.
std::vector<Eigen::Index> evenly_spread(Eigen::Index n, std::size_t count);

/// The evaluation of `set` with `methods` (at least one); twins found on the set's samples.
SetEvaluation evaluate_set(const EvalSet& set, const std::vector<MethodSpec>& methods,
                           const SetEvaluationOptions& options = {}, const ProgressCallback& progress = {});

/// The same for a set stored in the database file `db` (read only).
SetEvaluation evaluate_stored_set(const std::filesystem::path& db, const std::string& set,
                                  const SetEvaluationOptions& options = {}, const ProgressCallback& progress = {});

}  // namespace mocapdb::eval
