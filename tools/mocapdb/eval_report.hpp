#pragma once
// mocapdb eval: the writers of eval/REPORT.md, results.json, the CSV tables and the SVG figures
// (everything generated, nothing hand-edited) from the library's results and verdicts
// (mocapdb/eval/evaluation.hpp, verdicts.hpp). Formatting only.
#include <filesystem>

#include "mocapdb/eval/evaluation.hpp"

namespace mocapdb::cli {

/// Writes REPORT.md, results.json, *.csv and *.svg into `out` (created; existing files of these names
/// are replaced atomically).
void write_eval_report(const eval::EvalResults& results, const std::filesystem::path& out);

}  // namespace mocapdb::cli
