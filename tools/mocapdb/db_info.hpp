#pragma once
// mocapdb info on a database file (dispatched from cmd_info.cpp when the file is HDF5).
#include <string>

namespace mocapdb::cli {

/// Prints what the database holds: clips, skeletons, sets, shapes and sizes; JSON with `json`.
void print_database_info(const std::string& file, bool json);

}  // namespace mocapdb::cli
