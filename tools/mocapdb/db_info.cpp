#include "db_info.hpp"

#include <cstdio>
#include <iostream>
#include <map>
#include <optional>

#include "json_writer.hpp"
#include "mocapdb/store/database.hpp"

namespace mocapdb::cli {
namespace {

// The packed tier's entry of each clip (null when the clip is not in it).
struct PackedEntry {
    const PackedGroupRecord* group = nullptr;
    const PackedClipRecord* clip = nullptr;
};

std::map<std::string, PackedEntry> packed_entries(const std::optional<PackedTierRecord>& tier) {
    std::map<std::string, PackedEntry> out;
    if (!tier) return out;
    for (const PackedGroupRecord& g : tier->groups)
        for (const PackedClipRecord& c : g.clips) out[c.id] = {&g, &c};
    return out;
}

void print_json(const std::string& file, const Database& db, const std::vector<ClipRecord>& clips,
                const std::vector<SetRecord>& sets) {
    const std::optional<PackedTierRecord> tier = db.packed();
    const auto entries = packed_entries(tier);
    JsonWriter j;
    std::size_t frames = 0;
    double seconds = 0.0;
    for (const ClipRecord& c : clips) {
        frames += c.frames;
        seconds += c.duration();
    }
    j.begin_object();
    j.key("file").value(file);
    j.key("format").value("mocapdb");
    j.key("format_version").value(db.format_version());
    j.key("file_bytes").value(static_cast<std::size_t>(db.file_size()));
    j.key("clip_count").value(clips.size());
    j.key("total_frames").value(frames);
    j.key("total_seconds").value(seconds);
    j.key("clips").begin_array();
    for (const ClipRecord& c : clips) {
        j.begin_object();
        j.key("id").value(c.id);
        j.key("frames").value(c.frames);
        j.key("frame_rate").value(c.frame_rate);
        j.key("duration").value(c.duration());
        j.key("channels").value(c.channels);
        j.key("skeleton").value(c.skeleton);
        j.key("source_file").value(c.source.file_name);
        j.key("source_format").value(c.source.format);
        j.key("source_sha256").value(c.source.sha256);
        j.key("source_skeleton_file").value(c.source.skeleton_file);
        j.key("subject").value(c.source.subject);
        j.key("description").value(c.source.description);
        j.key("labels").begin_array();
        for (const std::string& l : c.source.labels) j.value(l);
        j.end_array();
        j.key("stored_bytes").value(static_cast<std::size_t>(c.stored_bytes));
        j.key("tiers").begin_array();
        if (c.lossless) j.value("lossless");
        const auto it = entries.find(c.id);
        if (it != entries.end()) j.value("packed");
        j.end_array();
        j.key("lossless_bytes").value(static_cast<std::size_t>(c.stored_bytes));
        if (it != entries.end()) {
            j.key("packed_group").value(it->second.group->name);
            j.key("packed_payload_bytes").value(static_cast<std::size_t>(it->second.clip->payload_bytes));
            j.key("packed_max_cm").value(it->second.clip->max_cm);
        } else {
            j.key("packed_group").null();
            j.key("packed_payload_bytes").null();
            j.key("packed_max_cm").null();
        }
        j.end_object();
    }
    j.end_array();
    j.key("skeletons").begin_array();
    for (const std::string& id : db.skeletons()) {
        const auto s = db.load_skeleton(id);
        j.begin_object();
        j.key("id").value(id);
        j.key("source_file").value(db.skeleton_source(id));
        j.key("joints").value(s->size());
        j.key("channels").value(s->channel_count());
        j.end_object();
    }
    j.end_array();
    j.key("sets").begin_array();
    for (const SetRecord& s : sets) {
        j.begin_object();
        j.key("name").value(s.name);
        j.key("samples").value(s.samples);
        j.key("parameters").begin_array();
        for (const std::string& p : s.parameter_names) j.value(p);
        j.end_array();
        j.key("parameter_source").value(s.parameter_source);
        j.key("aligned").value(s.aligned);
        j.key("tensor_dims").begin_array().value("sample").value("time").value("dof").end_array();
        if (s.aligned) {
            j.key("tensor_shape").begin_array();
            for (std::size_t e : s.tensor_shape) j.value(e);
            j.end_array();
        } else {
            j.key("tensor_shape").null();
        }
        j.key("tensor_stored_bytes").value(static_cast<std::size_t>(s.tensor_stored_bytes));
        j.key("model").value(s.model);
        if (s.model) {
            j.key("model_ranks").begin_array();
            for (std::size_t r : s.model_ranks) j.value(r);
            j.end_array();
        } else {
            j.key("model_ranks").null();
        }
        j.key("model_stored_bytes").value(static_cast<std::size_t>(s.model_stored_bytes));
        j.end_object();
    }
    j.end_array();
    if (tier) {
        j.key("packed").begin_object();
        j.key("max_error_cm").value(tier->max_error_cm);
        j.key("bytes").value(static_cast<std::size_t>(tier->bytes));
        j.key("clips").value(tier->clips);
        j.key("frames").value(tier->frames);
        j.key("max_cm").value(tier->max_cm);
        j.key("p99_cm").value(tier->p99_cm);
        j.key("rmse_cm").value(tier->rmse_cm);
        j.key("groups").begin_array();
        for (const PackedGroupRecord& g : tier->groups) {
            j.begin_object();
            j.key("name").value(g.name);
            j.key("skeleton").value(g.skeleton);
            j.key("frame_rate").value(g.frame_rate);
            j.key("clips").value(g.clips.size());
            j.key("frames").value(g.frames);
            j.key("bytes").value(static_cast<std::size_t>(g.bytes));
            j.key("stored_bytes").value(static_cast<std::size_t>(g.stored_bytes));
            j.key("max_cm").value(g.max_cm);
            j.end_object();
        }
        j.end_array();
        j.end_object();
    } else {
        j.key("packed").null();
    }
    j.end_object();
    std::cout << j.str();
}

void print_text(const std::string& file, const Database& db, const std::vector<ClipRecord>& clips,
                const std::vector<SetRecord>& sets) {
    std::size_t frames = 0;
    double seconds = 0.0;
    std::uint64_t stored = 0;
    for (const ClipRecord& c : clips) {
        frames += c.frames;
        seconds += c.duration();
        stored += c.stored_bytes;
    }
    std::printf("file        %s (%.1f MB)\n", file.c_str(), static_cast<double>(db.file_size()) / 1e6);
    std::printf("format      mocapdb %d\n", db.format_version());
    std::printf("clips       %zu: %zu frames, %.1f s of motion, channels %.1f MB stored\n", clips.size(), frames,
                seconds, static_cast<double>(stored) / 1e6);
    std::printf("skeletons   %zu\n", db.skeletons().size());
    std::printf("sets        %zu\n", sets.size());
    const std::optional<PackedTierRecord> tier = db.packed();
    const auto entries = packed_entries(tier);
    if (tier) {
        std::printf("packed      %zu clips in %zu groups at max error %g cm: %.1f kB (max %.4f cm, p99 %.4f cm, RMSE %.4f cm)\n",
                    tier->clips, tier->groups.size(), tier->max_error_cm, static_cast<double>(tier->bytes) / 1e3,
                    tier->max_cm, tier->p99_cm, tier->rmse_cm);
    } else {
        std::printf("packed      none (mocapdb pack)\n");
    }
    if (!clips.empty()) {
        std::printf("\n%-24s %8s %8s %9s %9s %9s  %-17s %-14s %s\n", "clip", "frames", "rate Hz", "seconds", "stored kB",
                    "packed kB", "tiers", "skeleton", "source");
        for (const ClipRecord& c : clips) {
            const auto it = entries.find(c.id);
            char packed_kb[32] = "-";
            if (it != entries.end())
                std::snprintf(packed_kb, sizeof packed_kb, "%.1f", static_cast<double>(it->second.clip->payload_bytes) / 1e3);
            std::printf("%-24s %8zu %8.6g %9.2f %9.1f %9s  %-17s %-14s %s\n", c.id.c_str(), c.frames, c.frame_rate,
                        c.duration(), static_cast<double>(c.stored_bytes) / 1e3, packed_kb,
                        !c.lossless ? "packed" : it != entries.end() ? "lossless+packed" : "lossless", c.skeleton.c_str(),
                        c.source.file_name.c_str());
        }
        if (tier) std::printf("(packed kB: the clip's coded windows; each group's header and tables are shared)\n");
    }
    if (!sets.empty()) {
        std::printf("\n%-24s %8s %11s  %-24s %9s  %-16s %s\n", "set", "samples", "parameters",
                    "tensor (sample,time,dof)", "stored kB", "model (R1,R2,R3)", "stored kB");
        for (const SetRecord& s : sets) {
            std::string shape = "-";
            if (s.aligned)
                shape = std::to_string(s.tensor_shape[0]) + " x " + std::to_string(s.tensor_shape[1]) + " x " +
                        std::to_string(s.tensor_shape[2]);
            std::string ranks = "-";
            if (s.model)
                ranks = std::to_string(s.model_ranks[0]) + " x " + std::to_string(s.model_ranks[1]) + " x " +
                        std::to_string(s.model_ranks[2]);
            std::printf("%-24s %8zu %11zu  %-24s %9.1f  %-16s %.1f\n", s.name.c_str(), s.samples,
                        s.parameter_names.size(), shape.c_str(), static_cast<double>(s.tensor_stored_bytes) / 1e3,
                        ranks.c_str(), static_cast<double>(s.model_stored_bytes) / 1e3);
        }
    }
}

}  // namespace

void print_database_info(const std::string& file, bool json) {
    const Database db(file);
    const std::vector<ClipRecord> clips = db.clips();
    const std::vector<SetRecord> sets = db.sets();
    if (json) {
        print_json(file, db, clips, sets);
    } else {
        print_text(file, db, clips, sets);
    }
}

}  // namespace mocapdb::cli
