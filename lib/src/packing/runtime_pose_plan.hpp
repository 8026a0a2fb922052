#pragma once
// The runtime tier's y -> pose (internal to the packing module): per group the float32 dof basis and,
// per skeleton entry, the kernels' lanes (runtime_pose.hpp), built from a GroupModel. The encoder's
// bound check and every decode form the dofs by pose_dofs_portable / pose_dofs_avx2 (the same bits),
// so the bound holds for what is decoded.
#include <vector>

#include "group_model.hpp"
#include "runtime_pose.hpp"

namespace mocapdb::packing::detail {

struct RuntimePosePlan {
    std::vector<float> basis;  ///< dp (da rounded up to 16) by da, column-major, rows past da zero
    struct Skeleton {
        std::vector<double> inverse_weights;
        std::vector<PoseLanes> lanes[3];
        PoseKernel kernel;
        PoseRoot root;
        bool root_projects = false;    ///< the motion root has rotation channels, but not three: library path
        std::vector<int> rest_joints;  ///< joints whose rotation the kernels do not write (it stays at rest)
    };
    std::vector<Skeleton> skeletons;
    bool avx2 = false;    ///< the AVX2 kernels (the CPU has them and they were not turned off)
    bool avx512 = false;  ///< the AVX-512 kernels instead (the same conditions)

    /// Memory held (containers' capacities).
    std::size_t memory_bytes() const;
};

/// The plan of model m (at most 256 active dofs: InvalidArgument otherwise). `allow_avx2`: use the
/// AVX-512 or AVX2 kernels where the CPU has them.
void make_runtime_pose_plan(const GroupModel& m, bool allow_avx2, RuntimePosePlan& out);

/// Frame y's dofs (m.dofs values into p): x = U y in float32, unweighted, constants elsewhere.
inline void runtime_dofs(const RuntimePosePlan& plan, const ClipEntry& e, const double* y, double* p) {
    const PoseKernel& k = plan.skeletons[e.skeleton].kernel;
    if (plan.avx512) pose_dofs_avx512(k, y, p);
    else if (plan.avx2) pose_dofs_avx2(k, y, p);
    else pose_dofs_portable(k, y, p);
}

/// Frame y's local pose into out (p: m.dofs values of scratch, left holding the dofs): the kernels,
/// or ChannelWriter::write_local where they leave the pose (near gimbal lock, tiny angles).
void runtime_local_pose(const GroupModel& m, const RuntimePosePlan& plan, const ClipEntry& e, const double* y,
                        double* p, LocalPose& out);

}  // namespace mocapdb::packing::detail
