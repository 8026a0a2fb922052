#pragma once
// The JSON document of `mocapdb eval DB --set NAME --json` (eval/set_evaluation.hpp): one object,
// keys in docs/evaluation.md. Formatting only; non-finite numbers (n/a) are written as null.
#include "mocapdb/eval/set_evaluation.hpp"
#include "mocapdb_json/json_writer.hpp"

namespace mocapdb::json {

void write_set_evaluation(JsonWriter& j, const eval::SetEvaluation& e);

}  // namespace mocapdb::json
