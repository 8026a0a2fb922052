#pragma once
// Reading named clips of a shared CMU folder in tests (needs ../shared; see shared_data.hpp).
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "mocapdb/dataset/alignment.hpp"
#include "mocapdb/dataset/motion_set.hpp"
#include "mocapdb/dataset/param_extractors.hpp"
#include "mocapdb/io/clip_file.hpp"
#include "shared_data.hpp"

namespace mocapdb::test {

/// The clips `stems` of ../shared/datasets/FOLDER (STEM.amc beside its NN.asf, or STEM.bvh read at
/// 60 Hz, the PFNN folder's true rate), named by their stems; each cut to its first `max_frames`
/// frames when max_frames > 0.
inline std::vector<Clip> read_shared_clips(const std::string& folder, const std::vector<std::string>& stems,
                                           std::size_t max_frames = 0) {
    std::vector<Clip> out;
    for (const auto& stem : stems) {
        const auto dir = datasets_dir() / folder;
        ClipReadOptions o;
        std::filesystem::path path = dir / (stem + ".amc");
        if (!std::filesystem::exists(path)) {
            path = dir / (stem + ".bvh");
            o.frame_rate = 60.0;
        }
        Clip c = read_clip(path, o);
        c.name = stem;
        if (max_frames > 0 && c.frame_count() > max_frames) c = slice(c, 0, max_frames);
        out.push_back(std::move(c));
    }
    return out;
}

/// Whole clips of subject 16 (cmu-asfamc/16_TRIAL.amc) as a set "walks" with measured turn and
/// speed, DTW-aligned to `frames` frames.
struct Subject16Set {
    std::vector<Clip> clips;
    MotionSet set;
    AlignedSet aligned;
};

inline Subject16Set subject16_set(const std::vector<int>& trials, Eigen::Index frames) {
    Subject16Set r;
    const std::vector<ParameterExtractor> extractors{ParameterExtractor::parse("turn"), ParameterExtractor::parse("speed")};
    r.set.name = "walks";
    r.set.parameter_names = {"turn", "speed"};
    r.set.parameter_units = {"rad", "cm/s"};
    r.set.parameters.resize(static_cast<Eigen::Index>(trials.size()), 2);
    for (std::size_t i = 0; i < trials.size(); ++i) {
        const std::string id = "16_" + std::to_string(trials[i]);
        r.clips.push_back(read_clip(datasets_dir() / "cmu-asfamc" / (id + ".amc")));
        r.set.samples.push_back({id, 0, r.clips.back().frame_count()});
        r.set.parameters.row(static_cast<Eigen::Index>(i)) =
            extract_parameters(r.clips.back(), 0, r.clips.back().frame_count(), extractors).transpose();
    }
    AlignOptions options;
    options.frames = frames;
    r.aligned = align_samples(r.clips, options);
    return r;
}

}  // namespace mocapdb::test
