#pragma once
// Greedy sample reduction of a stored set as a library step (`mocapdb reduce`, the
// geostatistical paper §5.2): the samples removed one by one while the best-predicted one's
// leave-one-out reliability (with the set's synthesis kernel) stays at or above tau, and storing the
// kept samples as a new set aligned like the original. Nothing is printed.
// Errors: what loading the model throws (InvalidArgument naming the command to run when the set has no
// model or is not aligned), InvalidArgument from reduce_samples on a bad tau, and for storing: fewer than
// 2 kept samples or an existing set without `replace`; StoreError / IoError from the database.
// Threads: reads the database, then (store_reduced_set) writes it; no other writer meanwhile.
#include <filesystem>
#include <string>
#include <vector>

#include "mocapdb/dataset/motion_set.hpp"
#include "mocapdb/kriging/reduction.hpp"
#include "mocapdb/kriging/variogram_model.hpp"

namespace mocapdb::workflow {

struct ReductionRequest {
    std::string set;
    double tau = 0.85;
    Eigen::Index min_samples = 0;  ///< never keep fewer (0: trend size + 1)
    bool naive = false;            ///< the naive model's kernel (no compressed model needed)
};

struct ReductionOutcome {
    MotionSet set;                    ///< the set as stored
    std::vector<std::string> labels;  ///< per sample, "CLIP" or "CLIP:BEGIN-END"
    kriging::ReductionResult result;
    std::string model_kind;          ///< the model whose kernel judged ("tucker", "naive")
    kriging::VariogramModel kernel;  ///< that kernel's variogram
};

ReductionOutcome reduce_set(const std::filesystem::path& db, const ReductionRequest& request);

/// The kept samples of `set` (with their parameters and the repairs of their clips) as a set named
/// `name`; the parameter source is kept.
MotionSet reduced_set(const MotionSet& set, const std::vector<Eigen::Index>& kept, const std::string& name);

/// Stores reduced_set(outcome...) as `name`, aligned with the original's method and frames when the
/// original is aligned (returns whether it was).
bool store_reduced_set(const std::filesystem::path& db, const ReductionOutcome& outcome, const std::string& name,
                       bool replace);

}  // namespace mocapdb::workflow
