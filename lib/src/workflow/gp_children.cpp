#include "mocapdb/workflow/gp_children.hpp"

#include "mocapdb/dataset/set_builder.hpp"
#include "mocapdb/io/clip_file.hpp"
#include "mocapdb/store/database.hpp"

namespace mocapdb::workflow {

GpChildren set_children(const std::filesystem::path& db_path, const std::string& set_name) {
    GpChildren out;
    const Database db(db_path);
    const MotionSet set = db.load_set(set_name);
    for (std::size_t i = 0; i < set.samples.size(); ++i) {
        const SampleRef& s = set.samples[i];
        out.clips.push_back(sample_frames(set, i, db.load_clip(s.clip)));  // with the set's dropout repairs
        out.names.push_back(s.clip + ":" + std::to_string(s.begin) + "-" + std::to_string(s.end));
    }
    return out;
}

GpChildren clip_file_children(const std::vector<std::string>& paths, double frame_rate) {
    GpChildren out;
    ClipReadOptions o;
    if (frame_rate > 0.0) o.frame_rate = frame_rate;
    for (const std::string& p : paths) {
        out.clips.push_back(read_clip(p, o));
        out.names.push_back(std::filesystem::path(p).stem().string());
    }
    return out;
}

}  // namespace mocapdb::workflow
