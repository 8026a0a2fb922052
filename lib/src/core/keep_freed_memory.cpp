#include "mocapdb/core/keep_freed_memory.hpp"

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace mocapdb {

void keep_freed_memory() {
#if defined(__GLIBC__)
    mallopt(M_MMAP_THRESHOLD, 256 * 1024 * 1024);
    mallopt(M_TRIM_THRESHOLD, 512 * 1024 * 1024);
    mallopt(M_ARENA_MAX, 1);
#endif
}

}  // namespace mocapdb
