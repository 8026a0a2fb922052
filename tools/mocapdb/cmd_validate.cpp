// mocapdb validate DB.h5: check a database file against the format specification.
#include <iostream>
#include <string>

#include "commands.hpp"
#include "mocapdb/core/error.hpp"
#include "mocapdb/io/text_file.hpp"
#include "mocapdb/store/validate.hpp"
#include "progress_bar.hpp"

namespace mocapdb::cli {
namespace {

struct ValidateArgs {
    std::string file;
    std::size_t max = 20;
    std::string schema;
};

void run_validate(const ValidateArgs& args) {
    ValidateOptions options;
    options.max_violations = args.max;
    if (!args.schema.empty()) options.schema_json = read_text_file(args.schema);
    ValidationReport report;
    {
        ProgressBar bar("validate");
        options.progress = bar.callback();
        report = validate_database(args.file, options);
    }
    const std::string what = report.format_version > 0
                                 ? "mocapdb format " + std::to_string(report.format_version) + " file"
                                 : std::string("mocapdb file");
    if (report.ok()) {
        std::cout << args.file << ": valid " << what << " (" << report.objects << " objects checked, "
                  << report.datasets_read << " datasets read, checksums verified)\n";
        return;
    }
    for (const Violation& v : report.violations) std::cout << "  " << v.path << ": " << v.message << "\n";
    std::string count = std::to_string(report.violations.size()) + (report.truncated ? "+" : "");
    throw Error(args.file + ": not a valid " + what + ": " + count + " violation" +
                (report.violations.size() == 1 && !report.truncated ? "" : "s") + " (listed above" +
                (report.truncated ? ", first " + std::to_string(report.violations.size()) + " shown" : "") + ")");
}

}  // namespace

void setup_validate(CLI::App& app) {
    auto args = std::make_shared<ValidateArgs>();
    CLI::App* cmd = app.add_subcommand("validate", "Check a motion database file against the format specification");
    cmd->footer(
        "Checks every group, dataset and attribute against the mirror of the file's version,\n"
        "schemas/format-v1.json to format-v4.json (kinds, dtypes, dims, shapes, filters, values; for\n"
        "version 4 first that every top-level object links to an existing segment in DB.h5.d/), reads\n"
        "every dataset (verifying its fletcher32 checksums) and checks the content rules (every clip\n"
        "decodes and is finite, with columns matching its skeleton; set samples lie within stored clips,\n"
        "aligned tensors match their set, models match their aligned tensor).\n"
        "Exit code 0 when valid; 1 with the first violations otherwise.\n"
        "Example:\n"
        "  mocapdb validate cmu.h5");
    cmd->add_option("file", args->file, "database file")->required()->check(CLI::ExistingFile);
    cmd->add_option("--max", args->max, "violations to list at most (default 20)")->check(CLI::PositiveNumber);
    cmd->add_option("--schema", args->schema, "check against this schema mirror (JSON) instead of the built-in one")
        ->check(CLI::ExistingFile);
    cmd->callback([args] { run_validate(*args); });
}

}  // namespace mocapdb::cli
