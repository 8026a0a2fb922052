#pragma once
// CMU / Acclaim skeleton (ASF) and motion (AMC) files.
//
// Details: docs/headers/io.md (mocapdb/io/asf_amc.hpp).
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "mocapdb/core/diagnostics.hpp"
#include "mocapdb/motion/clip.hpp"

namespace mocapdb {

struct AmcReadOptions {
    /// AMC files do not store their rate; CMU captured at 120 Hz.
    double frame_rate = 120.0;
    /// Refuse defects instead of working around them.
    bool strict = false;
};

/// Parses ASF text; `source_name` names the file in errors. Throws ParseError ("FILE:LINE:COL: ...")
/// on malformed input: unknown sections/fields/axis orders, bones missing from or repeated in
/// :hierarchy, cycles, non-finite or absurd numbers, unsupported dofs.
Skeleton parse_asf(std::string_view text, const std::string& source_name);
/// Reads and parses an ASF file (IoError when it cannot be read).
std::shared_ptr<const Skeleton> read_asf(const std::filesystem::path& path);

/// Parses AMC text against its ASF skeleton. Throws ParseError on malformed input (see the policies
/// above); defects it works around are appended to `out_warnings`. Clip::name is the stem of
/// `source_name`; the rate is options.frame_rate. InvalidArgument for a null skeleton or a bad rate.
Clip parse_amc(std::string_view text, const std::string& source_name, std::shared_ptr<const Skeleton> skeleton,
               const AmcReadOptions& options = {}, Warnings* out_warnings = nullptr);
Clip read_amc(const std::filesystem::path& path, std::shared_ptr<const Skeleton> skeleton,
              const AmcReadOptions& options = {}, Warnings* out_warnings = nullptr);

/// The skeleton file of an AMC by the CMU naming: "NN_MM.amc" -> "NN.asf" in the same folder, if it exists.
std::optional<std::filesystem::path> find_asf_for_amc(const std::filesystem::path& amc_path);

}  // namespace mocapdb
