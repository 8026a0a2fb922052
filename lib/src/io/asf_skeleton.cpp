// ASF (Acclaim skeleton file) -> Skeleton. The mapping and unit conventions are documented in
// mocapdb/io/asf_amc.hpp; this file only parses and builds.
#include <algorithm>
#include <array>
#include <unordered_map>
#include <utility>
#include <vector>

#include "asf_text.hpp"
#include "mocapdb/core/error.hpp"
#include "mocapdb/io/asf_amc.hpp"
#include "mocapdb/io/text_file.hpp"
#include "text_scanner.hpp"

namespace mocapdb {
namespace {

using detail::iequals;
using detail::quoted;
using detail::TextScanner;

/// A degree of freedom as the ASF names it (tx ty tz rx ry rz; `l` is refused while parsing).
enum class Dof { TX, TY, TZ, RX, RY, RZ };

bool is_rotation_dof(Dof d) { return d >= Dof::RX; }
Axis dof_axis(Dof d) { return static_cast<Axis>(static_cast<int>(d) % 3); }
ChannelType channel_of(Dof d) { return static_cast<ChannelType>(static_cast<int>(d)); }

std::optional<Dof> dof_from_string(std::string_view t) {
    static constexpr std::string_view names[] = {"tx", "ty", "tz", "rx", "ry", "rz"};
    for (int i = 0; i < 6; ++i)
        if (iequals(t, names[i])) return static_cast<Dof>(i);
    return std::nullopt;
}

constexpr int kRootParent = -1;  // parent index of a bone hanging from the root
constexpr int kNoParent = -2;    // not (yet) placed in :hierarchy

struct BoneDef {
    std::string name;
    std::size_t begin_line = 0;
    std::size_t name_line = 0;
    Vec3 direction = Vec3::Zero();
    double length = 0.0;                      ///< file units
    Vec3 axis_angles = Vec3::Zero();          ///< about X, Y, Z, in the file's angle unit
    EulerOrder axis_order = EulerOrder::XYZ;  ///< letters as written; the first is applied first
    std::vector<Dof> dofs;
    std::size_t dof_line = 0;
    bool has_direction = false, has_length = false, has_axis = false;
    int parent = kNoParent;
    std::size_t parent_line = 0;
    std::vector<int> children;
};

struct RootDef {
    std::vector<Dof> order;
    EulerOrder axis_order = EulerOrder::XYZ;
    Vec3 position = Vec3::Zero();
    Vec3 orientation = Vec3::Zero();
};

/// The ASF composition of three angles (about X, Y, Z) in the written order: the axis written first
/// is applied first, so "XYZ" gives Rz·Ry·Rx.
Quat asf_rotation(const Vec3& angles_xyz, EulerOrder written) {
    Quat q = Quat::Identity();
    for (Axis a : axes_of(written)) {
        const int i = static_cast<int>(a);
        q = Quat(Eigen::AngleAxisd(angles_xyz[i], Vec3::Unit(i))) * q;
    }
    return q.normalized();
}

/// The Joint::rotation_order reproducing R = R_last · ... · R_first for rotation dofs listed in AMC
/// order: the listed axes reversed (outermost first); axes without a dof fill the rest (angle 0).
EulerOrder composition_order(const std::vector<Dof>& dofs) {
    std::array<Axis, 3> out{};
    bool used[3] = {};
    int n = 0;
    for (auto it = dofs.rbegin(); it != dofs.rend(); ++it) {
        if (!is_rotation_dof(*it)) continue;
        out[static_cast<std::size_t>(n++)] = dof_axis(*it);
        used[static_cast<int>(dof_axis(*it))] = true;
    }
    for (int a = 0; a < 3; ++a)
        if (!used[a]) out[static_cast<std::size_t>(n++)] = static_cast<Axis>(a);
    return *euler_order_from_axes(out[0], out[1], out[2]);
}

class AsfParser {
public:
    AsfParser(std::string_view text, const std::string& source_name)
        : text_(detail::blank_comments(text)), s_(text_, source_name) {}

