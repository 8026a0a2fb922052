// runtime_pose.hpp's kernels for the compiler's default target, and the run-time choice.
#include "runtime_pose.hpp"

#if defined(__SSE2__)
#include <immintrin.h>
#endif

namespace mocapdb::bench {
namespace {
#include "runtime_pose_kernel.inc"
}  // namespace

void pose_dofs_portable(const PoseKernel& k, const double* y, double* p) { kernel_dofs(k, y, p); }

bool pose_rotations_portable(const PoseKernel& k, const double* p, double* rotations) {
    return kernel_rotations(k, p, rotations);
}

bool pose_root_portable(const PoseKernel& k, const double* placement, const double* p, double* rotations, double* translations) {
    return kernel_root(k, placement, p, rotations, translations);
}

bool pose_avx2_available() {
#if defined(MOCAPDB_POSE_AVX2)
    return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
#else
    return false;
#endif
}

#if !defined(MOCAPDB_POSE_AVX2)
// No AVX2 build of the kernels: never called (pose_avx2_available() is false); the portable ones.
void pose_dofs_avx2(const PoseKernel& k, const double* y, double* p) { kernel_dofs(k, y, p); }
bool pose_rotations_avx2(const PoseKernel& k, const double* p, double* rotations) {
    return kernel_rotations(k, p, rotations);
}
bool pose_root_avx2(const PoseKernel& k, const double* placement, const double* p, double* rotations, double* translations) {
    return kernel_root(k, placement, p, rotations, translations);
}
#endif

}  // namespace mocapdb::bench
