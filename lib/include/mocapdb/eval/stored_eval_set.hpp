#pragma once
// A motion set stored in a database (created and aligned by the workflow) as an EvalSet, so that the
// evaluation's leave-one-out runs on a user's own set: the stored samples (their clips' frames with
// the set's repairs), parameters (periods kept), aligned tensor, the first clip's skeleton and frame
// rate, and the extractors that measured the parameters (none for a CSV). Samples keep their own
// clip's skeleton. Errors: those of workflow::load_aligned_set (the set or its alignment missing,
// naming the set and the file), StoreError / IoError from the database.
#include <string>

#include "mocapdb/eval/eval_set.hpp"

namespace mocapdb {
class Database;
}

namespace mocapdb::eval {

EvalSet load_eval_set(const Database& db, const std::string& set);

}  // namespace mocapdb::eval
