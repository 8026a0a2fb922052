#pragma once
// Runtime against the number of samples (the geostatistical paper, Tables 1-2): for each method and each
// training size N (the first N samples of an evenly spread order), the preprocessing time (building the
// method: variograms, fits, factorizations, Tucker) and the time to synthesize one whole aligned motion,
// both also per frame. Wall-clock medians over `repeats` runs on the calling thread.
#include <string>
#include <vector>

#include "mocapdb/core/progress.hpp"
#include "mocapdb/eval/eval_set.hpp"
#include "mocapdb/eval/synthesis_method.hpp"

namespace mocapdb::eval {

struct RuntimeRow {
    std::string method;
    Eigen::Index samples = 0;         ///< N
    Eigen::Index frames = 0;          ///< T
    double build_seconds = 0.0;       ///< median preprocessing time
    double build_us_per_frame = 0.0;  ///< build_seconds / (N T), microseconds
    double synth_us_per_frame = 0.0;  ///< median time of one aligned motion / T, microseconds
};

struct RuntimeOptions {
    std::vector<Eigen::Index> sizes;  ///< training sizes (each 3 .. N; empty = 8, 16, 32, ... and N)
    int repeats = 3;                  ///< >= 1 builds per size (median); queries: 5 x repeats
};

std::vector<RuntimeRow> runtime_scaling(const EvalSet& set, const std::vector<MethodSpec>& methods,
                                        const RuntimeOptions& options = {}, const ProgressCallback& progress = {});

}  // namespace mocapdb::eval
