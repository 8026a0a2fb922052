#pragma once
// The packed tier as the group /packed (format v3, schemas/format-v3.md §9): one subgroup per packed
// group holding its bytes (uint8, fletcher32), its clip ids in decoder order and per-clip figures.
#include <cstdint>
#include <string>
#include <vector>

#include "h5/file.hpp"
#include "mocapdb/store/database.hpp"

namespace mocapdb::store {

/// The `codec` attribute of /packed/{group}/bytes: packing::pack_group's format version, written as
/// the bytes' version byte says (4: runtime groups, 3: archive groups); version 2 (no motion root or
/// position-channel convention stored) is still read.
inline const std::string kPackedGroupCodecRuntime = "mocapdb-packed-group-4";
inline const std::string kPackedGroupCodec = "mocapdb-packed-group-3";
inline const std::string kPackedGroupCodecV2 = "mocapdb-packed-group-2";

/// The codec of a group's bytes (its version byte); Error for bytes without the packed group's magic
/// or of an unknown version.
std::string packed_group_codec(const std::vector<std::uint8_t>& bytes);

/// Writes /packed (which must not exist) with `tier`'s figures and one group per entry; the groups'
/// names are tier.groups[i].name.
void write_packed(h5::File& file, const PackedTierRecord& tier,
                  const std::vector<std::vector<std::uint8_t>>& group_bytes);
/// Reads the records (attributes and the small datasets, not the bytes). StoreError naming the
/// offending object for wrong kinds, dtypes, shapes or values.
PackedTierRecord read_packed_record(const h5::File& file);
/// The bytes of /packed/{group}/bytes (ChecksumError when corrupted).
std::vector<std::uint8_t> read_packed_bytes(const h5::File& file, const std::string& group);

}  // namespace mocapdb::store
