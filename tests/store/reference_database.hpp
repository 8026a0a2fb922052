#pragma once
// The tiny reference database of format version 1 kept in tests/data forever
// (tests/data/reference-v1.h5, its `h5dump -H` in tests/data/reference-v1.h5dump.txt).
// Everything in it is fixed here, so a test can rebuild it and compare.
#include <filesystem>

#include "mocapdb/dataset/aligned_set.hpp"
#include "mocapdb/dataset/motion_set.hpp"
#include "mocapdb/motion/clip.hpp"
#include "mocapdb/store/clip_record.hpp"

namespace mocapdb::test {

struct ReferenceContent {
    Clip clip;            ///< "tiny_walk": 3 joints + end site, 4 frames at 30 Hz
    ClipSource source;
    MotionSet set;        ///< "tiny_set": 2 samples of tiny_walk, 1 parameter
    AlignedSet aligned;   ///< 9 dofs × 3 frames × 2 samples, tensor(d,t,s) = d + 10t + 100s
};

ReferenceContent reference_content();
/// Writes the reference database to `path` (which must not exist) through DatabaseWriter.
void write_reference_database(const std::filesystem::path& path);

}  // namespace mocapdb::test
