#pragma once
// Where things live in a database file (see schemas/format-v3.md), and the one place where Eigen's
// column-major layout meets HDF5's C order.
#include <string>
#include <vector>

#include "h5/file.hpp"
#include "mocapdb/core/types.hpp"
#include "mocapdb/dataset/aligned_set.hpp"

namespace mocapdb::store {

inline const std::string kSkeletons = "/skeletons";
inline const std::string kClips = "/clips";
inline const std::string kSets = "/sets";
inline const std::string kPacked = "/packed";

inline std::string skeleton_path(const std::string& id) { return kSkeletons + "/" + id; }
inline std::string clip_path(const std::string& id) { return kClips + "/" + id; }
inline std::string set_path(const std::string& name) { return kSets + "/" + name; }
inline std::string aligned_path(const std::string& set) { return set_path(set) + "/aligned"; }
inline std::string repairs_path(const std::string& set) { return set_path(set) + "/repairs"; }
inline std::string packed_group_path(const std::string& group) { return kPacked + "/" + group; }
inline std::string model_path(const std::string& set) { return set_path(set) + "/model"; }
inline std::string kernel_path(const std::string& set) { return model_path(set) + "/kernel"; }

/// "/a/b/c" -> {"a", "b", "c"}.
std::vector<std::string> split_path(const std::string& path);

/// InvalidArgument unless `name` can be one HDF5 link name: non-empty, no '/', not "." or "..",
/// no control characters. `what` names it in the message ("clip id", "set name").
void check_link_name(const std::string& name, const char* what);

/// The C-order shape of a column-major (dof, time, sample) tensor: (sample, time, dof). Eigen's
/// column-major buffer of a D×T×N tensor IS the C-order buffer of an N×T×D array (element (d,t,s) at
/// d + D·(t + T·s) in both), so the data is written and read as it is, with this shape.
h5::Shape c_order_shape(const Tensor3& tensor);
/// A column-major rows×cols matrix as a C-order [rows][cols] buffer, and back.
std::vector<double> to_c_order(const MatX& matrix);
MatX from_c_order(const std::vector<double>& data, Eigen::Index rows, Eigen::Index cols);

}  // namespace mocapdb::store
