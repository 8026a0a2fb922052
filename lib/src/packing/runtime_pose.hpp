#pragma once
// The runtime tier's y -> local pose (internal to the packing module): x = U y in float32, the dofs,
// and the joints' rotations as ChannelWriter::write_local forms them (exp maps, projections onto the
// joints' channels; equal to its rotations to rounding, not to the bit), from plain arrays. One kernel
// source (runtime_pose_kernel.inc) built three times: portable (runtime_pose_portable.cpp), with AVX2
// + FMA (runtime_pose_avx2.cpp) and with AVX-512 F and VL (runtime_pose_avx512.cpp; each where the
// compiler takes the flags), chosen at run time by the CPU. No Eigen and no shared inline code in the
// kernels, so one build's code cannot stand in for another's (ODR). Every build gives the same bits
// (IEEE operations lane by lane, no contraction); tests/packing checks the CPU's best against the
// portable one.
#include <cstddef>

namespace mocapdb::packing::detail {

/// Active dofs a runtime group holds at most (the kernels' and key walk's stack arrays).
constexpr int kRuntimeMaxDofs = 1024;

/// Four joints of one kind (two, one or three rotation channels); lanes past `count` repeat lane 0.
struct PoseLanes {
    int count = 0;
    int pose_row[4]{};     ///< first of each joint's three exp-map dofs in p
    int joint[4]{};        ///< skeleton index (LocalPose slot)
    double frame[9][4]{};  ///< two channels: the Euler frame A (row-major) by lane
    double missing[4]{}, first[3][4]{}, second[3][4]{}, cross[3][4]{}, dot[4]{};  ///< two channels
    double axis[3][4]{};                                                          ///< one channel: C·e
};

/// The motion root's transform as ChannelWriter::write_local forms it (quaternions x, y, z, w).
struct PoseRoot {
    int joint = 0;
    int translates[3]{};        ///< 1 where the root has that position channel
    bool rotates = false;       ///< has rotation channels (three: no projection)
    bool adds = false;          ///< position channels add to the offset
    double above_inverse[4]{};  ///< the rotation above the motion root, inverted
    double above_position[3]{}, root_offset[3]{}, offset[3]{};
};

/// One skeleton of a group: what the kernels read (owned by the caller).
struct PoseKernel {
    int da = 0, dp = 0, dofs = 0;             ///< active dofs, da rounded up to 16, all dofs
    const float* basis = nullptr;             ///< dp by da, column-major (column k at k·dp), rows past da zero
    const double* inverse_weights = nullptr;  ///< 1 / the da active weights
    const int* active = nullptr;              ///< da indices into p
    const double* constant = nullptr;         ///< dofs values (p where not active)
    const PoseLanes* lanes[3]{};              ///< joints with two, one, three channels
    int groups[3]{};                          ///< lane groups of each kind
    const PoseRoot* root = nullptr;
};

/// p (dofs values) of y (da values): x = U y in float32 (each x[i] summed over ascending k, a
/// product then a sum, no FMA), x[i] · inverse_weights[i] at active[i], constant elsewhere.
void pose_dofs_portable(const PoseKernel& k, const double* y, double* p);
void pose_dofs_avx2(const PoseKernel& k, const double* y, double* p);
void pose_dofs_avx512(const PoseKernel& k, const double* y, double* p);
/// The rotations (x, y, z, w per joint, the layout of Eigen::Quaterniond) of the lanes' joints from
/// p; false when a lane needs ChannelWriter's scalar path (an exp-map angle above 7 rad, near gimbal
/// lock or the Euler family boundary): then nothing is complete and the caller decodes the pose that
/// way. Each lane's rotation is write_local's to rounding (~1e-15).
bool pose_rotations_portable(const PoseKernel& k, const double* p, double* rotations);
bool pose_rotations_avx2(const PoseKernel& k, const double* p, double* rotations);
bool pose_rotations_avx512(const PoseKernel& k, const double* p, double* rotations);
/// The motion root's rotation and translation (x, y, z, w and x, y, z at its joint) from p, for a
/// clip placed by `placement` (heading x, y, z, w, then translation); false when an exp map's angle is
/// under 1e-12 (then nothing is complete: the caller decodes the pose by ChannelWriter).
bool pose_root_portable(const PoseKernel& k, const double* placement, const double* p, double* rotations,
                        double* translations);
bool pose_root_avx2(const PoseKernel& k, const double* placement, const double* p, double* rotations,
                    double* translations);
bool pose_root_avx512(const PoseKernel& k, const double* placement, const double* p, double* rotations,
                      double* translations);
/// pose_root then pose_rotations (the same bits), their stages interleaved; false when either is.
bool pose_local_portable(const PoseKernel& k, const double* placement, const double* p, double* rotations,
                         double* translations);
bool pose_local_avx2(const PoseKernel& k, const double* placement, const double* p, double* rotations,
                     double* translations);
bool pose_local_avx512(const PoseKernel& k, const double* placement, const double* p, double* rotations,
                       double* translations);
/// Whether this build has the AVX2 kernels and the CPU runs them.
bool pose_avx2_available();
/// Whether this build has the AVX-512 kernels and the CPU runs them (then it runs the AVX2 ones too).
bool pose_avx512_available();

/// The functions above of one build (suffix portable, avx2 or avx512), in a file that includes
/// runtime_pose_kernel.inc.
#define MOCAPDB_POSE_KERNELS(suffix)                                                                           \
    void pose_dofs_##suffix(const PoseKernel& k, const double* y, double* p) { kernel_dofs(k, y, p); }         \
    bool pose_rotations_##suffix(const PoseKernel& k, const double* p, double* rotations) {                    \
        return kernel_local(k, nullptr, p, rotations, nullptr, false, true);                                   \
    }                                                                                                          \
    bool pose_root_##suffix(const PoseKernel& k, const double* placement, const double* p, double* rotations,  \
                            double* translations) {                                                            \
        return kernel_local(k, placement, p, rotations, translations, true, false);                            \
    }                                                                                                          \
    bool pose_local_##suffix(const PoseKernel& k, const double* placement, const double* p, double* rotations, \
                             double* translations) {                                                           \
        return kernel_local(k, placement, p, rotations, translations, true, true);                             \
    }

}  // namespace mocapdb::packing::detail
