#pragma once
// Control parameters measured from a motion sample. Exact definitions (the sample is frames
// [begin, end) of a clip; p(f) is the global root position, ψ(f) the root heading about +Y,
// unwrapped along the sample, 0 when facing the skeleton's rest forward direction (+Z for CMU)).
//
// Details: docs/headers/dataset.md (mocapdb/dataset/param_extractors.hpp).
#include <string>
#include <vector>

#include "mocapdb/core/types.hpp"
#include "mocapdb/dataset/foot_contacts.hpp"
#include "mocapdb/motion/clip.hpp"

namespace mocapdb {

enum class ParameterKind { Displacement, Turn, Speed, Reach, Jump, Bearing };

struct ParameterExtractor {
    ParameterKind kind = ParameterKind::Turn;
    std::string joint;            ///< Reach: the end effector
    std::string at;               ///< Reach: "F", "end" or "P%"
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
