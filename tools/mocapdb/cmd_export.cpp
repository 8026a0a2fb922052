// mocapdb export DB.h5 --clip ID -o OUT.bvh|OUT.amc: write a stored clip back to a motion file.
#include <iostream>

#include "commands.hpp"
#include "mocapdb/core/error.hpp"
#include "mocapdb/io/amc_writer.hpp"
#include "mocapdb/io/bvh.hpp"
#include "mocapdb/io/clip_file.hpp"
#include "mocapdb/store/database.hpp"

namespace mocapdb::cli {
namespace {

struct ExportArgs {
    std::string file;
    std::string clip;
    std::string output;
    std::string asf_output;
    int precision = 0;  // 0: the format's default
    bool force = false;
};

void refuse_existing(const std::filesystem::path& path, bool force) {
    std::error_code ec;
    if (!force && std::filesystem::exists(path, ec))
        throw IoError(path.string() + ": exists (pass --force to overwrite it)");
}

void run_export(const ExportArgs& args) {
    namespace fs = std::filesystem;
    const fs::path out = args.output;
    const auto format = clip_format_of(out);
    if (!format) throw InvalidArgument(out.string() + ": unsupported output type (expected .bvh or .amc)");
    const Database db(args.file);
    if (!db.has_clip(args.clip)) throw InvalidArgument(args.file + ": no clip '" + args.clip + "' (see mocapdb info)");
    const Clip clip = db.load_clip(args.clip);
    refuse_existing(out, args.force);
    if (*format == ClipFormat::Bvh) {
        BvhWriteOptions o;
        if (args.precision > 0) o.precision = args.precision;
        // A BVH source is written back in its own length unit; other sources in centimetres.
        if (db.find_clip(args.clip)->source.format == "bvh") o.cm_per_unit = clip.skeleton->source_units().cm_per_unit;
        write_bvh(out, clip, o);
        std::cout << "wrote " << out.string() << " (" << clip.frame_count() << " frames at " << clip.frame_rate
                  << " Hz)\n";
        return;
    }
    const std::string why = asf_incompatibility(*clip.skeleton);
    if (!why.empty())
        throw InvalidArgument("clip '" + args.clip + "' cannot be written as AMC: " + why + " (export it as .bvh)");
    fs::path asf = args.asf_output.empty() ? fs::path(out).replace_extension(".asf") : fs::path(args.asf_output);
    refuse_existing(asf, args.force);
    AsfWriteOptions ao;
    ao.name = db.find_clip(args.clip)->skeleton;
    write_asf(asf, *clip.skeleton, ao);
    AmcWriteOptions o;
    if (args.precision > 0) o.precision = args.precision;
    o.asf_name = asf.filename().string();
    write_amc(out, clip, o);
    std::cout << "wrote " << out.string() << " (" << clip.frame_count() << " frames at " << clip.frame_rate
              << " Hz) and its skeleton " << asf.string() << "\n";
}

}  // namespace

void setup_export(CLI::App& app) {
    auto args = std::make_shared<ExportArgs>();
    CLI::App* cmd = app.add_subcommand("export", "Write a stored clip as BVH, or as AMC with its ASF skeleton");
    cmd->footer(
        "A clip exported in its source format is written in its source units (length unit; degrees or\n"
        "radians), reproducing the source numbers; BVH export of an AMC clip writes centimetres. AMC\n"
        "export writes the skeleton beside it (OUT.asf unless --asf-out) and needs an ASF-shaped\n"
        "skeleton (clips imported from AMC); any clip can be exported as BVH. Outputs are never\n"
        "overwritten without --force.\n"
        "Examples:\n"
        "  mocapdb export cmu.h5 --clip 16_15 -o 16_15.amc      (reread: mocapdb info 16_15.amc --asf 16_15.asf)\n"
        "  mocapdb export cmu.h5 --clip 02_01_60fps -o 02_01.bvh");
    cmd->add_option("file", args->file, "database file")->required()->check(CLI::ExistingFile);
    cmd->add_option("--clip", args->clip, "clip id (see mocapdb info DB.h5)")->required();
    cmd->add_option("-o,--output", args->output, "output file: .bvh or .amc")->required();
    cmd->add_option("--asf-out", args->asf_output, "where to write the skeleton of an AMC export (default OUT.asf)");
    cmd->add_option("--precision", args->precision, "significant digits (default: BVH 9, AMC 10; 17 is lossless)")
        ->check(CLI::Range(1, 17));
    cmd->add_flag("--force", args->force, "overwrite existing output files");
    cmd->callback([args] { run_export(*args); });
}

}  // namespace mocapdb::cli