    Skeleton run() {
        while (!s_.at_end()) {
            const std::string_view kw = s_.token();
            if (kw.front() != ':')
                s_.fail_at_token(
                    "expected a section keyword (:version, :name, :units, :documentation, :root, "
                    ":bonedata, :hierarchy), found " +
                    quoted(kw));
            if (iequals(kw, ":version")) {
                if (s_.token_on_line().empty()) s_.fail("expected a version number after ':version'");
                finish_line(":version");
            } else if (iequals(kw, ":name")) {
                s_.rest_of_line();
            } else if (iequals(kw, ":documentation") || iequals(kw, ":skin")) {
                skip_section();
            } else if (iequals(kw, ":units")) {
                once(seen_units_, kw);
                parse_units();
            } else if (iequals(kw, ":root")) {
                once(seen_root_, kw);
                parse_root();
            } else if (iequals(kw, ":bonedata")) {
                once(seen_bonedata_, kw);
                parse_bonedata();
            } else if (iequals(kw, ":hierarchy")) {
                once(seen_hierarchy_, kw);
                parse_hierarchy();
            } else {
                s_.fail_at_token("unknown section " + quoted(kw) +
                                 " (expected :version, :name, :units, :documentation, :root, :bonedata or :hierarchy)");
            }
        }
        return build();
    }

private:
    std::string text_;  // comment-free copy the scanner reads
    TextScanner s_;
    bool seen_units_ = false, seen_root_ = false, seen_bonedata_ = false, seen_hierarchy_ = false;
    double length_factor_ = 1.0;
    bool degrees_ = true;
    RootDef root_;
    std::vector<BoneDef> bones_;
    std::unordered_map<std::string, int> bone_index_;
    std::vector<int> root_children_;

    [[noreturn]] void fail_at_line(std::size_t line, const std::string& message) const {
        throw ParseError(s_.source_name(), line, 0, message);
    }

    void once(bool& seen, std::string_view kw) {
        if (seen) s_.fail_at_token("duplicate section " + quoted(kw));
        seen = true;
    }

    void expect_keyword(std::string_view keyword, std::string_view why) {
        const std::string_view t = s_.token();
        if (!iequals(t, keyword))
            s_.fail_at_token("expected '" + std::string(keyword) + "' " + std::string(why) + ", found " +
                             (t.empty() ? std::string("end of file") : quoted(t)));
    }

    bool at_section_end() {
        const std::string_view t = s_.peek_token();
        return t.empty() || t.front() == ':';
    }

    void finish_line(std::string_view what) {
        if (!s_.at_line_end()) {
            const std::string_view extra = s_.token_on_line();
            s_.fail_at_token("unexpected " + quoted(extra) + " after " + std::string(what));
        }
    }

    Vec3 three_numbers_on_line(std::string_view what) {
        Vec3 v;
        for (int i = 0; i < 3; ++i) v[i] = s_.number_on_line(what);
        return v;
    }

    EulerOrder axis_order(std::string_view what) {
        const std::string_view t = s_.token_on_line();
        if (t.empty()) s_.fail("expected the " + std::string(what) + " axis order (XYZ, XZY, YXZ, YZX, ZXY or ZYX)");
        const auto order = euler_order_from_string(t);
        if (!order)
            s_.fail_at_token("unknown axis order " + quoted(t) + " for the " + std::string(what) +
                             " (expected XYZ, XZY, YXZ, YZX, ZXY or ZYX)");
        return *order;
    }

    // Everything up to the next line that starts with a section keyword.
    void skip_section() {
        s_.next_line();
        while (!at_section_end()) {
            s_.skip_whitespace();
            s_.next_line();
        }
    }

    void parse_units() {
        while (!at_section_end()) {
            const std::string_view key = s_.token();
            if (iequals(key, "mass")) {
                s_.number("mass unit");
            } else if (iequals(key, "length")) {
                const double v = s_.number("length unit");
                // Below 1e-9 the converted lengths could overflow; no real file comes near it.
                if (!(v >= 1e-9)) s_.fail_at_token("the length unit must be positive (at least 1e-9)");
                length_factor_ = v;
            } else if (iequals(key, "angle")) {
                const std::string_view u = s_.token();
                if (iequals(u, "deg") || iequals(u, "degree") || iequals(u, "degrees")) {
                    degrees_ = true;
                } else if (iequals(u, "rad") || iequals(u, "radian") || iequals(u, "radians")) {
                    degrees_ = false;
                } else {
                    s_.fail_at_token("expected 'deg' or 'rad' as the angle unit, found " +
                                     (u.empty() ? std::string("end of file") : quoted(u)));
                }
            } else {
                s_.fail_at_token("unknown unit " + quoted(key) + " in :units (expected mass, length or angle)");
            }
        }
    }

