#pragma once
// Control parameters measured from a motion sample. Exact definitions (the sample is frames
// [begin, end) of a clip; p(f) is the global root position, ψ(f) the root heading about +Y,
// unwrapped along the sample, 0 when facing the skeleton's rest forward direction (+Z for CMU)):
//
//   displacement  dx, dz [cm]: p(end−1) − p(begin) on the floor (x, z), rotated by −ψ(begin) so that
//                 dz is forward and dx is to the character's left (+X when facing +Z) at the start.
//   turn          [rad]: ψ(end−1) − ψ(begin); positive = counter-clockwise seen from above (left).
//   speed         [cm/s]: horizontal path length Σ‖(p(f+1) − p(f))_xz‖ divided by the duration
//                 (end − 1 − begin) / frame rate.
//   reach:J@F     J_x, J_y, J_z [cm]: position of joint J at frame begin+F minus the root position
//                 at that frame, rotated by −ψ at that frame (x left, y up, z forward). F is a frame
//                 offset, or "end" for the last frame, or "P%" for a fraction of the sample.
//   bearing       [rad]: direction of travel, atan2(dx, dz) of `displacement` (0 = straight ahead of the
//                 start heading, + = to the left, in (-pi, pi]); periodic with period 2 pi. Undefined when
//                 the root travels less than 1 cm.
//   jump          [cm]: horizontal root travel between take-off and landing of the longest flight
//                 (the longest run of frames in which no foot is in contact, foot_contacts.hpp):
//                 ‖(p(landing) − p(takeoff))_xz‖, take-off = the last contact frame before the
//                 flight, landing = the first contact frame after it.
#include <string>
#include <vector>

#include "mocapdb/core/types.hpp"
#include "mocapdb/dataset/foot_contacts.hpp"
#include "mocapdb/motion/clip.hpp"

namespace mocapdb {

enum class ParameterKind { Displacement, Turn, Speed, Reach, Jump, Bearing };

struct ParameterExtractor {
    ParameterKind kind = ParameterKind::Turn;
    std::string joint;     ///< Reach: the end effector
    std::string at;        ///< Reach: "F", "end" or "P%"
    FootContactOptions contacts;  ///< Jump

    /// Parses "displacement", "turn", "speed", "jump", "bearing", "reach:JOINT@F". InvalidArgument otherwise.
    static ParameterExtractor parse(const std::string& spec);
    /// The spec this extractor parses from (parse(e.spec()) == e).
    std::string spec() const;
    /// Names and units of the columns this extractor produces (displacement 2, reach 3, others 1).
    std::vector<std::string> names() const;
    std::vector<std::string> units() const;
    /// Period of each column (2 pi for bearing), 0 for a linear one.
    std::vector<double> periods() const;
};

/// Values of every extractor, in order, for frames [begin, end) of the clip. InvalidArgument when a
/// quantity is undefined (a jump with no flight, a reach joint not in the skeleton, a frame outside).
VecX extract_parameters(const Clip& clip, std::size_t begin, std::size_t end,
                        const std::vector<ParameterExtractor>& extractors);

}  // namespace mocapdb
