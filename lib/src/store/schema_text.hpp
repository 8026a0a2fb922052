#pragma once
// The schema mirrors schemas/format-vN.json of every version this library reads, compiled in
// (generated from schema_text.cpp.in by lib/CMakeLists.txt).
namespace mocapdb::store {

/// The text of schemas/format-v{format_version}.json; nullptr for a version without a mirror.
const char* schema_json_text(int format_version);

}  // namespace mocapdb::store
