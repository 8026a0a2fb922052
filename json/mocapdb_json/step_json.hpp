#pragma once
// One JSON document per workflow step, shared by the CLI (`--json`) and Python (the same keys as a
// dict): import, set create, align, compress, pack. Each function writes one whole object into an
// empty JsonWriter (write_parts / write_joint_error: members of the open object). Formatting only;
// no I/O. Keys: docs/json.md. The collection report: report_json.hpp.
#include <cstddef>
#include <string>

#include "mocapdb/compression/joint_error.hpp"
#include "mocapdb/packing/byte_parts.hpp"
#include "mocapdb/workflow/clip_import.hpp"
#include "mocapdb/workflow/pack_collection.hpp"
#include "mocapdb/workflow/set_alignment.hpp"
#include "mocapdb/workflow/set_compression.hpp"
#include "mocapdb/workflow/set_creation.hpp"
#include "mocapdb_json/json_writer.hpp"

namespace mocapdb::json {

void write_import(JsonWriter& j, const std::string& db, const workflow::ImportOutcome& o);
void write_set(JsonWriter& j, const workflow::SetOutcome& o);
void write_alignment(JsonWriter& j, const std::string& set, const workflow::AlignOutcome& o);
void write_compression(JsonWriter& j, const std::string& set, const workflow::CompressOutcome& o);
void write_pack(JsonWriter& j, const std::string& db, const workflow::PackDatabaseOutcome& o);
/// `pack --drop-lossless` without a new tier: {file, dropped_lossless_clips}.
void write_dropped_lossless(JsonWriter& j, const std::string& db, std::size_t dropped);

/// Pieces the other documents also use (keys of the current object).
void write_parts(JsonWriter& j, const packing::ByteParts& parts);
void write_joint_error(JsonWriter& j, const compression::JointErrorStats& e);

}  // namespace mocapdb::json
