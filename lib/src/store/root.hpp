#pragma once
// The root of a format-1 file: attributes format / format_version / kind and the three top groups.
#include "h5/file.hpp"

namespace mocapdb::store {

/// Writes the root attributes and creates /skeletons, /clips and /sets in a new file.
void write_root(h5::File& file);
/// Writes only the root attributes (after the top groups were copied in).
void write_root_attributes(h5::File& file);
/// StoreError naming "/" (or the missing group) and the expected vs found values unless the file is a
/// mocapdb database of this version. A newer version says so.
void check_root(const h5::File& file);

}  // namespace mocapdb::store
