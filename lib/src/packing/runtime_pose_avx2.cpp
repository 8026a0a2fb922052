// runtime_pose.hpp's kernels built with -mavx2 -mfma -ffp-contract=off (lib/CMakeLists.txt);
// called only when pose_avx2_available(). Nothing here is shared with other translation units.
#include "runtime_pose.hpp"

#if defined(__SSE2__)
#include <immintrin.h>
#endif

namespace mocapdb::packing::detail {
namespace {
#include "runtime_pose_kernel.inc"
}  // namespace

MOCAPDB_POSE_KERNELS(avx2)

}  // namespace mocapdb::packing::detail
