#include "mocapdb/motion/skeleton.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_set>

#include "mocapdb/core/error.hpp"

namespace mocapdb {
namespace {
constexpr const char* kChannelNames[] = {"Xposition", "Yposition", "Zposition", "Xrotation", "Yrotation", "Zrotation"};
}

std::string to_string(ChannelType type) { return kChannelNames[static_cast<int>(type)]; }

std::optional<ChannelType> channel_type_from_string(std::string_view text) {
    for (int i = 0; i < 6; ++i)
        if (text == kChannelNames[i]) return static_cast<ChannelType>(i);
    return std::nullopt;
}

std::string to_string(PositionChannels mode) {
    return mode == PositionChannels::replace_offset ? "replace_offset" : "add_to_offset";
}

std::optional<PositionChannels> position_channels_from_string(std::string_view text) {
    if (text == "replace_offset") return PositionChannels::replace_offset;
    if (text == "add_to_offset") return PositionChannels::add_to_offset;
    return std::nullopt;
}

bool is_rotation(ChannelType type) { return static_cast<int>(type) >= 3; }

Axis channel_axis(ChannelType type) { return static_cast<Axis>(static_cast<int>(type) % 3); }

Skeleton::Skeleton(std::vector<Joint> joints, SourceUnits units, Vec3 forward, PositionChannels positions,
                   std::size_t motion_root)
    : joints_(std::move(joints)), units_(units), positions_(positions), motion_root_(motion_root) {
    if (joints_.empty()) throw InvalidArgument("skeleton: at least one joint is required");
    if (!(forward.allFinite() && std::abs(forward.y()) < 1e-9 && forward.norm() > 1e-9))
        throw InvalidArgument("skeleton: the forward direction must be a finite, non-zero horizontal vector");
    forward_ = forward.normalized();
    if (!(units_.cm_per_unit > 0.0 && std::isfinite(units_.cm_per_unit)))
        throw InvalidArgument("skeleton: source length unit must be positive and finite");

    std::unordered_set<std::string> names;
    std::vector<int> child_count(joints_.size(), 0);
    for (std::size_t i = 0; i < joints_.size(); ++i) {
        const Joint& j = joints_[i];
        const std::string who = "skeleton: joint " + std::to_string(i) + " '" + j.name + "'";
        if (j.name.empty()) throw InvalidArgument("skeleton: joint " + std::to_string(i) + " has an empty name");
        if (!names.insert(j.name).second) throw InvalidArgument(who + ": duplicate joint name");
        if (i == 0 && j.parent != -1) throw InvalidArgument(who + ": the first joint must be the root (parent -1)");
        if (i > 0 && (j.parent < 0 || j.parent >= static_cast<int>(i)))
            throw InvalidArgument(who + ": parent index " + std::to_string(j.parent) +
                                  " must name an earlier joint (parents before children, one root)");
        if (!j.offset.allFinite()) throw InvalidArgument(who + ": offset is not finite");
        if (!j.axis.coeffs().allFinite() || std::abs(j.axis.norm() - 1.0) > 1e-6)
            throw InvalidArgument(who + ": axis rotation is not a unit quaternion");
        if (j.channels.size() > 6)
            throw InvalidArgument(who + ": " + std::to_string(j.channels.size()) + " channels, at most 6 allowed");
        bool seen[6] = {};
        for (ChannelType c : j.channels) {
            if (seen[static_cast<int>(c)]) throw InvalidArgument(who + ": channel " + to_string(c) + " appears twice");
            seen[static_cast<int>(c)] = true;
        }
        if (j.end_site && !j.channels.empty()) throw InvalidArgument(who + ": an end site cannot have channels");
        if (i > 0) {
            ++child_count[j.parent];
            if (joints_[j.parent].end_site) throw InvalidArgument(who + ": its parent is an end site");
        }
    }

    first_channel_.resize(joints_.size());
    columns_.resize(joints_.size());
    for (std::size_t i = 0; i < joints_.size(); ++i) {
        first_channel_[i] = channel_count_;
        columns_[i].fill(-1);
        for (ChannelType c : joints_[i].channels) columns_[i][static_cast<int>(c)] = static_cast<int>(channel_count_++);
    }

    if (motion_root_ >= joints_.size() || joints_[motion_root_].end_site)
        throw InvalidArgument("skeleton: motion root " + std::to_string(motion_root_) + " is not a joint");
    chain_.clear();
    for (int j = static_cast<int>(motion_root_); j >= 0; j = joints_[static_cast<std::size_t>(j)].parent)
        chain_.insert(chain_.begin(), static_cast<std::size_t>(j));
    for (std::size_t i = 1; i < joints_.size(); ++i) {
        const auto parent = static_cast<std::size_t>(joints_[i].parent);
        const bool above = parent != motion_root_ && std::find(chain_.begin(), chain_.end(), parent) != chain_.end();
        if (above && !joints_[i].end_site && std::find(chain_.begin(), chain_.end(), i) == chain_.end())
            throw InvalidArgument("skeleton: joint '" + joints_[parent].name + "' above the motion root '" +
                                  joints_[motion_root_].name + "' has another child, '" + joints_[i].name + "'");
    }
}

Skeleton Skeleton::with_motion_root(std::size_t motion_root) const {
    return Skeleton(joints_, units_, forward_, positions_, motion_root);
}

std::size_t find_motion_root(const Skeleton& s, const FrameMatrix& channels) {
    // No frames: nothing moves, and an empty matrix has no columns to look at (its data is null).
    if (channels.rows() == 0) return 0;
    std::vector<std::vector<std::size_t>> children(s.size());
    for (std::size_t i = 1; i < s.size(); ++i)
        if (!s.joint(i).end_site) children[static_cast<std::size_t>(s.joint(i).parent)].push_back(i);
    auto at_rest = [&](std::size_t j) {
        const Joint& joint = s.joint(j);
        for (std::size_t k = 0; k < joint.channels.size(); ++k) {
            const ChannelType c = joint.channels[k];
            const double rest = is_rotation(c) ? 0.0 : s.rest_position_value(j, channel_axis(c));
            const double tolerance = is_rotation(c) ? 1e-9 : 1e-6;
            const auto column = channels.col(static_cast<Eigen::Index>(s.first_channel(j) + k));
            if ((column.array() - rest).abs().maxCoeff() > tolerance) return false;
        }
        return true;
    };
    std::size_t m = 0;
    while (children[m].size() == 1 && at_rest(m)) m = children[m].front();
    return m;
}

std::optional<std::size_t> Skeleton::find(std::string_view name) const {
    for (std::size_t i = 0; i < joints_.size(); ++i)
        if (joints_[i].name == name) return i;
    return std::nullopt;
}

int Skeleton::channel_column(std::size_t index, ChannelType type) const {
    return columns_.at(index)[static_cast<int>(type)];
}

bool Skeleton::has_rotation(std::size_t index) const {
    const auto& c = columns_.at(index);
    return c[3] >= 0 || c[4] >= 0 || c[5] >= 0;
}

Quat Skeleton::local_rotation(std::size_t index, const double* row) const {
    const Joint& j = joints_[index];
    const auto& cols = columns_[index];
    Quat r = Quat::Identity();
    for (Axis a : axes_of(j.rotation_order)) {
        const int col = cols[3 + static_cast<int>(a)];
        if (col >= 0) r = r * Eigen::AngleAxisd(row[col], Vec3::Unit(static_cast<int>(a)));
    }
    if (j.axis.w() != 1.0) r = j.axis * r * j.axis.conjugate();
    return r;
}

Vec3 Skeleton::local_translation(std::size_t index, const double* row) const {
    const auto& cols = columns_[index];
    Vec3 t = joints_[index].offset;
    if (positions_ == PositionChannels::replace_offset) {
        for (int a = 0; a < 3; ++a)
            if (cols[a] >= 0) t[a] = row[cols[a]];
    } else {
        for (int a = 0; a < 3; ++a)
            if (cols[a] >= 0) t[a] += row[cols[a]];
    }
    return t;
}

double Skeleton::rest_position_value(std::size_t index, Axis axis) const {
    return positions_ == PositionChannels::replace_offset ? joints_.at(index).offset[static_cast<int>(axis)] : 0.0;
}

bool Skeleton::offset_replaced(std::size_t index) const {
    const auto& c = columns_.at(index);
    return positions_ == PositionChannels::replace_offset && c[0] >= 0 && c[1] >= 0 && c[2] >= 0;
}

bool Skeleton::same_structure(const Skeleton& other, double tol) const {
    if (size() != other.size() || motion_root_ != other.motion_root_) return false;
    for (std::size_t i = 0; i < size(); ++i) {
        const Joint& a = joints_[i];
        const Joint& b = other.joints_[i];
        if (a.name != b.name || a.parent != b.parent || a.channels != b.channels || a.end_site != b.end_site ||
            a.rotation_order != b.rotation_order)
            return false;
        for (int k = 0; k < 3; ++k) {
            if (columns_[i][k] < 0) {
                if (std::abs(a.offset[k] - b.offset[k]) > tol) return false;
                continue;
            }
            // A position channel: the offset is replaced (no effect) or added (must match). Between
            // the two conventions the rows mean the same only where the adding side's offset is 0.
            const bool a_adds = positions_ == PositionChannels::add_to_offset;
            const bool b_adds = other.positions_ == PositionChannels::add_to_offset;
            if (a_adds && b_adds && std::abs(a.offset[k] - b.offset[k]) > tol) return false;
            if (a_adds != b_adds && std::abs((a_adds ? a : b).offset[k]) > tol) return false;
        }
        if (angle_between(a.axis, b.axis) > tol) return false;
    }
    return true;
}

bool Skeleton::same_definition(const Skeleton& other, double tol) const {
    if (!same_structure(other, tol)) return false;
    for (std::size_t i = 0; i < size(); ++i)
        if ((joints_[i].offset - other.joints_[i].offset).cwiseAbs().maxCoeff() > tol) return false;
    return true;
}

}  // namespace mocapdb
