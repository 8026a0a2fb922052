// mocapdb import FILES|DIRS... -o DB.h5: store clips in a motion database (atomic, appending).
#include <chrono>
#include <cstdio>
#include <iostream>

#include "commands.hpp"
#include "mocapdb/core/error.hpp"
#include "mocapdb/store/import.hpp"
#include "progress_bar.hpp"

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
};

std::string megabytes(std::uint64_t bytes) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.1f MB", static_cast<double>(bytes) / 1e6);
    return buffer;
}

void run_import(const ImportArgs& args) {
    namespace fs = std::filesystem;
    std::vector<fs::path> inputs(args.inputs.begin(), args.inputs.end());
    const std::vector<fs::path> files = collect_clip_files(inputs);
    if (files.empty()) throw InvalidArgument("no .bvh or .amc files found in the given inputs");
    Manifest manifest;
    ImportOptions options;
    if (!args.manifest.empty()) {
        manifest = Manifest::read(args.manifest);
        options.manifest = &manifest;
    }
    options.asf = args.asf;
    if (args.fps > 0.0) options.frame_rate = args.fps;
    options.strict = args.strict;

    const fs::path db = args.output;
    std::error_code ec;
    const bool existed = fs::exists(db, ec);
    const auto mode = args.force ? DatabaseWriter::Mode::Create : DatabaseWriter::Mode::OpenOrCreate;
    std::unique_ptr<DatabaseWriter> writer;
    try {
        writer = std::make_unique<DatabaseWriter>(db, mode);
    } catch (const StoreError& e) {
        throw StoreError(e.file(), e.object_path(),
                         e.message() + " (import appends to a mocapdb database; --force replaces the file with a new one)");
    }

    const auto start = std::chrono::steady_clock::now();
    ProgressBar bar("import");
    const ImportSummary summary = import_files(*writer, files, options, bar.callback(), [&](const ImportedFile& f) {
        if (f.warnings.empty() && f.result.added) return;
        bar.clear();
        for (const Warning& w : f.warnings) std::cerr << "mocapdb: warning: " << w.to_string() << "\n";
        if (!f.result.added) std::cout << f.file.string() << ": " << f.result.message << "\n";
    });
    bar.clear();
    if (summary.added > 0 || !existed || args.force) writer->commit();
    writer.reset();
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    const Database view(db);
    const std::size_t clips = view.clips().size();
    char line[512];
    std::snprintf(line, sizeof line,
                  "imported %zu clip%s (%zu skipped as duplicates): %zu frames, %.1f s of motion; read %s in %.2f s "
                  "(%.1f MB/s, %.1f clips/s); %s now holds %zu clips, %s\n",
                  summary.added, summary.added == 1 ? "" : "s", summary.skipped, summary.frames, summary.seconds,
                  megabytes(summary.bytes_read).c_str(), seconds,
                  seconds > 0 ? static_cast<double>(summary.bytes_read) / 1e6 / seconds : 0.0,
                  seconds > 0 ? static_cast<double>(summary.files) / seconds : 0.0, db.string().c_str(), clips,
                  megabytes(view.file_size()).c_str());
    std::cout << line;
}

}  // namespace

void setup_import(CLI::App& app) {
    auto args = std::make_shared<ImportArgs>();
    CLI::App* cmd = app.add_subcommand("import", "Store BVH and ASF/AMC clips in a motion database (HDF5)");
    cmd->footer(
        "Folders are searched recursively for *.bvh and *.amc; NN_MM.amc uses NN.asf beside it unless --asf\n"
        "is given. An existing database is appended to (a file whose sha256 is already stored is skipped);\n"
        "--force starts a new database instead. The file is replaced atomically at the end: an interrupted\n"
        "import leaves it as it was.\n"
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
        ->check(CLI::PositiveNumber);
    cmd->add_option("--manifest", args->manifest, "CSV with per-file subject, description, labels, fps")
        ->check(CLI::ExistingFile);
    cmd->add_flag("--strict", args->strict, "refuse file defects instead of working around them");
    cmd->add_flag("--force", args->force, "replace an existing output file with a new database");
    cmd->callback([args] { run_import(*args); });
}

}  // namespace mocapdb::cli
