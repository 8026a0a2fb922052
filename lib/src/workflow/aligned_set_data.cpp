#include "mocapdb/workflow/aligned_set_data.hpp"

#include "mocapdb/core/error.hpp"
#include "mocapdb/store/database.hpp"

namespace mocapdb::workflow {

AlignedSetData load_aligned_set(const Database& db, const std::string& name) {
    AlignedSetData d;
    d.set = db.load_set(name);
    auto aligned = db.load_aligned(name);
    if (!aligned)
        throw InvalidArgument("set '" + name + "' in " + db.path().string() + " is not aligned (run: mocapdb align " +
                              db.path().string() + " --set " + name + ")");
    d.aligned = std::move(*aligned);
    for (const SampleRef& s : d.set.samples) {
        const auto record = db.find_clip(s.clip);
        if (!record) throw InvalidArgument("set '" + name + "': clip '" + s.clip + "' is missing");
        if (!d.skeleton) {
            d.skeleton = db.load_skeleton(record->skeleton);
            d.frame_rate = record->frame_rate;
        }
        d.seconds_of_motion += static_cast<double>(s.frame_count()) / record->frame_rate;
        d.clip_channel_values += static_cast<std::uint64_t>(s.frame_count()) * d.skeleton->channel_count();
    }
    return d;
}

}  // namespace mocapdb::workflow
