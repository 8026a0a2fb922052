#include "db_info.hpp"

#include <cstdio>
#include <iostream>

#include "json_writer.hpp"
#include "mocapdb/workflow/database_summary.hpp"

namespace mocapdb::cli {
namespace {

using workflow::DatabaseSummary;

void print_json(const std::string& file, const DatabaseSummary& d) {
    const std::vector<ClipRecord>& clips = d.clips;
    const std::optional<PackedTierRecord>& tier = d.packed;
    JsonWriter j;
    j.begin_object();
    j.key("file").value(file);
    j.key("format").value("mocapdb");
    j.key("format_version").value(d.format_version);
    j.key("file_bytes").value(static_cast<std::size_t>(d.file_bytes));
    j.key("clip_count").value(clips.size());
    j.key("total_frames").value(d.total_frames);
    j.key("total_seconds").value(d.total_seconds);
    j.key("clips").begin_array();
    for (std::size_t i = 0; i < clips.size(); ++i) {
        const ClipRecord& c = clips[i];
        const std::optional<workflow::PackedClipEntry>& packed = d.packed_clips[i];
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
        if (packed) j.value("packed");
        j.end_array();
        j.key("lossless_bytes").value(static_cast<std::size_t>(c.stored_bytes));
        if (packed) {
            j.key("packed_group").value(packed->group);
            j.key("packed_payload_bytes").value(static_cast<std::size_t>(packed->clip.payload_bytes));
            j.key("packed_max_cm").value(packed->clip.max_cm);
        } else {
            j.key("packed_group").null();
            j.key("packed_payload_bytes").null();
            j.key("packed_max_cm").null();
        }
        j.end_object();
    }
    j.end_array();
    j.key("skeletons").begin_array();
    for (const workflow::SkeletonSummary& s : d.skeletons) {
        j.begin_object();
        j.key("id").value(s.id);
        j.key("source_file").value(s.source_file);
        j.key("joints").value(s.joints);
        j.key("channels").value(s.channels);
        j.end_object();
    }
    j.end_array();
    j.key("sets").begin_array();
    for (const SetRecord& s : d.sets) {
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

void print_text(const std::string& file, const DatabaseSummary& d) {
    const std::vector<ClipRecord>& clips = d.clips;
    const std::vector<SetRecord>& sets = d.sets;
    std::printf("file        %s (%.1f MB)\n", file.c_str(), static_cast<double>(d.file_bytes) / 1e6);
    std::printf("format      mocapdb %d\n", d.format_version);
    std::printf("clips       %zu: %zu frames, %.1f s of motion, channels %.1f MB stored\n", clips.size(),
                d.total_frames, d.total_seconds, static_cast<double>(d.total_stored_bytes) / 1e6);
    std::printf("skeletons   %zu\n", d.skeletons.size());
    std::printf("sets        %zu\n", sets.size());
    const std::optional<PackedTierRecord>& tier = d.packed;
    if (tier) {
        std::printf(
            "packed      %zu clips in %zu groups at max error %g cm: %.1f kB (max %.4f cm, p99 %.4f cm, RMSE %.4f cm)\n",
            tier->clips, tier->groups.size(), tier->max_error_cm, static_cast<double>(tier->bytes) / 1e3, tier->max_cm,
            tier->p99_cm, tier->rmse_cm);
    } else {
        std::printf("packed      none (mocapdb pack)\n");
    }
    if (!clips.empty()) {
        std::printf("\n%-24s %8s %8s %9s %9s %9s  %-17s %-14s %s\n", "clip", "frames", "rate Hz", "seconds",
                    "stored kB", "packed kB", "tiers", "skeleton", "source");
        for (std::size_t i = 0; i < clips.size(); ++i) {
            const ClipRecord& c = clips[i];
            const std::optional<workflow::PackedClipEntry>& packed = d.packed_clips[i];
            char packed_kb[32] = "-";
            if (packed)
                std::snprintf(packed_kb, sizeof packed_kb, "%.1f",
                              static_cast<double>(packed->clip.payload_bytes) / 1e3);
            std::printf("%-24s %8zu %8.6g %9.2f %9.1f %9s  %-17s %-14s %s\n", c.id.c_str(), c.frames, c.frame_rate,
                        c.duration(), static_cast<double>(c.stored_bytes) / 1e3, packed_kb,
                        !c.lossless ? "packed"
                        : packed    ? "lossless+packed"
                                    : "lossless",
                        c.skeleton.c_str(), c.source.file_name.c_str());
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
    const DatabaseSummary summary = workflow::summarize_database(file);
    if (json) {
        print_json(file, summary);
    } else {
        print_text(file, summary);
    }
}

}  // namespace mocapdb::cli
