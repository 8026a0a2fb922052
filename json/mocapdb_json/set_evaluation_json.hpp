#pragma once
// The JSON document of `mocapdb eval DB --set NAME --json` (eval/set_evaluation.hpp): one object,
// keys in docs/evaluation.md. Formatting only; non-finite numbers (n/a) are written as null.
#include <string>
#include <vector>

#include "mocapdb/eval/set_evaluation.hpp"
#include "mocapdb_json/json_writer.hpp"

namespace mocapdb::json {

void write_set_evaluation(JsonWriter& j, const eval::SetEvaluation& e);

/// "twins": [{samples: [index], labels: [label]}], a key of the current object (also in set create's
/// document); labels[i] names sample i.
void write_twins(JsonWriter& j, const SampleTwins& twins, const std::vector<std::string>& labels);

}  // namespace mocapdb::json
