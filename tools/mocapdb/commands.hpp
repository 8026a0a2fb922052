#pragma once
// Every subcommand lives in its own cmd_<name>.cpp and registers itself here.
#include <CLI/CLI.hpp>

namespace mocapdb::cli {

void setup_info(CLI::App& app);
void setup_convert(CLI::App& app);

}  // namespace mocapdb::cli
