// mocapdb import FILES|DIRS... -o DB.h5: store clips in a motion database (atomic, appending).
#include <iostream>

#include "clip_options.hpp"
#include "commands.hpp"
#include "json_writer.hpp"
#include "mocapdb_json/step_json.hpp"
#include "pipeline.hpp"

namespace mocapdb::cli {
namespace {

struct ImportArgs {
    std::vector<std::string> inputs;
    std::string output;
    std::string asf;
    double fps = 0.0;
    std::string manifest;
    bool strict = false;
    bool force = false;
    bool keep_going = false;
    std::string bvh_positions = "replace";
    bool json = false;
};

void run_import(const ImportArgs& args) {
    std::vector<std::filesystem::path> inputs(args.inputs.begin(), args.inputs.end());
    workflow::Manifest manifest;
    workflow::ImportOptions options;
    if (!args.manifest.empty()) {
        manifest = workflow::Manifest::read(args.manifest);
        options.manifest = &manifest;
    }
    options.asf = args.asf;
    if (args.fps > 0.0) options.frame_rate = args.fps;
    options.strict = args.strict;
    options.bvh_positions = bvh_positions_from_option(args.bvh_positions);
    options.keep_going = args.keep_going;
    const std::filesystem::path db = args.output;
    const ImportOutcome outcome = import_clips(db, inputs, options, args.force, args.json ? std::cerr : std::cout);
    if (args.json) {
        JsonWriter j;
        json::write_import(j, db.string(), outcome);
        std::cout << j.str();
    } else {
        std::cout << describe_import(db, outcome);
    }
    if (outcome.summary.failed > 0)
        throw Error(std::to_string(outcome.summary.failed) + (outcome.summary.failed == 1 ? " file" : " files") +
                    " could not be imported (errors above); " +
                    (outcome.summary.added > 0 ? "the other clips were stored" : "no clip was stored"));
}

}  // namespace

void setup_import(CLI::App& app) {
    auto args = std::make_shared<ImportArgs>();
    CLI::App* cmd = app.add_subcommand("import", "Store BVH and ASF/AMC clips in a motion database (HDF5)");
    cmd->footer(
        "Folders are searched recursively for *.bvh and *.amc; NN_MM.amc uses NN.asf beside it unless --asf\n"
        "is given. An existing database is appended to (a file whose sha256 is already stored is skipped);\n"
        "--force starts a new database instead. The file is replaced atomically at the end: an interrupted\n"
        "import leaves it as it was. An empty or unreadable file is reported and skipped, the others are\n"
        "stored, and the exit code is 1; when nothing is stored, nothing is created.\n"
        "Manifest CSV: header row with column 'file' (name or stem) and any of subject, description,\n"
        "labels (';'-separated), fps.\n"
        "Examples:\n"
        "  mocapdb import ../shared/datasets/cmu-asfamc -o cmu.h5\n"
        "  mocapdb import ../shared/datasets/cmu-walkrun-pfnn --fps 60 -o cmu.h5");
    cmd->add_option("inputs", args->inputs, "clip files and folders")->required()->check(CLI::ExistingPath);
    cmd->add_option("-o,--output", args->output, "database file to create or append to")->required();
    cmd->add_option("--asf", args->asf, "ASF skeleton for every AMC file (default: NN.asf beside NN_MM.amc)")
        ->check(CLI::ExistingFile);
    cmd->add_option("--fps", args->fps, "frame rate in Hz for every file (default: BVH Frame Time, AMC 120)")
        ->check(frame_rate_check());
    cmd->add_option("--manifest", args->manifest, "CSV with per-file subject, description, labels, fps")
        ->check(CLI::ExistingFile);
    cmd->add_flag("--strict", args->strict, "refuse file defects instead of working around them");
    add_bvh_positions_option(*cmd, args->bvh_positions);
    cmd->add_flag("--keep-going", args->keep_going,
                  "store the files that can be read, list the others with their errors (exit code 1 if any failed)");
    cmd->add_flag("--force", args->force, "replace an existing output file with a new database");
    cmd->add_flag("--json", args->json, "print one JSON object (the keys of Python's mocapdb.import_files)");
    cmd->callback([args] { run_import(*args); });
}

}  // namespace mocapdb::cli
