// results.json of `mocapdb eval` (eval_report_parts.hpp): the document of json/mocapdb_json/eval_json.hpp.
#include "eval_report_parts.hpp"

#include "json_writer.hpp"
#include "mocapdb_json/eval_json.hpp"

namespace mocapdb::cli::eval_report {

std::string results_json(const EvalResults& e) {
    JsonWriter j;
    json::write_eval_results(j, e);
    return j.str();
}

}  // namespace mocapdb::cli::eval_report
