#pragma once
// The documents of synthesis from a stored set: `mocapdb synth`, `query`, `reliability` and `reduce`
// (--json). Each takes the library's outcome and a small struct of what the command adds (names,
// files, timings). Formatting only; no I/O. Keys: docs/json.md.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "mocapdb/core/types.hpp"
#include "mocapdb/motion/skeleton.hpp"
#include "mocapdb/synthesis/predictor_choice.hpp"
#include "mocapdb/tensor/unfold.hpp"
#include "mocapdb/workflow/reliability_map.hpp"
#include "mocapdb/workflow/set_reduction.hpp"
#include "mocapdb/workflow/synthesis_step.hpp"
#include "mocapdb/workflow/synthesis_warnings.hpp"
#include "mocapdb_json/json_writer.hpp"

namespace mocapdb::json {

/// What `mocapdb synth` reports beside the outcome.
struct SynthReport {
    std::string set;
    std::string model;      ///< the model's kind()
    tensor::Ranks ranks{};  ///< at the level synthesized
    std::vector<std::string> parameter_names;
    std::vector<std::string> parameter_units;
    std::vector<std::vector<std::string>> parameter_levels;  ///< MotionSet::parameter_levels (empty: none)
    std::vector<std::string> warnings;
    workflow::SynthesisWarnings judged;  ///< the judgement behind the warnings (threshold, misses)
    double load_s = 0.0;                 ///< loading the set and the model
    double precompute_s = 0.0;
    bool kernel_stored = false;
    long long local_neighbours = 0;  ///< SynthesisReport::local_neighbours (0: exact kriging of all samples)
    std::string predictor;           ///< what blended the samples (synthesis::to_string(Predictor))
    std::optional<synthesis::PredictorChoice> predictor_choice;  ///< the stored cross-validated choice
    std::string output;                                          ///< the BVH file written
};
void write_synthesis(JsonWriter& j, const SynthReport& r, const workflow::SynthOutcome& o);

/// A set's calibrated reliability threshold as one object (the `reliability_warning` of `set show` and
/// `compress`): variance_ratio, rho_threshold, beyond_sd, tolerance_share, probes, misses, detection,
/// false_alarms.
void write_edge_warning(JsonWriter& j, const synthesis::EdgeWarning& w);

/// One pose of `mocapdb query`: as joint positions (3J by 1, cm) or as channels (1 by C).
struct PoseQuery {
    std::string set;
    std::string model;      ///< the model's kind()
    std::string predictor;  ///< what blended the samples (synthesis::to_string(Predictor))
    double frame = 0.0;
    double reliability = 0.0;
    std::vector<std::string> warnings;
    workflow::SynthesisWarnings judged;  ///< the judgement behind the warnings (threshold)
    std::shared_ptr<const Skeleton> skeleton;
    VecX pose;             ///< the pose vector
    bool joints = false;   ///< positions rather than channels
    MatX joint_positions;  ///< with `joints`
    FrameMatrix channels;  ///< without
};
void write_pose_query(JsonWriter& j, const PoseQuery& q);

/// What `mocapdb reliability` reports beside the map.
struct ReliabilityMapReport {
    std::string set;
    std::string model;  ///< the model's kind()
    std::string x;      ///< the parameters of the axes
    std::string y;
    std::string svg;  ///< files written ("csv" only when not empty)
    std::string csv;
};
void write_reliability_map(JsonWriter& j, const ReliabilityMapReport& r, const workflow::ReliabilityMap& m);

/// What `mocapdb reduce` reports beside the outcome.
struct ReductionReport {
    std::string set;
    double tau = 0.0;
    std::optional<std::string> written_set;  ///< with --apply
    double seconds = 0.0;
};
void write_reduction(JsonWriter& j, const ReductionReport& r, const workflow::ReductionOutcome& o);

}  // namespace mocapdb::json