    void parse_root() {
        while (!at_section_end()) {
            const std::string_view key = s_.token();
            if (iequals(key, "order")) {
                root_.order.clear();
                for (std::string_view t = s_.token_on_line(); !t.empty(); t = s_.token_on_line()) {
                    const auto d = dof_from_string(t);
                    if (!d)
                        s_.fail_at_token("unknown root channel " + quoted(t) +
                                         " in 'order' (expected TX, TY, TZ, RX, RY or RZ)");
                    if (std::find(root_.order.begin(), root_.order.end(), *d) != root_.order.end())
                        s_.fail_at_token("root channel " + quoted(t) + " appears twice in 'order'");
                    root_.order.push_back(*d);
                }
                if (root_.order.empty()) s_.fail("expected root channels (TX, TY, TZ, RX, RY, RZ) after 'order'");
            } else if (iequals(key, "axis")) {
                root_.axis_order = axis_order("root");
                finish_line("the root axis order");
            } else if (iequals(key, "position")) {
                root_.position = three_numbers_on_line("root position");
                finish_line("the root position");
            } else if (iequals(key, "orientation")) {
                root_.orientation = three_numbers_on_line("root orientation");
                finish_line("the root orientation");
            } else {
                s_.fail_at_token("unknown :root field " + quoted(key) +
                                 " (expected order, axis, position or orientation)");
            }
        }
    }

    void parse_bonedata() {
        while (!at_section_end()) {
            expect_keyword("begin", "to open a bone");
            parse_bone(s_.token_line());
        }
    }

    // One "(min max)" pair; ASF writers glue the parentheses to the numbers or not, and use inf.
    void parse_limit_pair() {
        std::string_view t = s_.token();
        t.remove_prefix(1);  // the caller saw '('
        int numbers = 0;
        bool closed = false;
        for (;;) {
            if (!t.empty() && t.back() == ')') {
                closed = true;
                t.remove_suffix(1);
            }
            if (t.find_first_of("()") != std::string_view::npos)
                s_.fail_at_token("malformed limits pair near " + quoted(t) + " (expected '(min max)')");
            if (!t.empty()) {
                const bool infinite = iequals(t, "inf") || iequals(t, "-inf") || iequals(t, "+inf");
                if (!infinite) s_.to_number(t, "limit");
                ++numbers;
            }
            if (closed) break;
            t = s_.token();
            if (t.empty()) s_.fail("unexpected end of file inside a limits pair (expected ')')");
        }
        if (numbers != 2)
            s_.fail_at_token("expected two numbers in a limits pair '(min max)', found " + std::to_string(numbers));
    }

