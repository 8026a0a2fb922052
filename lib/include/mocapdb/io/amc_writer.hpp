#pragma once
// Writing CMU / Acclaim files: a Skeleton as ASF and a Clip as AMC, the inverse of the mapping in
// asf_amc.hpp (joints at bone starts, bone vector = the offset of the bone's children or of its end
// site "<bone>_end", axis C, dof order = channel order, cm = value / (:units length) · 2.54).
//
// Details: docs/headers/io.md (mocapdb/io/amc_writer.hpp).
#include <filesystem>
#include <iosfwd>
#include <string>

#include "mocapdb/motion/clip.hpp"

namespace mocapdb {

struct AsfWriteOptions {
    std::string name = "mocapdb";  ///< the :name line
};

struct AmcWriteOptions {
    int precision = 10;    ///< significant digits of every value (1..17; 17 is lossless for doubles)
    std::string asf_name;  ///< named in the "#!OML:ASF" header comment (informational)
};

/// Empty when the skeleton can be written as ASF; otherwise the first reason it cannot.
std::string asf_incompatibility(const Skeleton& skeleton);

/// Writes the skeleton as ASF text. InvalidArgument (with asf_incompatibility) when it cannot.
void write_asf(std::ostream& out, const Skeleton& skeleton, const AsfWriteOptions& options = {});
/// Atomic: writes a temporary file beside `path` and renames it over `path`.
void write_asf(const std::filesystem::path& path, const Skeleton& skeleton, const AsfWriteOptions& options = {});

/// Writes the clip's motion as AMC text (one line per bone with channels, in skeleton order; frames
/// numbered from 1; :DEGREES or :RADIANS as the skeleton's source units). InvalidArgument for an
/// invalid clip, bad options or a skeleton that is not ASF-compatible.
void write_amc(std::ostream& out, const Clip& clip, const AmcWriteOptions& options = {});
/// Atomic: writes a temporary file beside `path` and renames it over `path`.
void write_amc(const std::filesystem::path& path, const Clip& clip, const AmcWriteOptions& options = {});

}  // namespace mocapdb
