#pragma once
// `mocapdb report DB.h5 --collection`: runs the library's whole-collection benchmark
// (eval/collection_report.hpp), places it beside ACL (eval/acl_reference.hpp) and formats it as a
// text table, JSON, CSV and an SVG chart. Only parsing and formatting live here.
#include <string>
#include <vector>

namespace mocapdb::cli {

struct CollectionReportArgs {
    std::string db;
    std::vector<double> max_error_cm;      ///< empty: 1, 0.5, 0.1, 0.03, 0.01
    std::vector<std::string> references;   ///< per-clip ACL tables
    std::vector<std::string> source_dirs;  ///< where the clips' source files are (gzip -9)
    int threads = 2;
    std::size_t poses = 20000;
    bool json = false;
    std::string csv;
    std::string svg;
    bool force = false;
};

/// Runs the report and prints it (stdout); writes --csv / --svg. Throws mocapdb::Error.
void run_collection_report(const CollectionReportArgs& args);

}  // namespace mocapdb::cli
