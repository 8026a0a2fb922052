#pragma once
// The interpolation methods the evaluation compares, behind one interface: build on a (training) set,
// then synthesize the motion at control parameters c as D x T aligned poses plus its timing (the warp:
// source frame shown at each aligned frame), and from those a clip at the set's frame rate.
//
// Details: docs/headers/eval.md (mocapdb/eval/synthesis_method.hpp).
#include <memory>
#include <string>
#include <vector>

#include "mocapdb/eval/eval_set.hpp"
#include "mocapdb/eval/nearest_neighbour.hpp"
#include "mocapdb/tensor/tucker.hpp"

namespace mocapdb::eval {

enum class MethodKind {
    PerPoseKriging,
    PerElementKriging,
    TuckerKriging,
    NaiveKriging,
    Rbf,
    NearestNeighbour,
    TrendOnly,
    Average  ///< the mean of the motions of MethodSpec::averaged (synthesis's Average predictor)
};

struct MethodSpec {
    MethodKind kind = MethodKind::PerPoseKriging;
    std::string name;              ///< label in reports (e.g. "tucker-1cm")
    tensor::Ranks ranks{0, 0, 0};  ///< TuckerKriging: (R1, R2, R3), R3 clamped to the training size
    NearestNeighbourOptions nn;    ///< NearestNeighbour
    /// Average: the methods (two or more; not Average) whose synthesized aligned poses and warps are averaged
    /// (the poses as the mean of their weights; the warps of their clamped increments).
    std::vector<MethodKind> averaged;
    bool is_kriging() const {
        return kind != MethodKind::Rbf && kind != MethodKind::NearestNeighbour && kind != MethodKind::TrendOnly;
    }
};

const char* to_string(MethodKind kind);

struct SynthesizedMotion {
    MatX aligned;  ///< D by T pose vectors at aligned frames (canonical frame)
    VecX warp;     ///< T, strictly increasing from 0: the synthesized source frame at each aligned frame
};

class Synthesizer {
public:
    virtual ~Synthesizer() = default;
    /// c: P values in the set's units. Thread-safe (immutable).
    virtual void synthesize(const Eigen::Ref<const VecX>& c, SynthesizedMotion& out) const = 0;
    /// The method's own reliability rho at Q parameter points (Q by P, set's units), computed with its own
    /// kernel; empty (size 0) for methods without one (RBF, nearest neighbour, trend only).
    virtual VecX reliability_batch(const Eigen::Ref<const MatX>& /*c*/) const { return VecX(); }
    double build_seconds = 0.0;  ///< wall time of the construction (variograms, trends, factorizations, Tucker)
};

/// Builds the method on `training` (>= 3 samples). InvalidArgument on bad specs.
std::unique_ptr<Synthesizer> build_synthesizer(const MethodSpec& method, const EvalSet& training);

/// The synthesized motion as a clip on `skeleton` at `frame_rate`: frames 0 .. floor(warp(T-1)), each pose
/// interpolated at the aligned time where the warp reaches it; canonical placement (origin, facing +Z).
Clip motion_clip(const SynthesizedMotion& motion, std::shared_ptr<const Skeleton> skeleton, double frame_rate);

/// The Tucker ranks (HOSVD, smallest bound) whose measured max joint error on the whole set is <= max_cm
/// (compression::search_ranks_for_max_error).
tensor::Ranks ranks_for_max_error(const EvalSet& set, double max_cm);

/// Per sample (N by T): d_p(q_i(t), q_0(0)), the RMS over joints of the distance between the joint
/// positions of the aligned pose and those of sample 0's first pose, both with the root's floor position
/// and heading removed (cm). The PerPose kernels' signal.
MatX pose_signal(const EvalSet& set);

/// Sample i's aligned poses (D by T).
MatX aligned_sample(const AlignedSet& aligned, Eigen::Index i);

}  // namespace mocapdb::eval
