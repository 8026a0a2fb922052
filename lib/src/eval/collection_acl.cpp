#include "mocapdb/eval/collection_acl.hpp"

namespace mocapdb::eval {

CollectionAcl read_collection_acl(const std::vector<std::string>& tables) {
    CollectionAcl ref;
    if (tables.empty()) return ref;
    ref.given = true;
    for (std::size_t i = 0; i < tables.size(); ++i) {
        AclTable t = read_acl_table(tables[i]);
        if (i == 0) ref.table = std::move(t);
        else append(ref.table, std::move(t));
    }
    return ref;
}

void compare_collection_with_acl(CollectionAcl& ref, const CollectionReport& r) {
    if (!ref.given) return;
    ref.acl = aggregate_acl(ref.table, r.clip_names);
    if (r.clips == 0) ref.unusable = "the database has no clips";
    else if (!ref.acl.missing.empty())
        ref.unusable = std::to_string(ref.acl.missing.size()) + " of " + std::to_string(r.clips) +
                       " clips have no row in the reference (e.g. " + ref.acl.missing.front() +
                       "): ACL's bytes would not be for the same clips";
    else if (!ref.acl.complete()) ref.unusable = "not every clip has a row at every ACL setting in the reference";
    for (const TargetFigures& t : r.targets)
        ref.per_target.push_back(ref.unusable.empty() ? compare_with_acl(ref.acl, static_cast<double>(t.total.bytes),
                                                                         t.total.max_cm, t.total.rmse_cm)
                                                      : AclComparison{});
}

}  // namespace mocapdb::eval
