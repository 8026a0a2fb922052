// Database::clips_file_bytes (issue 36 item 5): what the files spend on the clips, HDF5 objects
// included, so that lossless figures are honest. It must account for what a clip really adds to the
// files (the difference between databases of 2 and 8 clips of one rig), not only the channel data.
#include <catch2/catch.hpp>

#include "mocapdb/store/database.hpp"
#include "store_test_support.hpp"

using namespace mocapdb;
using namespace mocapdb::test;

namespace {

std::filesystem::path database_of(const TempDir& dir, const std::string& name, unsigned clips) {
    const auto db = dir / name;
    DatabaseWriter w(db);
    for (unsigned k = 0; k < clips; ++k)
        w.add_clip(synthetic_clip(200, 8, 40 + k), synthetic_source("c" + std::to_string(k) + ".bvh", "bytes " + std::to_string(k)));
    w.commit();
    return db;
}

}  // namespace

TEST_CASE("clips_file_bytes: what the clips add to the files, HDF5 objects included", "[store]") {
    TempDir dir("clips-file-bytes");
    const Database two(database_of(dir, "two.h5", 2));
    const Database eight(database_of(dir, "eight.h5", 8));
    std::uint64_t channels_two = 0, channels_eight = 0;
    for (const ClipRecord& r : two.clips()) channels_two += r.stored_bytes;
    for (const ClipRecord& r : eight.clips()) channels_eight += r.stored_bytes;
    const std::uint64_t clips_two = two.clips_file_bytes(), clips_eight = eight.clips_file_bytes();
    INFO("channel data " << channels_two << " / " << channels_eight << ", clips " << clips_two << " / " << clips_eight
                         << ", files " << two.file_size() << " / " << eight.file_size());
    // More than the channel data (each clip's group, dataset headers, chunk index...), within the files.
    CHECK(clips_two > channels_two + 2 * 2000);
    CHECK(clips_eight > channels_eight + 8 * 2000);
    CHECK(clips_two < two.file_size());
    CHECK(clips_eight < eight.file_size());
    // What six more clips cost the files is what the accounting says they cost (within 3 %: the
    // files' unused space and shared heaps are not attributed).
    const double added_files = static_cast<double>(eight.file_size()) - static_cast<double>(two.file_size());
    const double added_clips = static_cast<double>(clips_eight) - static_cast<double>(clips_two);
    CHECK(added_clips == Approx(added_files).epsilon(0.03));
    CHECK(Database(database_of(dir, "none.h5", 0)).clips_file_bytes() < 2000);
}
