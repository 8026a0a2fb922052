// mocapdb info FILE: what a clip file holds (skeleton, frames, rate, duration, channels).
#include <cstdio>
#include <iostream>

#include "clip_options.hpp"
#include "commands.hpp"
#include "db_info.hpp"
#include "json_writer.hpp"
#include "mocapdb_json/clip_json.hpp"
#include "mocapdb/motion/figure_height.hpp"
#include "mocapdb/store/database.hpp"

namespace mocapdb::cli {
namespace {

struct InfoArgs {
    std::string file;
    ClipOptions clip;
    bool json = false;
    bool tree = false;
};

void print_json(const std::string& file, const Clip& clip) {
    JsonWriter j;
    json::write_clip_info(j, file, clip);
    std::cout << j.str();
}

void print_tree(const Skeleton& s, std::size_t index, int depth) {
    const Joint& joint = s.joint(index);
    std::printf("  %*s%s", 2 * depth, "", joint.name.c_str());
    if (!joint.channels.empty()) {
        std::printf("  [");
        for (std::size_t k = 0; k < joint.channels.size(); ++k)
            std::printf("%s%s", k ? " " : "", to_string(joint.channels[k]).c_str());
        std::printf("]");
    }
    std::printf("\n");
    for (std::size_t c = index + 1; c < s.size(); ++c)
        if (s.joint(c).parent == static_cast<int>(index)) print_tree(s, c, depth + 1);
}

void print_text(const std::string& file, const Clip& clip, bool tree) {
    const Skeleton& s = *clip.skeleton;
    std::size_t end_sites = 0;
    for (const Joint& j : s.joints()) end_sites += j.end_site ? 1 : 0;
    std::printf("file        %s\n", file.c_str());
    std::printf("joints      %zu (%zu end sites), root '%s'", s.size(), end_sites, s.joint(0).name.c_str());
    if (s.motion_root() != 0) std::printf(", body carried by '%s'", s.joint(s.motion_root()).name.c_str());
    std::printf("\n");
    if (clip.frame_count() > 0)
        std::printf("height      %.1f cm (frame 0, lowest to highest joint)\n", figure_height(s, clip.frame(0)));
    else std::printf("height      - (no frames)\n");
    std::printf("channels    %zu per frame\n", s.channel_count());
    std::printf("frames      %zu\n", clip.frame_count());
    std::printf("frame rate  %.6g Hz\n", clip.frame_rate);
    std::printf("duration    %.3f s\n", clip.duration());
    if (tree) {
        std::printf("hierarchy\n");
        print_tree(s, 0, 0);
    }
}

}  // namespace

void setup_info(CLI::App& app) {
    auto args = std::make_shared<InfoArgs>();
    CLI::App* cmd = app.add_subcommand("info", "Describe a motion file: skeleton, frames, rate, duration, channels");
    cmd->footer(
        "Examples:\n"
        "  mocapdb info walk.bvh\n"
        "  mocapdb info 16_15.amc --asf 16.asf --json\n"
        "JSON keys: file, frames, frame_rate (Hz), duration (s), channels (values per frame),\n"
        "figure_height_cm (frame 0, lowest to highest joint), root, motion_root (the joint that carries\n"
        "the body: a static ROOT's only child), position_channels (replace_offset or add_to_offset),\n"
        "joints (array of {name, parent, end_site, offset_cm, channels}).\n"
        "On a database file (mocapdb info cmu.h5 --json) the keys are: file, format, format_version,\n"
        "file_bytes, clip_count, total_frames, total_seconds, clips (array of {id, frames, frame_rate,\n"
        "duration, channels, skeleton, source_file, source_format, source_sha256, source_skeleton_file,\n"
        "subject, description, labels, stored_bytes}), skeletons ({id, source_file, joints, channels}),\n"
        "sets ({name, samples, parameters, parameter_source, aligned, tensor_dims, tensor_shape,\n"
        "tensor_stored_bytes, model, model_ranks (R1, R2, R3) or null, model_stored_bytes}).");
    cmd->add_option("file", args->file, "BVH file, AMC file (with --asf or NN.asf beside it), or database (.h5)")
        ->required()
        ->check(CLI::ExistingFile);
    add_clip_options(*cmd, args->clip);
    cmd->add_flag("--json", args->json, "print JSON instead of a table");
    cmd->add_flag("--tree", args->tree, "also print the joint hierarchy");
    cmd->callback([args] {
        if (is_hdf5_file(args->file)) {  // a motion database: see db_info.cpp
            print_database_info(args->file, args->json);
            return;
        }
        const Clip clip = load_clip(args->file, args->clip, std::cerr);
        const std::string tall = clip.frame_count() > 0
                                     ? figure_height_warning(figure_height(*clip.skeleton, clip.frame(0)))
                                     : std::string();
        if (!tall.empty()) std::cerr << "mocapdb: warning: " << args->file << ": " << tall << " (--bvh-positions)\n";
        if (args->json) {
            print_json(args->file, clip);
        } else {
            print_text(args->file, clip, args->tree);
        }
    });
}

}  // namespace mocapdb::cli