    void parse_bone(std::size_t begin_line) {
        BoneDef b;
        b.begin_line = begin_line;
        std::size_t limit_pairs = 0, limits_line = 0;
        for (;;) {
            const std::string_view key = s_.token();
            if (key.empty())
                s_.fail("unexpected end of file in the bone begun at line " + std::to_string(begin_line) +
                        " (expected 'end')");
            if (iequals(key, "end")) break;
            if (iequals(key, "id")) {
                s_.integer("bone id");
                finish_line("the bone id");
            } else if (iequals(key, "name")) {
                const std::string_view name = s_.token_on_line();
                if (name.empty()) s_.fail("expected a bone name after 'name'");
                b.name = std::string(name);
                b.name_line = s_.token_line();
                if (b.name == "root") s_.fail_at_token("a bone cannot be named 'root' (the name of the root)");
                if (const auto it = bone_index_.find(b.name); it != bone_index_.end())
                    s_.fail_at_token("duplicate bone name " + quoted(name) + " (first defined at line " +
                                     std::to_string(bones_[static_cast<std::size_t>(it->second)].name_line) + ")");
                finish_line("the bone name");
            } else if (iequals(key, "direction")) {
                b.direction = three_numbers_on_line("direction");
                b.has_direction = true;
                finish_line("the bone direction");
            } else if (iequals(key, "length")) {
                b.length = s_.number_on_line("length");
                if (b.length < 0.0) s_.fail_at_token("bone length must not be negative");
                b.has_length = true;
                finish_line("the bone length");
            } else if (iequals(key, "axis")) {
                b.axis_angles = three_numbers_on_line("axis angle");
                b.axis_order = axis_order("bone");
                b.has_axis = true;
                finish_line("the bone axis");
            } else if (iequals(key, "dof")) {
                b.dofs.clear();
                b.dof_line = s_.token_line();
                for (std::string_view t = s_.token_on_line(); !t.empty(); t = s_.token_on_line()) {
                    if (iequals(t, "l"))
                        s_.fail_at_token(
                            "dof 'l' (bone stretch) is not supported: mocapdb skeletons have "
                            "fixed bone lengths");
                    const auto d = dof_from_string(t);
                    if (!d) s_.fail_at_token("unknown dof " + quoted(t) + " (expected rx, ry, rz, tx, ty, tz)");
                    if (std::find(b.dofs.begin(), b.dofs.end(), *d) != b.dofs.end())
                        s_.fail_at_token("dof " + quoted(t) + " appears twice");
                    b.dofs.push_back(*d);
                }
            } else if (iequals(key, "limits")) {
                limits_line = s_.token_line();
                limit_pairs = 0;
                for (std::string_view t = s_.peek_token(); !t.empty() && t.front() == '('; t = s_.peek_token()) {
                    parse_limit_pair();
                    ++limit_pairs;
                }
                if (limit_pairs == 0) s_.fail("expected '(min max)' pairs after 'limits'");
            } else if (iequals(key, "bodymass") || iequals(key, "cofmass")) {
                s_.number_on_line(key);
                finish_line(key);
            } else {
                s_.fail_at_token("unknown bone field " + quoted(key) +
                                 " (expected id, name, direction, length, axis, dof, limits or end)");
            }
        }
        if (b.name.empty()) fail_at_line(begin_line, "the bone begun here has no 'name'");
        const std::string who = "bone '" + b.name + "'";
        if (!b.has_direction) fail_at_line(begin_line, who + " has no 'direction'");
        if (!b.has_length) fail_at_line(begin_line, who + " has no 'length'");
        if (limits_line != 0 && limit_pairs != b.dofs.size())
            fail_at_line(limits_line, who + ": expected " + std::to_string(b.dofs.size()) +
                                          " limits pairs (one per dof), found " + std::to_string(limit_pairs));
        // Translation dofs become position channels, which move along the parent's axes; that equals
        // the ASF meaning (along the bone's own axis frame) only when the axis is the identity.
        const bool translates = std::any_of(b.dofs.begin(), b.dofs.end(), [](Dof d) { return !is_rotation_dof(d); });
        if (translates && b.axis_angles != Vec3::Zero())
            fail_at_line(b.dof_line, who +
                                         ": translation dofs (tx, ty, tz) are supported only on bones whose "
                                         "axis is 0 0 0");
        bone_index_.emplace(b.name, static_cast<int>(bones_.size()));
        bones_.push_back(std::move(b));
    }

    int hierarchy_node(std::string_view name, bool as_child) {
        if (name == "root") {
            if (as_child) s_.fail_at_token("'root' cannot be the child of another bone in :hierarchy");
            return kRootParent;
        }
        const auto it = bone_index_.find(std::string(name));
        if (it == bone_index_.end())
            s_.fail_at_token("unknown bone " + quoted(name) + " in :hierarchy (not defined in :bonedata)");
        return it->second;
    }

    const std::string& node_name(int index) const {
        static const std::string root = "root";
        return index == kRootParent ? root : bones_[static_cast<std::size_t>(index)].name;
    }

