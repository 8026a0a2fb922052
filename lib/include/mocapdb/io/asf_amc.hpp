#pragma once
// CMU / Acclaim skeleton (ASF) and motion (AMC) files.
//
// The ASF skeleton becomes a Skeleton whose joints sit at the START of each ASF bone: joint "root",
// then one joint per bone (named as the bone, ordered parents first by the :hierarchy section), and
// an end site "<bone>_end" after every leaf bone. A bone's joint offset is its parent bone's vector
// (direction · length), so bone b's own vector is the offset of its children / end site. Each joint's
// rotation is C · R(dof) · C⁻¹ with C the bone's `axis` and R the dof rotations composed in the ASF
// sense (the dof listed first is applied first: "rx ry rz" means R = Rz·Ry·Rx).
// Units: lengths are converted to centimetres as cm = value / (:units length) · 2.54 (CMU's FAQ:
// the file's lengths are inches times the length factor); angles by `:units angle` (deg or rad).
//
// Reading choices (the Acclaim text leaves them open):
// - `axis a b c ORDER` (and the root's `orientation` with its `axis ORDER`): a, b, c are the angles
//   about X, Y, Z; ORDER is the sequence, first letter applied first ("XYZ": C = Rz(c)·Ry(b)·Rx(a)).
// - Root `order`: any subset/permutation of TX TY TZ RX RY RZ; it is the root's channel order. The
//   root's offset is its `position`; position channels add to it.
// - dof `l` (bone stretch) is refused (ParseError): skeletons have fixed bone lengths. Bone dofs tx,
//   ty, tz become position channels, accepted only on bones with axis 0 0 0 (otherwise they would move
//   along the wrong axes). `limits` are checked for syntax (one pair per dof, ±inf allowed) and dropped.
// - '#' starts a comment anywhere on a line; LF and CRLF are accepted; keywords are case-insensitive.
// - AMC: a bone line holds the joint's channel values in channel order (the ASF dof order). End sites
//   are not bones. :DEGREES / :RADIANS state the AMC's angle unit and win over the ASF's; a clash is a
//   warning. Frame numbers that do not count up by one are a warning (frames are kept in file order).
//   Every bone with dofs must appear exactly once per frame: a missing bone is a ParseError, except in
//   the file's last frame, which the file may have been cut inside: non-strict drops that frame with a
//   warning (the complete frames are kept, as the BVH reader does), strict refuses. Strict mode turns
//   every warning into a ParseError. No complete frame at all is a ParseError.
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
