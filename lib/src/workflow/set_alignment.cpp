#include "mocapdb/workflow/set_alignment.hpp"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <map>

#include "mocapdb/core/error.hpp"
#include "mocapdb/dataset/alignment.hpp"
#include "mocapdb/dataset/gait_phase.hpp"
#include "mocapdb/dataset/set_builder.hpp"
#include "mocapdb/store/database.hpp"

namespace mocapdb::workflow {
namespace {

// Is `begin` within a frame of a left-foot pass of the clip (where gait_cycles cuts)? `passes` caches
// the clip's passes by clip id. False when the clip's feet are not found.
bool starts_at_pass(const Clip& clip, const SampleRef& s, std::map<std::string, std::vector<std::size_t>>& passes) {
    auto it = passes.find(s.clip);
    if (it == passes.end()) {
        std::vector<std::size_t> found;
        try {
            found = left_foot_passes(forward_foot_separation(clip));
        } catch (const InvalidArgument&) {
            // No feet: no passes.
        }
        it = passes.emplace(s.clip, std::move(found)).first;
    }
    for (const std::size_t p : it->second)
        if (p + 1 >= s.begin && p <= s.begin + 1) return true;
    return false;
}

}  // namespace

AlignOutcome align_set(const std::filesystem::path& db_path, const AlignRequest& a) {
    const auto start = std::chrono::steady_clock::now();
    // Read from the published file (errors name it), write in a session only once aligned. The read
    // view is closed before the commit (an open reader keeps replaced segments on disk).
    std::vector<Clip> samples;
    AlignOutcome o;
    {
        const Database db(db_path);
        const MotionSet set = db.load_set(a.set);
        std::map<std::string, std::vector<std::size_t>> passes;
        o.cut_at_gait_phase = !set.samples.empty();
        for (const SampleRef& s : set.samples) {
            const Clip clip = db.load_clip(s.clip);
            if (o.cut_at_gait_phase) o.cut_at_gait_phase = starts_at_pass(clip, s, passes);
            o.labels.push_back(sample_label(s, clip.frame_count()));
            samples.push_back(sample_frames(set, samples.size(), clip));  // with the set's dropout repairs
            if (a.read_progress) a.read_progress({samples.size(), set.samples.size(), s.clip});
        }
    }
    AlignOptions options;
    options.method = a.method;
    options.frames = a.frames;
    if (!a.reference.empty()) {
        const auto it = std::find(o.labels.begin(), o.labels.end(), a.reference);
        if (it == o.labels.end())
            throw InvalidArgument("set '" + a.set + "' has no sample '" + a.reference + "' (see mocapdb set show)");
        options.reference = static_cast<std::size_t>(it - o.labels.begin());
    }
    options.progress = a.progress;
    o.aligned = align_samples(samples, options);
    o.distance = mean_alignment_distance(samples, o.aligned);
    try {
        o.phase = check_phase(samples, o.aligned);
    } catch (const InvalidArgument&) {
        // No feet to compare (not a legged figure): no phase check.
    }
    DatabaseWriter writer(db_path, DatabaseWriter::Mode::OpenOrCreate);
    writer.put_aligned(a.set, o.aligned);
    writer.commit();
    o.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return o;
}

}  // namespace mocapdb::workflow