    void parse_hierarchy() {
        expect_keyword("begin", "after :hierarchy");
        for (;;) {
            const std::string_view parent_name = s_.token();
            if (parent_name.empty()) s_.fail("unexpected end of file in :hierarchy (expected 'end')");
            if (iequals(parent_name, "end")) break;
            if (parent_name.front() == ':')
                s_.fail_at_token("expected 'end' to close :hierarchy, found " + quoted(parent_name));
            const int parent = hierarchy_node(parent_name, false);
            for (std::string_view t = s_.token_on_line(); !t.empty(); t = s_.token_on_line()) {
                const int child = hierarchy_node(t, true);
                BoneDef& c = bones_[static_cast<std::size_t>(child)];
                if (c.parent != kNoParent)
                    s_.fail_at_token("bone " + quoted(t) + " has two parents in :hierarchy: '" + node_name(c.parent) +
                                     "' (line " + std::to_string(c.parent_line) + ") and '" + node_name(parent) + "'");
                // Refusing each cycle-closing link keeps every parent chain finite.
                for (int a = parent; a != kRootParent && a != kNoParent; a = bones_[static_cast<std::size_t>(a)].parent)
                    if (a == child)
                        s_.fail_at_token("cycle in :hierarchy: bone " + quoted(t) +
                                         " would be its own ancestor (via '" + node_name(parent) + "')");
                c.parent = parent;
                c.parent_line = s_.token_line();
                (parent == kRootParent ? root_children_ : bones_[static_cast<std::size_t>(parent)].children)
                    .push_back(child);
            }
        }
    }

    Skeleton build() {
        if (!seen_root_) fail_at_line(0, "no :root section (expected one before :bonedata)");
        if (!bones_.empty() && !seen_hierarchy_)
            fail_at_line(0, "no :hierarchy section (the bones must be connected to the root)");
        // A bone whose chain does not end at the root (no parent, or under such a bone) is unplaceable.
        for (const BoneDef& b : bones_) {
            int top = bone_index_.at(b.name);
            while (bones_[static_cast<std::size_t>(top)].parent >= 0)
                top = bones_[static_cast<std::size_t>(top)].parent;
            if (bones_[static_cast<std::size_t>(top)].parent == kNoParent)
                fail_at_line(b.name_line, "bone '" + b.name + "' is not connected to the root in :hierarchy");
            if (b.children.empty() && bone_index_.count(b.name + "_end"))
                fail_at_line(b.name_line,
                             "bone '" + b.name + "_end' clashes with the end site of leaf bone '" + b.name + "'");
        }

        const double cm = 2.54 / length_factor_;
        const double angle = degrees_ ? kPi / 180.0 : 1.0;
        std::vector<Joint> joints;
        joints.reserve(2 * bones_.size() + 1);

        Joint root;
        root.name = "root";
        root.offset = root_.position * cm;
        for (Dof d : root_.order) root.channels.push_back(channel_of(d));
        root.rotation_order = composition_order(root_.order);
        root.axis = asf_rotation(root_.orientation * angle, root_.axis_order);
        joints.push_back(std::move(root));

        // Depth-first, children in :hierarchy order; explicit stack so deep chains cannot overflow.
        std::vector<std::pair<int, int>> stack;  // (bone, parent joint)
        for (auto it = root_children_.rbegin(); it != root_children_.rend(); ++it) stack.emplace_back(*it, 0);
        while (!stack.empty()) {
            const auto [bi, parent_joint] = stack.back();
            stack.pop_back();
            const BoneDef& b = bones_[static_cast<std::size_t>(bi)];
            Joint j;
            j.name = b.name;
            j.parent = parent_joint;
            if (b.parent >= 0) {
                const BoneDef& p = bones_[static_cast<std::size_t>(b.parent)];
                j.offset = p.direction * (p.length * cm);
            }
            for (Dof d : b.dofs) j.channels.push_back(channel_of(d));
            j.rotation_order = composition_order(b.dofs);
            j.axis = asf_rotation(b.axis_angles * angle, b.axis_order);
            const int index = static_cast<int>(joints.size());
            joints.push_back(std::move(j));
            if (b.children.empty()) {
                Joint end;
                end.name = b.name + "_end";
                end.parent = index;
                end.offset = b.direction * (b.length * cm);
                end.end_site = true;
                joints.push_back(std::move(end));
            }
            for (auto it = b.children.rbegin(); it != b.children.rend(); ++it) stack.emplace_back(*it, index);
        }

        try {
            return Skeleton(std::move(joints), SourceUnits{cm, degrees_}, Vec3::UnitZ());
        } catch (const InvalidArgument& e) {
            fail_at_line(0, e.what());
        }
    }
};

}  // namespace

Skeleton parse_asf(std::string_view text, const std::string& source_name) { return AsfParser(text, source_name).run(); }

std::shared_ptr<const Skeleton> read_asf(const std::filesystem::path& path) {
    return std::make_shared<const Skeleton>(parse_asf(read_text_file(path), path.string()));
}

}  // namespace mocapdb
