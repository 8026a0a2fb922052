#pragma once
// A clip as glTF 2.0 (.gltf with the buffer embedded, or binary .glb), written with Debian's tinygltf:
// one node per joint and end site (named as the skeleton names them, but see gltf_node_name; rest
// offsets as translations), one
// animation with every rotating joint's rotation and every translating joint's translation at the clip's
// frame times (linear), and bone shapes (an octahedron from each joint to each child, a mesh node under
// the joint named "mocapdb_bone:CHILD") so that viewers show a figure. Metres, Y up (glTF's units: the
// clip's cm / 100). Errors: IoError naming the file when it cannot be written (atomic: no partial file);
// InvalidArgument for a clip without frames.
#include <filesystem>
#include <ostream>
#include <string>

#include "mocapdb/motion/clip.hpp"

namespace mocapdb {

enum class GltfContainer { Gltf, Glb };

void write_gltf(const std::filesystem::path& path, const Clip& clip, GltfContainer container);
/// The same into a stream (IoError when the writer fails).
void write_gltf(std::ostream& out, const Clip& clip, GltfContainer container);

/// The prefix of the bone shapes' node names (what a reader skips to find the joints).
inline constexpr const char* kGltfBonePrefix = "mocapdb_bone:";

/// A joint's node name: its own, except "root", which three.js's animation binding reads as "the
/// animated object itself" (PropertyBinding): written "root_joint" so that three.js plays the file.
std::string gltf_node_name(const std::string& joint);

}  // namespace mocapdb
