#pragma once
// The tiny reference database of the current format version (3) kept in tests/data forever
// (tests/data/reference-v3.h5, its `h5dump -H` in tests/data/reference-v3.h5dump.txt). Everything in
// it is fixed here, so a test can rebuild it and compare. The version-3 file has a packed tier. tests/data/reference-v2.h5 (version 2) holds
// the same content with float64 clip channels, tests/data/reference-v1.h5 (version 1) the same clip,
// set and aligned set without the model.
#include <filesystem>

#include "mocapdb/compression/set_model.hpp"
#include "mocapdb/dataset/aligned_set.hpp"
#include "mocapdb/dataset/motion_set.hpp"
#include "mocapdb/motion/clip.hpp"
#include "mocapdb/store/clip_record.hpp"
#include "mocapdb/store/database.hpp"

namespace mocapdb::test {

struct ReferenceContent {
    Clip clip;            ///< "tiny_walk": 3 joints + end site, 4 frames at 30 Hz
    ClipSource source;
    MotionSet set;        ///< "tiny_set": 2 samples of tiny_walk, 1 parameter
    AlignedSet aligned;   ///< 9 dofs × 3 frames × 2 samples, tensor(d,t,s) = d + 10t + 100s
    /// HOSVD of the aligned tensor at ranks (1, 2, 2) with the skeleton's position-error weights (exact:
    /// the weighted, centred tensor has multilinear rank (1, 2, 2)); figures measured by eval.
    compression::SetModel model;
    ModelFigures figures;
};

ReferenceContent reference_content();
/// The bound of the reference file's packed tier (cm).
inline constexpr double kReferencePackedErrorCm = 0.1;
/// Writes the reference database (version 3, with the model and a packed tier at
/// kReferencePackedErrorCm) to `path` through DatabaseWriter and pack_database.
void write_reference_database(const std::filesystem::path& path);

}  // namespace mocapdb::test
