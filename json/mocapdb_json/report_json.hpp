#pragma once
// The documents of `mocapdb report`: the rate-distortion table of a set (report --set, and the
// demo's "rate_distortion") and the whole-collection benchmark (report --collection; Python's
// collection_report returns the same keys). Formatting only; no I/O. Keys: docs/json.md.
#include <string>

#include "mocapdb/eval/collection_acl.hpp"
#include "mocapdb/eval/collection_report.hpp"
#include "mocapdb/workflow/set_rate_report.hpp"
#include "mocapdb_json/json_writer.hpp"

namespace mocapdb::json {

/// `reference`: eval::read_collection_acl of no table gives "reference": null and "acl": null.
void write_collection_report(JsonWriter& j, const std::string& db, const eval::CollectionReport& r,
                             const eval::CollectionAcl& reference);

/// {set, dims, raw_bytes, raw_clip_bytes, side_bytes, seconds_of_motion, rows}.
void write_rate_report(JsonWriter& j, const std::string& set, const workflow::RateOutcome& r);
/// "rows": [...] with every figure of each row, as a member of the open object.
void write_rate_rows(JsonWriter& j, const workflow::RateOutcome& r);

}  // namespace mocapdb::json
