#pragma once
// The whole collection's packed tier beside ACL (`mocapdb report --collection
// --reference`): the per-clip ACL tables read and appended, aggregated over the report's clips, and
// per max-error bound E the comparison of our bytes with ACL's at our measured error; or why no
// comparison is possible (no clips, clips without a row, an incomplete table). Nothing is printed.
// Errors: IoError / ParseError from the tables (acl_reference.hpp). Threads: no shared state.
#include <string>
#include <vector>

#include "mocapdb/eval/acl_reference.hpp"
#include "mocapdb/eval/collection_report.hpp"

namespace mocapdb::eval {

struct CollectionAcl {
    bool given = false;                     ///< tables were given
    AclTable table;                         ///< every table, appended in order
    AclCollection acl;                      ///< aggregated over the report's clips
    std::vector<AclComparison> per_target;  ///< per report target (empty comparisons when unusable)
    std::string unusable;                   ///< why there is no comparison ("" when there is one)
    bool usable() const { return given && unusable.empty(); }
};

/// Reads and appends the tables (none: given = false). Done before the long measurement, so that a
/// malformed table is refused at once.
CollectionAcl read_collection_acl(const std::vector<std::string>& tables);

/// Aggregates the tables over `report`'s clips and compares every target (no-op when not given).
void compare_collection_with_acl(CollectionAcl& reference, const CollectionReport& report);

}  // namespace mocapdb::eval
