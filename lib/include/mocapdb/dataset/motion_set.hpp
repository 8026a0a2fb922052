#pragma once
// A motion set: an ordered list of comparable samples (whole clips or frame ranges of clips) that
// share one skeleton, each with a control-parameter vector.
#include <string>
#include <vector>

#include "mocapdb/core/types.hpp"

namespace mocapdb {

/// Frames [begin, end) of a stored clip.
struct SampleRef {
    std::string clip;       ///< clip id in the database
    std::size_t begin = 0;  ///< first frame
    std::size_t end = 0;    ///< one past the last frame
    std::size_t frame_count() const noexcept { return end - begin; }
};

/// Frames of a stored clip whose joint was repaired when the set's samples were taken from it (a
/// solver dropout, see dropout_repair.hpp): joint `joint` at clip frames [begin, end).
struct RepairedFrames {
    std::string clip;
    std::string joint;
    std::size_t begin = 0;
    std::size_t end = 0;
};

struct MotionSet {
    std::string name;
    std::vector<SampleRef> samples;            ///< N samples
    std::vector<std::string> parameter_names;  ///< P names
    std::vector<std::string> parameter_units;  ///< P units ("cm", "rad", "cm/s", "" ...)
    MatX parameters;                           ///< N by P control parameters
    /// Periods of periodic parameters (e.g. 2 pi for a bearing in rad), 0 for a linear one: P values, or
    /// empty when every parameter is linear. Kriging measures distances along a periodic axis on a
    /// circle (kriging/trend.hpp ControlScaling), so c and c + period are the same request.
    VecX parameter_periods;
    /// Levels of categorical parameters (docs/synthesis.md, "Categorical parameters"): P lists, or empty
    /// when every parameter is numeric. A categorical parameter has >= 2 level names and its column of
    /// `parameters` holds level indices 0 .. L-1 (so the matrix stays numeric); a numeric one has none.
    std::vector<std::vector<std::string>> parameter_levels;
    std::string parameter_source;  ///< how they were obtained ("extract:...; csv:FILE; category:...")
    /// True when the clips were checked for dropouts as the set was built (sets stored before that
    /// check existed read as false and are taken as stored, unrepaired).
    bool dropouts_checked = false;
    /// The repaired runs of the set's clips (with dropouts_checked; clip order, then joint, frame).
    /// Samples are the clips' frames with these repairs applied (with_repairs, dropout_repair.hpp).
    std::vector<RepairedFrames> repairs;
};

/// Throws InvalidArgument unless: a non-empty name, at least one sample, every sample has at least
/// two frames, the parameter matrix is N by P with P names and P units, all finite; parameter_periods
/// empty or P finite values >= 0; parameter_levels empty or P lists, each empty or >= 2 distinct
/// names, whose column holds level indices in [0, L) and which is not periodic.
void validate(const MotionSet& set);

/// True when parameter p has levels (a categorical parameter).
bool is_categorical(const MotionSet& set, std::size_t p);
/// Number of levels per parameter (0 for a numeric one): P values, or empty when none is categorical
/// (the form kriging::ControlScaling::levels takes).
std::vector<int> parameter_level_counts(const MotionSet& set);
/// The index of level `level` of categorical parameter p. InvalidArgument listing the known levels
/// when there is no such level.
Eigen::Index level_index(const MotionSet& set, std::size_t p, const std::string& level);

/// Appends a categorical parameter `name` whose level for each sample is `levels[i]` (N values): the
/// level names are the distinct values, sorted. InvalidArgument for a name the set already has, fewer
/// than 2 distinct levels, or a level with fewer than kMinSamplesPerLevel samples (naming it).
inline constexpr std::size_t kMinSamplesPerLevel = 2;
void add_categorical_parameter(MotionSet& set, const std::string& name, const std::vector<std::string>& levels);

/// The level of each sample from its clip id: the first group of `pattern` (ECMAScript regex) searched
/// in the id as std::regex_search does. InvalidArgument for a bad pattern, one without a group, or a
/// clip the pattern does not match (naming it).
std::vector<std::string> levels_from_clip_names(const MotionSet& set, const std::string& pattern);

/// Marks parameter `name` periodic with `period` (> 0, finite; in the parameter's unit), or linear with 0.
/// InvalidArgument naming the set's parameters when there is no such parameter, or for a bad period.
void set_parameter_period(MotionSet& set, const std::string& name, double period);

/// Throws InvalidArgument, saying why, when the set cannot serve to tell motions apart by their
/// parameters: fewer than 2 samples, or (with parameters) every sample at the same parameter vector
/// (kriging would get a degenerate kernel and give one motion for every request). Checked where sets
/// are created; stored sets of earlier versions still load.
void check_distinguishable(const MotionSet& set);

// Requests. Control parameters given as text (a synthesis at "style=happy, turn=1.0"): the items are
// either all positional (one per parameter, in the set's order) or all named ("NAME=VALUE", any order,
// each parameter once). A numeric parameter takes a finite number in its unit, a categorical one a
// level name (docs/synthesis.md, "Categorical parameters").
//
// Errors: InvalidArgument saying what was expected (the set's parameters with units, or a categorical
// parameter's levels) and what was found.

/// The request as the set's P-vector (a level as its index). Items are trimmed of blanks.
VecX parameter_request(const MotionSet& set, const std::vector<std::string>& items);

/// "name [unit], style {walk|run}, ..." of the set's parameters, for messages.
std::string describe_parameters(const MotionSet& set);

/// A value of parameter p as text: the level name of a categorical one, else the number (%g).
std::string parameter_value_text(const MotionSet& set, std::size_t p, double value);

}  // namespace mocapdb
