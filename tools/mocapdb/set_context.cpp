#include "set_context.hpp"

#include "mocapdb/core/error.hpp"

namespace mocapdb::cli {

SetContext load_set_context(const Database& db, const std::string& name) {
    SetContext c;
    c.set = db.load_set(name);
    auto aligned = db.load_aligned(name);
    if (!aligned)
        throw InvalidArgument("set '" + name + "' in " + db.path().string() +
                              " is not aligned (run: mocapdb align " + db.path().string() + " --set " + name + ")");
    c.aligned = std::move(*aligned);
    const auto record = db.find_clip(c.set.samples.front().clip);
    c.skeleton = db.load_skeleton(record->skeleton);
    c.frame_rate = record->frame_rate;
    for (const SampleRef& s : c.set.samples) {
        const auto r = db.find_clip(s.clip);
        c.seconds_of_motion += static_cast<double>(s.frame_count()) / r->frame_rate;
        c.clip_channel_values += static_cast<std::uint64_t>(s.frame_count()) * c.skeleton->channel_count();
    }
    return c;
}

}  // namespace mocapdb::cli
