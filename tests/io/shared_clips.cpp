#include "shared_clips.hpp"

#include <algorithm>
#include <filesystem>

#include "mocapdb/io/clip_file.hpp"
#include "shared_data.hpp"

namespace mocapdb::test {
namespace {

// Under the sanitizers (10-20x slower) every 6th clip is enough to check memory safety; the release
// pass of the suite checks every clip.
#ifdef MOCAPDB_SANITIZED_BUILD
constexpr std::size_t kStride = 6;
#else
constexpr std::size_t kStride = 1;
#endif

std::vector<LoadedClip> load_folder(const std::filesystem::path& dir, const std::string& extension,
                                    const ClipReadOptions& options) {
    std::vector<LoadedClip> out;
    if (!std::filesystem::exists(dir)) return out;
    std::vector<std::filesystem::path> paths;
    for (const auto& entry : std::filesystem::directory_iterator(dir))
        if (entry.path().extension() == extension) paths.push_back(entry.path());
    std::sort(paths.begin(), paths.end());
    for (std::size_t i = 0; i < paths.size(); i += kStride) {
        const auto& p = paths[i];
        Warnings warnings;
        Clip clip = read_clip(p, options, &warnings);
        out.push_back({p.string(), std::move(clip), warnings.size()});
    }
    return out;
}

}  // namespace

const std::vector<LoadedClip>& shared_bvh_clips() {
    static const std::vector<LoadedClip> clips = [] {
        ClipReadOptions options;
        options.frame_rate = 60.0;  // the headers' Frame Time is wrong (see SOURCE.txt)
        return load_folder(datasets_dir() / "cmu-walkrun-pfnn", ".bvh", options);
    }();
    return clips;
}

const std::vector<LoadedClip>& shared_amc_clips() {
    static const std::vector<LoadedClip> clips =
        load_folder(datasets_dir() / "cmu-asfamc", ".amc", ClipReadOptions{});
    return clips;
}

}  // namespace mocapdb::test
