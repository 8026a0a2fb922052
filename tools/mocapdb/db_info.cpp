#include "db_info.hpp"

#include <cstdio>
#include <iostream>

#include "json_writer.hpp"
#include "mocapdb_json/database_json.hpp"
#include "mocapdb/workflow/database_summary.hpp"

namespace mocapdb::cli {
namespace {

using workflow::DatabaseSummary;

void print_json(const std::string& file, const DatabaseSummary& d) {
    JsonWriter j;
    json::write_database_info(j, file, d);
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
