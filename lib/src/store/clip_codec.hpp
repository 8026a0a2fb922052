#pragma once
// A clip as the group /clips/{id}: provenance attributes and the float64 channel matrix.
#include <string>

#include "h5/file.hpp"
#include "mocapdb/motion/clip.hpp"
#include "mocapdb/store/clip_record.hpp"

namespace mocapdb::store {

void write_clip(h5::File& file, const std::string& id, const Clip& clip, const std::string& skeleton_id,
                const ClipSource& source);
/// Metadata only (attributes and the channel dataset's shape).
ClipRecord read_clip_record(const h5::File& file, const std::string& id);
/// frames × `channels` matrix in cm and radians; StoreError unless the dataset is float64 with that
/// many columns, ChecksumError when a chunk is corrupted.
FrameMatrix read_clip_channels(const h5::File& file, const std::string& id, std::size_t channels);

}  // namespace mocapdb::store
