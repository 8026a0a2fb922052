// runtime_pose.hpp's kernels built with -mavx2 -mfma -ffp-contract=off (benchmarks/CMakeLists.txt);
// called only when pose_avx2_available(). Nothing here is shared with other translation units.
#include "runtime_pose.hpp"

#if defined(__SSE2__)
#include <immintrin.h>
#endif

namespace mocapdb::bench {
namespace {
#include "runtime_pose_kernel.inc"
}  // namespace

void pose_dofs_avx2(const PoseKernel& k, const double* y, double* p) { kernel_dofs(k, y, p); }

bool pose_rotations_avx2(const PoseKernel& k, const double* p, double* rotations) {
    return kernel_rotations(k, p, rotations);
}

bool pose_root_avx2(const PoseKernel& k, const double* placement, const double* p, double* rotations, double* translations) {
    return kernel_root(k, placement, p, rotations, translations);
}

}  // namespace mocapdb::bench
