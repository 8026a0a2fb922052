#pragma once
// The CLI's --json documents: the shared JsonWriter (json/mocapdb_json/json_writer.hpp).
#include "mocapdb_json/json_writer.hpp"

namespace mocapdb::cli {
using json::JsonWriter;
}  // namespace mocapdb::cli
