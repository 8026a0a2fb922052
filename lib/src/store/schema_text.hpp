#pragma once
// The schema mirror schemas/format-v1.json, compiled in (generated from schema_text.cpp.in).
namespace mocapdb::store {

const char* schema_v1_json_text();

}  // namespace mocapdb::store
