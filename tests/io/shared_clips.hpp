#pragma once
// The shared CMU clips, loaded once per test executable (they are read-only).
#include <string>
#include <vector>

#include "mocapdb/motion/clip.hpp"

namespace mocapdb::test {

struct LoadedClip {
    std::string path;
    Clip clip;
    std::size_t warnings = 0;
};

/// Every BVH in datasets/cmu-walkrun-pfnn at its true 60 fps; empty when the folder is absent.
/// In a sanitizer build (MOCAPDB_SANITIZED_BUILD) every 6th clip of each folder only.
const std::vector<LoadedClip>& shared_bvh_clips();
/// Every AMC in datasets/cmu-asfamc with its NN.asf; empty when the folder is absent.
const std::vector<LoadedClip>& shared_amc_clips();

}  // namespace mocapdb::test
