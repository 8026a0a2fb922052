#pragma once
// Property lists for following links. A database's index file reaches its segments through external
// links (schemas/format-v4.md); segments are immutable once published, so every link traversal
// opens its target read-only, whatever the intent of the file it starts from (a writing session's
// index is open read-write, the segments it reads are not). Created once per process.
#include <hdf5.h>

namespace mocapdb::store::h5 {

/// Link access: external links open their target read-only.
hid_t link_access();
/// The same for H5Dopen2 (dataset access lists derive from link access lists).
hid_t dataset_access();
/// The same for H5Gopen2.
hid_t group_access();

}  // namespace mocapdb::store::h5
