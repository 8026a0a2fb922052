#include "mocapdb/dataset/param_extractors.hpp"

#include <cmath>

#include "mocapdb/core/error.hpp"
#include "mocapdb/motion/forward_kinematics.hpp"

namespace mocapdb {
namespace {

Vec3 rotate_about_y(const Vec3& v, double angle) { return Eigen::AngleAxisd(angle, Vec3::UnitY()) * v; }

std::size_t reach_frame(const std::string& at, std::size_t begin, std::size_t end) {
    const std::size_t n = end - begin;
    if (at == "end") return end - 1;
    try {
        std::size_t used = 0;
        if (!at.empty() && at.back() == '%') {
            const double percent = std::stod(at.substr(0, at.size() - 1), &used);
            if (used + 1 != at.size() || !(percent >= 0 && percent <= 100)) throw std::invalid_argument(at);
            return begin + static_cast<std::size_t>(std::lround(percent / 100.0 * static_cast<double>(n - 1)));
        }
        const long long f = std::stoll(at, &used);
        if (used != at.size() || f < 0 || static_cast<std::size_t>(f) >= n) throw std::invalid_argument(at);
        return begin + static_cast<std::size_t>(f);
    } catch (const std::logic_error&) {
        throw InvalidArgument("reach frame '" + at + "' must be a frame offset within the sample's " +
                              std::to_string(n) + " frames, 'end', or a percentage 'P%'");
    }
}

double jump_length(const Clip& clip, std::size_t begin, std::size_t end, const FootContactOptions& options,
                   const MatX& root) {
    const std::optional<Flight> flight = longest_flight(foot_contacts(slice(clip, begin, end), options));
    if (!flight)
        throw InvalidArgument("clip '" + clip.name + "' frames [" + std::to_string(begin) + ", " + std::to_string(end) +
                              "): no flight phase (a run of frames with no foot contact between contacts); "
                              "not a jump, or the contact tolerances need adjusting");
    const Eigen::Index takeoff = static_cast<Eigen::Index>(begin) + flight->takeoff;
    const Eigen::Index landing = static_cast<Eigen::Index>(begin) + flight->landing;
    return std::hypot(root(0, landing) - root(0, takeoff), root(2, landing) - root(2, takeoff));
}

}  // namespace

ParameterExtractor ParameterExtractor::parse(const std::string& spec) {
    ParameterExtractor e;
    if (spec == "displacement") e.kind = ParameterKind::Displacement;
    else if (spec == "turn") e.kind = ParameterKind::Turn;
    else if (spec == "speed") e.kind = ParameterKind::Speed;
    else if (spec == "jump") e.kind = ParameterKind::Jump;
    else if (spec == "bearing") e.kind = ParameterKind::Bearing;
    else if (spec.rfind("reach:", 0) == 0) {
        const std::string rest = spec.substr(6);
        const auto at = rest.find('@');
        if (at == std::string::npos || at == 0 || at + 1 == rest.size())
            throw InvalidArgument("extractor '" + spec +
                                  "': expected reach:JOINT@FRAME (FRAME: offset, 'end' or 'P%')");
        e.kind = ParameterKind::Reach;
        e.joint = rest.substr(0, at);
        e.at = rest.substr(at + 1);
    } else {
        throw InvalidArgument("unknown extractor '" + spec +
                              "' (expected displacement, turn, speed, jump, bearing or reach:JOINT@FRAME)");
    }
    return e;
}

std::string ParameterExtractor::spec() const {
    switch (kind) {
        case ParameterKind::Displacement: return "displacement";
        case ParameterKind::Turn: return "turn";
        case ParameterKind::Speed: return "speed";
        case ParameterKind::Jump: return "jump";
        case ParameterKind::Bearing: return "bearing";
        case ParameterKind::Reach: return "reach:" + joint + "@" + at;
    }
    return {};
}

std::vector<std::string> ParameterExtractor::names() const {
    switch (kind) {
        case ParameterKind::Displacement: return {"dx", "dz"};
        case ParameterKind::Turn: return {"turn"};
        case ParameterKind::Speed: return {"speed"};
        case ParameterKind::Jump: return {"jump"};
        case ParameterKind::Bearing: return {"bearing"};
        case ParameterKind::Reach: return {joint + "_x", joint + "_y", joint + "_z"};
    }
    return {};
}

std::vector<std::string> ParameterExtractor::units() const {
    switch (kind) {
        case ParameterKind::Displacement: return {"cm", "cm"};
        case ParameterKind::Turn: return {"rad"};
        case ParameterKind::Speed: return {"cm/s"};
        case ParameterKind::Jump: return {"cm"};
        case ParameterKind::Bearing: return {"rad"};
        case ParameterKind::Reach: return {"cm", "cm", "cm"};
    }
    return {};
}

std::vector<double> ParameterExtractor::periods() const {
    std::vector<double> out(names().size(), 0.0);
    if (kind == ParameterKind::Bearing) out[0] = 2.0 * kPi;
    return out;
}

VecX extract_parameters(const Clip& clip, std::size_t begin, std::size_t end,
                        const std::vector<ParameterExtractor>& extractors) {
    validate(clip);
    if (end > clip.frame_count() || end < begin + 2)
        throw InvalidArgument("clip '" + clip.name + "': sample [" + std::to_string(begin) + ", " +
                              std::to_string(end) + ") needs at least 2 frames within its " +
                              std::to_string(clip.frame_count()));
    const MatX root = root_positions(clip);
    const VecX heading = root_headings(clip);
    const auto b = static_cast<Eigen::Index>(begin), last = static_cast<Eigen::Index>(end - 1);
    std::vector<double> values;
    for (const ParameterExtractor& e : extractors) {
        switch (e.kind) {
            case ParameterKind::Displacement: {
                Vec3 d = root.col(last) - root.col(b);
                d.y() = 0.0;
                const Vec3 local = rotate_about_y(d, -heading[b]);
                values.push_back(local.x());
                values.push_back(local.z());
                break;
            }
            case ParameterKind::Turn: values.push_back(heading[last] - heading[b]); break;
            case ParameterKind::Speed: {
                double path = 0.0;
                for (Eigen::Index f = b; f < last; ++f)
                    path += std::hypot(root(0, f + 1) - root(0, f), root(2, f + 1) - root(2, f));
                values.push_back(path * clip.frame_rate / static_cast<double>(last - b));
                break;
            }
            case ParameterKind::Reach: {
                const auto j = clip.skeleton->find(e.joint);
                if (!j)
                    throw InvalidArgument("reach joint '" + e.joint + "' is not in the skeleton of clip '" + clip.name +
                                          "'");
                const std::size_t f = reach_frame(e.at, begin, end);
                GlobalPose pose;
                forward_kinematics(*clip.skeleton, clip.frame(f), pose);
                const Vec3 local = rotate_about_y(pose.positions[*j] - pose.positions[clip.skeleton->motion_root()],
                                                  -heading[static_cast<Eigen::Index>(f)]);
                values.insert(values.end(), {local.x(), local.y(), local.z()});
                break;
            }
            case ParameterKind::Jump: values.push_back(jump_length(clip, begin, end, e.contacts, root)); break;
            case ParameterKind::Bearing: {
                Vec3 d = root.col(last) - root.col(b);
                d.y() = 0.0;
                if (!(d.norm() >= 1.0))
                    throw InvalidArgument("clip '" + clip.name + "' frames [" + std::to_string(begin) + ", " +
                                          std::to_string(end) + "): the root travels " + std::to_string(d.norm()) +
                                          " cm, too little for a bearing (direction of travel)");
                const Vec3 local = rotate_about_y(d, -heading[b]);
                values.push_back(std::atan2(local.x(), local.z()));
                break;
            }
        }
    }
    return Eigen::Map<const VecX>(values.data(), static_cast<Eigen::Index>(values.size()));
}

}  // namespace mocapdb
