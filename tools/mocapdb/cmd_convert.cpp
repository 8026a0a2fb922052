// mocapdb convert IN -o OUT.bvh: any supported clip to BVH.
#include <filesystem>
#include <iostream>

#include "clip_options.hpp"
#include "commands.hpp"
#include "output_files.hpp"
#include "mocapdb/core/error.hpp"
#include "mocapdb/io/bvh.hpp"

namespace mocapdb::cli {
namespace {

struct ConvertArgs {
    std::string input;
    std::string output;
    ClipOptions clip;
    int precision = 9;
    bool force = false;
};

}  // namespace

void setup_convert(CLI::App& app) {
    auto args = std::make_shared<ConvertArgs>();
    CLI::App* cmd = app.add_subcommand("convert", "Convert a BVH or ASF/AMC clip to BVH");
    cmd->footer(
        "Examples:\n"
        "  mocapdb convert 16_15.amc --asf 16.asf -o 16_15.bvh\n"
        "  mocapdb convert 02_01_60fps.bvh --fps 60 -o 02_01.bvh   (fixes a wrong Frame Time)");
    cmd->add_option("input", args->input, "BVH or AMC file")->required()->check(CLI::ExistingFile);
    cmd->add_option("-o,--output", args->output, "output BVH file")->required();
    add_clip_options(*cmd, args->clip);
    cmd->add_option("--precision", args->precision, "significant digits written")->check(CLI::Range(1, 17));
    cmd->add_flag("--force", args->force, "overwrite an existing output file");
    cmd->callback([args] {
        refuse_existing(args->output, args->force);
        const Clip clip = load_clip(args->input, args->clip, std::cerr);
        BvhWriteOptions options;
        options.precision = args->precision;
        write_bvh(std::filesystem::path(args->output), clip, options);
        std::cout << "wrote " << args->output << ": " << clip.frame_count() << " frames at " << clip.frame_rate
                  << " Hz, " << clip.skeleton->size() << " joints\n";
    });
}

}  // namespace mocapdb::cli
