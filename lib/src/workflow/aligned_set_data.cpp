#include "mocapdb/workflow/aligned_set_data.hpp"

#include <map>

#include "mocapdb/core/error.hpp"
#include "mocapdb/core/remedy.hpp"
#include "mocapdb/store/database.hpp"

namespace mocapdb::workflow {
namespace {

[[noreturn]] void not_aligned(const Database& db, const std::string& name) {
    throw Refused<InvalidArgument>(Remedy::AlignFirst,
                                   "set '" + name + "' in " + db.path().string() + " is not aligned");
}

// The skeleton and frame rate of the set's first clip and the source size; every sample's clip must exist.
struct SetSource {
    std::shared_ptr<const Skeleton> skeleton;
    double frame_rate = 0.0;
    double seconds_of_motion = 0.0;
    std::uint64_t clip_channel_values = 0;
};

SetSource set_source(const Database& db, const std::string& name, const MotionSet& set) {
    SetSource d;
    std::map<std::string, double> frame_rates;  // one record read per clip, not per sample (#16: windows)
    for (const SampleRef& s : set.samples) {
        auto known = frame_rates.find(s.clip);
        if (known == frame_rates.end()) {
            const auto record = db.find_clip(s.clip);
            if (!record) throw InvalidArgument("set '" + name + "': clip '" + s.clip + "' is missing");
            if (!d.skeleton) {
                d.skeleton = db.load_skeleton(record->skeleton);
                d.frame_rate = record->frame_rate;
            }
            known = frame_rates.emplace(s.clip, record->frame_rate).first;
        }
        d.seconds_of_motion += static_cast<double>(s.frame_count()) / known->second;
        d.clip_channel_values += static_cast<std::uint64_t>(s.frame_count()) * d.skeleton->channel_count();
    }
    return d;
}

}  // namespace

AlignedSetData load_aligned_set(const Database& db, const std::string& name) {
    AlignedSetData d;
    d.set = db.load_set(name);
    auto aligned = db.load_aligned(name);
    if (!aligned) not_aligned(db, name);
    d.aligned = std::move(*aligned);
    SetSource source = set_source(db, name, d.set);
    d.skeleton = std::move(source.skeleton);
    d.frame_rate = source.frame_rate;
    d.seconds_of_motion = source.seconds_of_motion;
    d.clip_channel_values = source.clip_channel_values;
    return d;
}

AlignedTimingData load_aligned_timing(const Database& db, const std::string& name) {
    AlignedTimingData d;
    d.set = db.load_set(name);
    auto timing = db.load_aligned_timing(name);
    if (!timing) not_aligned(db, name);
    d.timing = std::move(*timing);
    SetSource source = set_source(db, name, d.set);
    d.skeleton = std::move(source.skeleton);
    d.frame_rate = source.frame_rate;
    return d;
}

}  // namespace mocapdb::workflow
