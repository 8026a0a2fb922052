#pragma once
// Transparent huge pages for large fresh matrices. Where the kernel backs memory with 4 KB pages on first
// touch, a 74 MB matrix (3 043² doubles: a synthesis kernel's system) takes 18 000 page faults, which on
// a virtual machine cost more than the arithmetic that fills it (perf: 30 % of a model's load). Advised
// memory is backed by 2 MB pages instead (Linux, when /sys/kernel/mm/transparent_hugepage/enabled is
// "madvise" or "always"); elsewhere, and for blocks under 2 MB, this does nothing. Call it on memory not
// touched yet (after a resize, before the first write); the values are not changed.
#include <cstddef>
#include <cstdint>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace mocapdb {

/// Advises the 2 MB-aligned pages inside [data, data + bytes); errors are ignored (it is only advice).
inline void advise_huge_pages(void* data, std::size_t bytes) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    constexpr std::uintptr_t huge = std::uintptr_t{2} << 20;
    const auto begin = reinterpret_cast<std::uintptr_t>(data);
    const std::uintptr_t first = (begin + huge - 1) / huge * huge;
    const std::uintptr_t last = (begin + bytes) / huge * huge;
    if (data != nullptr && last > first) madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE);
#else
    (void)data;
    (void)bytes;
#endif
}

/// The same for an Eigen matrix or vector's storage.
template <class Dense>
void advise_huge_pages(Dense& m) {
    advise_huge_pages(static_cast<void*>(m.data()), static_cast<std::size_t>(m.size()) * sizeof(*m.data()));
}

}  // namespace mocapdb
