#pragma once
// The documents of `mocapdb gp` (--json): fit, interpolate, sample, and the thesis's experiments
// (artificial data, CMU replicates). `model` is the command's model name ("mohgp", "mohgp3", "moa").
// Formatting only; no I/O. Keys: docs/json.md.
#include <cstddef>
#include <string>
#include <vector>

#include "mocapdb/gp/experiment.hpp"
#include "mocapdb/gp/model_steps.hpp"
#include "mocapdb/gp/motion_data.hpp"
#include "mocapdb_json/json_writer.hpp"

namespace mocapdb::json {

void write_gp_fit(JsonWriter& j, const std::string& model, const gp::MotionData& md, const gp::FitResult& f);
/// `child`: the interpolated child's name.
void write_gp_interpolation(JsonWriter& j, const std::string& model, const gp::MotionData& md, const std::string& child,
                            const gp::ChildInterpolation& c);
/// `files`: the BVH files written (the samples, then the trend).
void write_gp_samples(JsonWriter& j, const std::string& model, const gp::MotionData& md,
                      const std::vector<std::string>& files, const gp::FitResult& f);

/// The artificial-data experiment: its settings and one result per test (`tests`: 1-based numbers).
struct GpArtificialReport {
    std::size_t runs = 0;
    std::size_t q = 0;
    std::string kernel;
    std::vector<std::size_t> tests;
};
void write_gp_artificial(JsonWriter& j, const GpArtificialReport& r, const std::vector<gp::ArtificialResult>& results);

/// The replicate experiment on training and evaluation motions (`all`).
struct GpReplicatesReport {
    int layers = 2;
    std::string test_child;
    std::size_t samples = 0;        ///< synthesized per model
    std::vector<std::string> real;  ///< the evaluation motions' names
};
void write_gp_replicates(JsonWriter& j, const GpReplicatesReport& r, const gp::MotionData& all,
                         const gp::ReplicateExperiment& e);

}  // namespace mocapdb::json
