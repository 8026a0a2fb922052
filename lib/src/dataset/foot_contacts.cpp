#include "mocapdb/dataset/foot_contacts.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "mocapdb/core/error.hpp"
#include "mocapdb/core/remedy.hpp"
#include "mocapdb/motion/forward_kinematics.hpp"
#include "mocapdb/motion/pose_vector.hpp"

namespace mocapdb {
namespace {

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return s;
}

// The words of a joint name, lower case: split at non-alphanumerics and where a lower-case letter
// meets an upper-case one ("mixamorig:LeftToeBase" -> mixamorig, left, toe, base; "Foot_L" -> foot, l).
std::vector<std::string> name_words(const std::string& name) {
    std::vector<std::string> words(1);
    for (std::size_t i = 0; i < name.size(); ++i) {
        const auto c = static_cast<unsigned char>(name[i]);
        const bool boundary =
            !std::isalnum(c) || (i > 0 && std::isupper(c) && std::islower(static_cast<unsigned char>(name[i - 1])));
        if (boundary && !words.back().empty()) words.emplace_back();
        if (std::isalnum(c)) words.back() += static_cast<char>(std::tolower(c));
    }
    if (words.back().empty()) words.pop_back();
    return words;
}

// A name on one side: a word "l"/"left" (or starting with "left"), or the whole name starting with the
// side (CMU's lfoot, rtoes).
bool on_side(const std::string& name, const std::string& letter, const std::string& word) {
    for (const std::string& w : name_words(name))
        if (w == letter || w.rfind(word, 0) == 0) return true;
    const std::string n = lower(name);
    return n.rfind(letter, 0) == 0 || n.rfind(word, 0) == 0;
}

// First joint (not an end site) on the side whose lower-case name contains `part`.
std::optional<std::string> find_foot(const Skeleton& s, const std::string& letter, const std::string& word,
                                     const char* part) {
    for (const Joint& j : s.joints()) {
        if (j.end_site || lower(j.name).find(part) == std::string::npos) continue;
        if (on_side(j.name, letter, word) &&
            !on_side(j.name, letter == "l" ? "r" : "l", letter == "l" ? "right" : "left"))
            return j.name;
    }
    return std::nullopt;
}

}  // namespace

std::vector<std::string> default_feet(const Skeleton& s) {
    for (const char* part : {"toe", "foot"}) {
        const auto left = find_foot(s, "l", "left", part);
        const auto right = find_foot(s, "r", "right", part);
        if (left && right) return {*left, *right};
    }
    throw Refused<InvalidArgument>(Remedy::Feet,
                                   "no left/right foot joints found by name (a joint named with toe or foot and "
                                   "left/right, L/R); name them explicitly");
}

Eigen::Matrix<bool, Eigen::Dynamic, Eigen::Dynamic> foot_contacts(const Clip& clip, const FootContactOptions& options) {
    validate(clip);
    const Skeleton& s = *clip.skeleton;
    const std::vector<std::string> feet = options.feet.empty() ? default_feet(s) : options.feet;
    std::vector<std::size_t> index;
    for (const std::string& name : feet) {
        const auto j = s.find(name);
        if (!j) throw InvalidArgument("foot joint '" + name + "' is not in the skeleton");
        index.push_back(*j);
    }
    const MatX p = joint_positions(clip);
    const auto frames = p.cols();
    Eigen::Matrix<bool, Eigen::Dynamic, Eigen::Dynamic> contact(static_cast<Eigen::Index>(feet.size()), frames);
    for (std::size_t k = 0; k < index.size(); ++k) {
        const auto r = 3 * static_cast<Eigen::Index>(index[k]);
        std::vector<double> heights(static_cast<std::size_t>(frames));
        for (Eigen::Index f = 0; f < frames; ++f) heights[static_cast<std::size_t>(f)] = p(r + 1, f);
        std::vector<double> sorted = heights;
        const auto nth = sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 20);
        std::nth_element(sorted.begin(), nth, sorted.end());
        const double floor = sorted.empty() ? 0.0 : *nth;
        for (Eigen::Index f = 0; f < frames; ++f) {
            // Central difference of the horizontal position (one-sided at the ends).
            const Eigen::Index a = std::max<Eigen::Index>(f - 1, 0), b = std::min<Eigen::Index>(f + 1, frames - 1);
            double speed = 0.0;
            if (b > a) {
                const double dx = p(r, b) - p(r, a), dz = p(r + 2, b) - p(r + 2, a);
                speed = std::hypot(dx, dz) * clip.frame_rate / static_cast<double>(b - a);
            }
            contact(static_cast<Eigen::Index>(k), f) =
                heights[static_cast<std::size_t>(f)] - floor <= options.height_tolerance_cm &&
                speed <= options.speed_tolerance_cm_s;
        }
    }
    return contact;
}

std::optional<Flight> longest_flight(const Eigen::Matrix<bool, Eigen::Dynamic, Eigen::Dynamic>& contacts) {
    const Eigen::Index frames = contacts.cols();
    std::optional<Flight> best;
    for (Eigen::Index f = 0; f < frames;) {
        if (contacts.col(f).any()) {
            ++f;
            continue;
        }
        Eigen::Index g = f;
        while (g < frames && !contacts.col(g).any()) ++g;
        if (f > 0 && g < frames && (!best || g - f > best->landing - best->takeoff - 1)) best = Flight{f - 1, g};
        f = g;
    }
    return best;
}

}  // namespace mocapdb
