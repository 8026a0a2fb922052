#pragma once
// A motion set as the group /sets/{name}, and its aligned form as /sets/{name}/aligned.
#include <string>

#include "h5/file.hpp"
#include "mocapdb/dataset/aligned_set.hpp"
#include "mocapdb/dataset/aligned_timing.hpp"
#include "mocapdb/dataset/motion_set.hpp"

namespace mocapdb::store {

void write_set(h5::File& file, const MotionSet& set);
/// StoreError naming the dataset for wrong dtypes or shapes (samples, parameters).
MotionSet read_set(const h5::File& file, const std::string& name);

void write_aligned(h5::File& file, const std::string& set, const AlignedSet& aligned);
/// StoreError naming the dataset for wrong dtypes or shapes (N, T, D must agree across datasets).
AlignedSet read_aligned(const h5::File& file, const std::string& set);
/// The aligned form's warps (checked as read_aligned checks them) and the tensor's D, from the
/// tensor's header (dtype float64, 3 dimensions): the tensor's values, mean, scale and
/// canonicalizations are not read.
AlignedTiming read_aligned_timing(const h5::File& file, const std::string& set);

}  // namespace mocapdb::store
