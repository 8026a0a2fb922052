#pragma once
// A small database of subject 16's walks built by the workflow steps themselves (issue #17), up to a
// stage: imported clips, a set "walks" of whole clips with measured turn and speed, aligned to 40
// frames, compressed to a max joint error of 1 cm. Each test file builds one and reuses it (a
// function-local static), so every step below the one under test runs once per test process.
#include <memory>
#include <string>
#include <vector>

#include "mocapdb/workflow/clip_import.hpp"
#include "mocapdb/workflow/set_alignment.hpp"
#include "mocapdb/workflow/set_compression.hpp"
#include "mocapdb/workflow/set_creation.hpp"
#include "shared_data.hpp"
#include "test_support.hpp"

namespace mocapdb::test {

enum class WalkStage { Imported, SetCreated, Aligned, Compressed };

/// The walks the database holds: 16_11 .. 16_22.
inline std::vector<std::filesystem::path> walk_files() {
    std::vector<std::filesystem::path> files;
    for (int t = 11; t <= 22; ++t) files.push_back(datasets_dir() / "cmu-asfamc" / ("16_" + std::to_string(t) + ".amc"));
    return files;
}

struct WalkDatabase {
    std::unique_ptr<TempDir> dir;
    std::filesystem::path path;
    workflow::ImportOutcome imported;
    workflow::SetOutcome set;
    workflow::AlignOutcome aligned;
    workflow::CompressOutcome compressed;
};

/// Aligns set `name` of `db` to `frames` frames and compresses it to a max joint error of 1 cm.
inline void align_and_compress(const std::filesystem::path& db, const std::string& name, Eigen::Index frames,
                               WalkDatabase* out = nullptr) {
    workflow::AlignRequest align;
    align.set = name;
    align.frames = frames;
    workflow::AlignOutcome aligned = workflow::align_set(db, align);
    workflow::CompressRequest compress;
    compress.set = name;
    compress.max_error_cm = 1.0;
    if (out) out->aligned = std::move(aligned);
    workflow::CompressOutcome compressed = workflow::compress_set(db, compress);
    if (out) out->compressed = std::move(compressed);
}

inline WalkDatabase make_walk_database(const std::string& tag, WalkStage upto) {
    WalkDatabase w;
    w.dir = std::make_unique<TempDir>(tag);
    w.path = w.dir->path() / "walks.h5";
    w.imported = workflow::import_clips(w.path, walk_files(), workflow::ImportOptions{}, false);
    if (upto == WalkStage::Imported) return w;
    workflow::SetRequest set;
    set.name = "walks";
    set.clips = {"16_*"};
    set.segment = "none";
    set.extract = {"turn", "speed"};
    w.set = workflow::create_set(w.path, set);
    if (upto == WalkStage::SetCreated) return w;
    if (upto == WalkStage::Aligned) {
        workflow::AlignRequest align;
        align.set = "walks";
        align.frames = 40;
        w.aligned = workflow::align_set(w.path, align);
        return w;
    }
    align_and_compress(w.path, "walks", 40, &w);
    return w;
}

}  // namespace mocapdb::test
