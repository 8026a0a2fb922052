#pragma once
// A clip as the group /clips/{id}: provenance attributes and the channel matrix, written in the
// lossless packed form (channels_packed, format v3); the float64 `channels` of v1/v2 files is read too.
#include <string>

#include "h5/file.hpp"
#include "mocapdb/motion/clip.hpp"
#include "mocapdb/store/clip_record.hpp"

namespace mocapdb::store {

/// Name of the packed channel dataset in a clip group (format v3).
inline const std::string kPackedChannels = "channels_packed";
/// Clip attribute marking a clip whose channel dataset was removed (its motion lives in /packed
/// only); value kLosslessDroppedValue. Such a clip records `frames` and `channels` as attributes.
inline const std::string kLosslessAttribute = "lossless";
inline const std::string kLosslessDroppedValue = "dropped";

void write_clip(h5::File& file, const std::string& id, const Clip& clip, const std::string& skeleton_id,
                const ClipSource& source);
/// The clip's channel dataset: /clips/{id}/channels_packed (v3) or /clips/{id}/channels (v1, v2, and
/// v3 files upgraded from them); StoreError naming the clip when both or neither exist (neither: also
/// when the lossless tier was dropped, saying so).
std::string clip_channels_path(const h5::File& file, const std::string& id);
/// True when the clip's lossless channels were dropped (attribute lossless = "dropped").
bool lossless_dropped(const h5::File& file, const std::string& id);
/// Removes the clip's channel dataset, keeping its frame and channel counts as attributes and
/// marking it dropped. StoreError when it has no lossless channels.
void drop_lossless_channels(h5::File& file, const std::string& id);
/// Metadata only (attributes and the channel dataset's shape; ClipRecord::lossless false and
/// stored_bytes 0 for a dropped clip).
ClipRecord read_clip_record(const h5::File& file, const std::string& id);
/// frames × `channels` matrix in cm and radians, from channels_packed or (older files) the float64
/// channels; StoreError unless it has that many columns and decodes, ChecksumError when a chunk is
/// corrupted.
FrameMatrix read_clip_channels(const h5::File& file, const std::string& id, std::size_t channels);
/// Decodes the packed dataset at `path` (StoreError naming it when it is malformed).
FrameMatrix read_packed_channels(const h5::File& file, const std::string& path, std::size_t channels);

}  // namespace mocapdb::store
