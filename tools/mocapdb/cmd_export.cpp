// mocapdb export DB.h5 --clip ID -o OUT.bvh|.amc|.gltf|.glb: write a stored clip back to a motion file.
#include <iostream>

#include "commands.hpp"
#include "output_files.hpp"
#include "mocapdb/core/error.hpp"
#include "mocapdb/io/amc_writer.hpp"
#include "mocapdb/io/bvh.hpp"
#include "mocapdb/io/clip_file.hpp"
#include "mocapdb/io/gltf_writer.hpp"
#include "mocapdb/store/database.hpp"
#include "mocapdb/workflow/aligned_set_data.hpp"
#include "mocapdb/workflow/sample_export.hpp"

namespace mocapdb::cli {
namespace {

struct ExportArgs {
    std::string file;
    std::string clip;
    std::string output;
    std::string asf_output;
    int precision = 0;  // 0: the format's default
    bool force = false;
    std::string set;
    long long sample = -1;
    bool from_model = false;
    bool from_packed = false;
    std::string format;  // "gltf" | "glb": glTF whatever the extension; empty: by the extension
};

// Sample I of a set, from its aligned tensor or its stored model, back at its own timing.
Clip sample_clip(const Database& db, const ExportArgs& args) {
    const workflow::AlignedSetData c = workflow::load_aligned_set(db, args.set);
    const Eigen::Index n_samples = c.aligned.samples();
    if (args.sample < 0 || args.sample >= n_samples)
        throw InvalidArgument("--sample " + std::to_string(args.sample) + ": set '" + args.set + "' has samples 0.." +
                              std::to_string(n_samples - 1));
    const auto n = static_cast<Eigen::Index>(args.sample);
    Tensor3 poses;
    if (args.from_model) {
        auto stored = db.load_model(args.set);
        if (!stored)
            throw InvalidArgument("set '" + args.set + "' in " + args.file + " has no model (run: mocapdb compress " +
                                  args.file + " --set " + args.set + ")");
        poses = stored->model.reconstruct();
    } else {
        poses = c.aligned.tensor;
    }
    return workflow::sample_at_own_timing(c, poses, n, args.set + "_" + std::to_string(n));
}

// A clip or set sample as glTF (a node per joint, one animation, bone shapes).
void export_gltf(const Database& db, const ExportArgs& args, GltfContainer container) {
    const std::filesystem::path out = args.output;
    if (args.set.empty() && args.clip.empty()) throw InvalidArgument("give --clip ID, or --set S --sample I");
    if (args.set.empty() && !db.has_clip(args.clip))
        throw InvalidArgument(args.file + ": no clip '" + args.clip + "' (see mocapdb info)");
    const Clip clip = !args.set.empty()  ? sample_clip(db, args)
                      : args.from_packed ? db.load_clip_packed(args.clip)
                                         : db.load_clip(args.clip);
    refuse_existing(out, args.force);
    write_gltf(out, clip, container);
    std::cout << "wrote " << out.string() << " (glTF 2.0" << (container == GltfContainer::Glb ? " binary" : "") << ", "
              << clip.skeleton->size() << " joint nodes, " << clip.frame_count() << " frames at " << clip.frame_rate
              << " Hz, metres)\n";
}

void run_export(const ExportArgs& args) {
    namespace fs = std::filesystem;
    const fs::path out = args.output;
    const Database db(args.file);
    const std::string ext = out.extension().string();
    if (args.format == "gltf" || args.format == "glb" || ext == ".gltf" || ext == ".glb")
        return export_gltf(
            db, args,
            args.format == "glb" || (args.format.empty() && ext == ".glb") ? GltfContainer::Glb : GltfContainer::Gltf);
    const auto format = clip_format_of(out);
    if (!format) throw InvalidArgument(out.string() + ": unsupported output type (expected .bvh, .amc, .gltf or .glb)");
    if (!args.set.empty()) {
        if (*format != ClipFormat::Bvh) throw InvalidArgument(out.string() + ": a set sample is exported as .bvh");
        const Clip clip = sample_clip(db, args);
        refuse_existing(out, args.force);
        BvhWriteOptions o;
        if (args.precision > 0) o.precision = args.precision;
        write_bvh(out, clip, o);
        std::cout << "wrote " << out.string() << " (sample " << args.sample << " of set '" << args.set << "' "
                  << (args.from_model ? "reconstructed from its model" : "from its aligned tensor") << ", "
                  << clip.frame_count() << " frames at " << clip.frame_rate << " Hz)\n";
        return;
    }
    if (args.clip.empty()) throw InvalidArgument("give --clip ID, or --set S --sample I");
    if (!db.has_clip(args.clip)) throw InvalidArgument(args.file + ": no clip '" + args.clip + "' (see mocapdb info)");
    if (!args.from_packed && !db.find_clip(args.clip)->lossless)
        throw InvalidArgument(args.file + ": clip '" + args.clip +
                              "' has no lossless channels (dropped by mocapdb pack --drop-lossless); "
                              "export --from-packed writes it as decoded from the packed tier");
    const Clip clip = args.from_packed ? db.load_clip_packed(args.clip) : db.load_clip(args.clip);
    if (args.from_packed && *format != ClipFormat::Bvh)
        throw InvalidArgument(out.string() + ": a clip decoded from the packed tier is exported as .bvh");
    refuse_existing(out, args.force);
    if (*format == ClipFormat::Bvh) {
        BvhWriteOptions o;
        if (args.precision > 0) o.precision = args.precision;
        // A BVH source is written back in its own length unit; other sources in centimetres.
        if (db.find_clip(args.clip)->source.format == "bvh") o.cm_per_unit = clip.skeleton->source_units().cm_per_unit;
        write_bvh(out, clip, o);
        std::cout << "wrote " << out.string() << " (" << clip.frame_count() << " frames at " << clip.frame_rate
                  << " Hz";
        if (args.from_packed)
            std::cout << ", decoded from the packed tier: every joint within " << db.packed()->max_error_cm
                      << " cm of the source";
        std::cout << ")\n";
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
        "  mocapdb export cmu.h5 --clip 02_01_60fps -o 02_01.bvh\n"
        "  mocapdb export cmu.h5 --set walks --sample 3 --from-model -o walk3.bvh\n"
        "  mocapdb export cmu.h5 --clip 16_15 --from-packed -o 16_15_packed.bvh\n"
        "  mocapdb export cmu.h5 --clip 16_15 -o 16_15.glb     (glTF: Blender, three.js; metres, Y up)\n"
        "A set sample is written as BVH at its own timing (the alignment's warp undone) and in its own\n"
        "place in the world, from the aligned tensor or, with --from-model, from the stored Tucker model.");
    cmd->add_option("file", args->file, "database file")->required()->check(CLI::ExistingFile);
    auto* clip = cmd->add_option("--clip", args->clip, "clip id (see mocapdb info DB.h5)");
    auto* set = cmd->add_option("--set", args->set, "motion set (aligned) whose sample to export");
    auto* sample = cmd->add_option("--sample", args->sample, "sample index in the set (0-based)");
    auto* from_model = cmd->add_flag("--from-model", args->from_model, "reconstruct the sample from the set's model");
    clip->excludes(set);
    set->needs(sample);
    sample->needs(set);
    from_model->needs(set);
    auto* from_packed =
        cmd->add_flag("--from-packed", args->from_packed,
                      "decode the clip from the packed tier (mocapdb pack) instead of the lossless one");
    from_packed->needs(clip);
    cmd->add_option("-o,--output", args->output, "output file: .bvh, .amc, .gltf or .glb")->required();
    cmd->add_option("--format", args->format, "gltf | glb: write glTF whatever the extension")
        ->check(CLI::IsMember({"gltf", "glb"}));
    cmd->add_option("--asf-out", args->asf_output, "where to write the skeleton of an AMC export (default OUT.asf)");
    cmd->add_option("--precision", args->precision, "significant digits (default: BVH 9, AMC 10; 17 is lossless)")
        ->check(CLI::Range(1, 17));
    cmd->add_flag("--force", args->force, "overwrite existing output files");
    cmd->callback([args] { run_export(*args); });
}

}  // namespace mocapdb::cli
