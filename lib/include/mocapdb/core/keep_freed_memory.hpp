#pragma once
// A process-wide allocator setting that applications may opt into; the library never calls it.
//
// Every GP likelihood evaluation allocates and frees matrices of several MB. glibc's defaults hand such
// blocks back to the kernel (mmap / trim) on every free, and the page faults then cost about 30 % of an
// evaluation at 39 outputs x 90 frames. keep_freed_memory() keeps freed memory in the process (one arena,
// no trimming, no mmap below 256 MB) for the rest of its life. No effect outside glibc.

namespace mocapdb {

void keep_freed_memory();

}  // namespace mocapdb
