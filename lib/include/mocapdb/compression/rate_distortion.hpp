#pragma once
// The compression report's engine: on one aligned set, in one run, the bytes each method
// needs to reach each max joint-error target, measured the same way for all of them
// (eval/joint_error.hpp: forward kinematics, every joint, frame and sample).
//
// Details: docs/headers/compression.md (mocapdb/compression/rate_distortion.hpp).
#include <memory>
#include <string>
#include <vector>

#include "mocapdb/core/progress.hpp"
#include "mocapdb/compression/joint_error.hpp"
#include "mocapdb/tensor/tucker.hpp"

namespace mocapdb::compression {

struct RateRow {
    std::string method;
    double target_cm = 0.0;        ///< 0 for the lossless row
    std::vector<long long> ranks;  ///< Tucker: R1, R2, R3; PCA: k; others: empty
    double setting = 0.0;          ///< zfp tolerance, residual step (in X units), quantization bits
    std::uint64_t bytes = 0;       ///< payload + side information
    double ratio = 0.0;            ///< raw aligned float32 bytes / bytes
    compression::JointErrorStats stats;
    double precompute_s = 0.0;  ///< fitting / encoding at the chosen setting
    double us_per_pose = 0.0;
    std::string access;  ///< "pose" or "stream" (see the header comment)
    bool target_met = true;
};

struct RateOptions {
    std::vector<double> max_cm = {1.0, 0.1};  ///< targets, each > 0
    Eigen::Index parameters = 0;              ///< control parameters per sample (side information)
    int quantization_bits = 12;               ///< tucker+residual: core and basis bits
    bool hooi = true;
    int hooi_iterations = 50;
    /// Called after each row (done = rows finished, total = rows of the report, item = the method
    /// just measured). May be empty.
    ProgressCallback progress;
};

struct RateReport {
    tensor::Dims3 dims{0, 0, 0};
    std::uint64_t raw_bytes = 0;   ///< aligned tensor as float32
    std::uint64_t side_bytes = 0;  ///< charged to every row
    std::vector<RateRow> rows;     ///< raw and lossless rows first, then per target in method order
};

/// poses: the aligned D × T × N pose tensor of `skeleton`. Throws InvalidArgument on bad targets.
RateReport rate_distortion(const Tensor3& poses, std::shared_ptr<const Skeleton> skeleton, const RateOptions& options);

/// Median-of-5 time (µs) to synthesize one pose from the model at full ranks (PoseEvaluator). Each
/// round evaluates 20 000 poses or stops after 0.1 s (at least one pose), so a large model costs
/// about half a second, not minutes.
double time_pose_evaluation(const tensor::TuckerModel& model);

}  // namespace mocapdb::compression
