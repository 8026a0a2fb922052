#pragma once
// results.json of `mocapdb eval`: the run's facts, per set its samples, methods, kernel headroom,
// leave-one-out, constraint, reduction and compression results, and the runtime table. Formatting
// only; no I/O. Keys: docs/json.md.
#include "mocapdb/eval/evaluation.hpp"
#include "mocapdb_json/json_writer.hpp"

namespace mocapdb::json {

void write_eval_results(JsonWriter& j, const eval::EvalResults& e);

}  // namespace mocapdb::json
