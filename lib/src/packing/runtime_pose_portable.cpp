// runtime_pose.hpp's kernels for the compiler's default target, and the run-time choice.
#include "runtime_pose.hpp"

#if defined(__SSE2__)
#include <immintrin.h>
#endif

namespace mocapdb::packing::detail {
namespace {
#include "runtime_pose_kernel.inc"
}  // namespace

MOCAPDB_POSE_KERNELS(portable)

bool pose_avx2_available() {
#if defined(MOCAPDB_POSE_AVX2)
    return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
#else
    return false;
#endif
}

bool pose_avx512_available() {
#if defined(MOCAPDB_POSE_AVX512)
    return pose_avx2_available() && __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl");
#else
    return false;
#endif
}

#if !defined(MOCAPDB_POSE_AVX2)
// No AVX2 build of the kernels: never called (pose_avx2_available() is false); the portable ones.
MOCAPDB_POSE_KERNELS(avx2)
#endif
#if !defined(MOCAPDB_POSE_AVX512)
// No AVX-512 build: never called (pose_avx512_available() is false); the portable ones.
MOCAPDB_POSE_KERNELS(avx512)
#endif

}  // namespace mocapdb::packing::detail
