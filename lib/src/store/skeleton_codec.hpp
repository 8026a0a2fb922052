#pragma once
// A Skeleton as the group /skeletons/{id}: one dataset per joint field, one per channel field.
#include <string>

#include "h5/file.hpp"
#include "mocapdb/motion/skeleton.hpp"

namespace mocapdb::store {

void write_skeleton(h5::File& file, const std::string& id, const Skeleton& skeleton, const std::string& source_file);
/// StoreError naming the dataset for wrong dtypes or shapes, or the group for an invalid skeleton.
Skeleton read_skeleton(const h5::File& file, const std::string& id);

}  // namespace mocapdb::store
