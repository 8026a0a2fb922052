#pragma once
// The root of a database file: attributes format / format_version / kind and the three top groups.
#include "h5/file.hpp"

namespace mocapdb::store {

/// The oldest format version this library reads (every version up to kDatabaseFormatVersion is read;
/// a later version only adds optional objects, so an older file is also a file of the current one).
constexpr int kOldestDatabaseFormatVersion = 1;

/// Writes the root attributes and creates /skeletons, /clips and /sets in a new file.
void write_root(h5::File& file);
/// Writes the root attributes of a segment (kind "segment") and its three top groups.
void write_segment_root(h5::File& file);
/// Writes only the root attributes (after the top groups were copied in).
void write_root_attributes(h5::File& file);
/// The file's format_version. StoreError naming "/" (or the missing group) and the expected vs found
/// values unless the file is a mocapdb database of a version in [kOldestDatabaseFormatVersion,
/// kDatabaseFormatVersion]. A newer version says so.
int check_root(const h5::File& file);
/// Sets the root attribute format_version to kDatabaseFormatVersion (a writer session on an older file:
/// the older file is a valid file of the current version, so only the number changes).
void upgrade_root(h5::File& file);

}  // namespace mocapdb::store
