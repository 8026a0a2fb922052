#include "mocapdb/workflow/database_summary.hpp"

#include <map>

namespace mocapdb::workflow {

DatabaseSummary summarize_database(const std::filesystem::path& path) {
    const Database db(path);
    DatabaseSummary s;
    s.format_version = db.format_version();
    s.file_bytes = static_cast<std::uint64_t>(db.file_size());
    s.clips = db.clips();
    s.sets = db.sets();
    s.packed = db.packed();
    std::map<std::string, PackedClipEntry> entries;
    if (s.packed)
        for (const PackedGroupRecord& g : s.packed->groups)
            for (const PackedClipRecord& c : g.clips) entries[c.id] = {g.name, c};
    for (const ClipRecord& c : s.clips) {
        s.total_frames += c.frames;
        s.total_seconds += c.duration();
        s.total_stored_bytes += c.stored_bytes;
        const auto it = entries.find(c.id);
        s.packed_clips.push_back(it == entries.end() ? std::nullopt : std::optional<PackedClipEntry>(it->second));
    }
    for (const std::string& id : db.skeletons()) {
        const auto sk = db.load_skeleton(id);
        s.skeletons.push_back({id, db.skeleton_source(id), sk->size(), sk->channel_count()});
    }
    return s;
}

}  // namespace mocapdb::workflow
