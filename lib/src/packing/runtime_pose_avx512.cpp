// runtime_pose.hpp's kernels built with -mavx2 -mfma -mavx512f -mavx512vl -ffp-contract=off
// (lib/CMakeLists.txt): the product's float lanes sixteen wide. Called only when
// pose_avx512_available(). Nothing here is shared with other translation units.
#include "runtime_pose.hpp"

#if defined(__SSE2__)
#include <immintrin.h>
#endif

namespace mocapdb::packing::detail {
namespace {
#include "runtime_pose_kernel.inc"
}  // namespace

MOCAPDB_POSE_KERNELS(avx512)

}  // namespace mocapdb::packing::detail
