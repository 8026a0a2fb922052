#pragma once
// Every subcommand lives in its own cmd_<name>.cpp and registers itself here.
#include <CLI/CLI.hpp>

namespace mocapdb::cli {

void setup_info(CLI::App& app);
void setup_convert(CLI::App& app);
void setup_import(CLI::App& app);
void setup_pack(CLI::App& app);
void setup_validate(CLI::App& app);
void setup_export(CLI::App& app);
void setup_variogram(CLI::App& app);
void setup_krige(CLI::App& app);
void setup_set(CLI::App& app);
void setup_align(CLI::App& app);
void setup_generate(CLI::App& app);
void setup_compress(CLI::App& app);
void setup_report(CLI::App& app);
void setup_gp(CLI::App& app);
void setup_synth(CLI::App& app);
void setup_query(CLI::App& app);
void setup_reliability(CLI::App& app);
void setup_reduce(CLI::App& app);
void setup_demo(CLI::App& app);
void setup_eval(CLI::App& app);
void setup_serve(CLI::App& app);

}  // namespace mocapdb::cli
