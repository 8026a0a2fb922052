#include "mocapdb/procedural/parametric_set.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <ostream>
#include <set>
#include <system_error>

#include "mocapdb/core/error.hpp"
#include "mocapdb/core/remedy.hpp"
#include "mocapdb/io/bvh.hpp"
#include "mocapdb/io/text_file.hpp"

namespace mocapdb::procedural {
namespace {

constexpr double kDeg = kPi / 180.0;

double parse_number(const std::string& text, const std::string& spec) {
    double value = 0.0;
    const char* end = text.data() + text.size();
    const auto r = std::from_chars(text.data(), end, value);
    if (text.empty() || r.ec != std::errc() || r.ptr != end || !std::isfinite(value))
        throw InvalidArgument("grid axis '" + spec + "': '" + text + "' is not a number");
    return value;
}

std::string number(double value) {
    if (value == 0.0) value = 0.0;
    char buffer[64];
    const auto r = std::to_chars(buffer, buffer + sizeof buffer, value);
    return std::string(buffer, r.ptr);
}

// A name not yet in `taken` (base, base_2, base_3, ...).
std::string unique(const std::string& base, std::set<std::string>& taken) {
    std::string name = base;
    for (int k = 2; !taken.insert(name).second; ++k) name = base + "_" + std::to_string(k);
    return name;
}

std::string signed_int(double value, int width) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%+0*ld", width + 1, std::lround(value));
    return buffer;
}

// Columns of the axes that vary (a constant column would make a linear trend in c singular); all
// of them when none varies.
struct Column {
    const GridAxis* axis;
    std::string unit;
    double scale;  // written value = grid value · scale
};

std::vector<Column> varying(const std::vector<Column>& all) {
    std::vector<Column> out;
    for (const Column& c : all)
        if (c.axis->count > 1 && c.axis->low != c.axis->high) out.push_back(c);
    return out.empty() ? all : out;
}

void check_axis(const GridAxis& a) {
    if (a.count < 1 || a.count > 10000) throw InvalidArgument("grid axis '" + a.name + "': count must be 1…10000");
    if (!std::isfinite(a.low) || !std::isfinite(a.high))
        throw InvalidArgument("grid axis '" + a.name + "': bounds must be finite");
}

}  // namespace

double GridAxis::value(std::size_t i) const {
    if (count <= 1) return low;
    return low + (high - low) * static_cast<double>(i) / static_cast<double>(count - 1);
}

GridAxis parse_grid_axis(const std::string& spec) {
    const auto eq = spec.find('=');
    if (eq == std::string::npos || eq == 0)
        throw InvalidArgument("grid axis '" + spec + "': expected NAME=LOW:HIGH:COUNT or NAME=VALUE");
    GridAxis a;
    a.name = spec.substr(0, eq);
    const std::string rest = spec.substr(eq + 1);
    const auto c1 = rest.find(':');
    if (c1 == std::string::npos) {
        a.low = a.high = parse_number(rest, spec);
        a.count = 1;
        return a;
    }
    const auto c2 = rest.find(':', c1 + 1);
    if (c2 == std::string::npos)
        throw InvalidArgument("grid axis '" + spec + "': expected NAME=LOW:HIGH:COUNT or NAME=VALUE");
    a.low = parse_number(rest.substr(0, c1), spec);
    a.high = parse_number(rest.substr(c1 + 1, c2 - c1 - 1), spec);
    const double count = parse_number(rest.substr(c2 + 1), spec);
    if (count < 1 || count > 10000 || count != std::floor(count))
        throw InvalidArgument("grid axis '" + spec + "': COUNT must be a whole number 1…10000");
    a.count = static_cast<std::size_t>(count);
    return a;
}

void apply_grid_specs(WalkGrid& grid, const std::vector<std::string>& specs) {
    for (const std::string& spec : specs) {
        GridAxis a = parse_grid_axis(spec);
        if (a.name == "speed") grid.speed = a;
        else if (a.name == "turn") grid.turn = a;
        else if (a.name == "stride") grid.stride = a;
        else
            throw InvalidArgument("grid axis '" + spec +
                                  "': a walk grid has the axes speed (m/s), turn (deg), stride (m)");
    }
}

void apply_grid_specs(ReachGrid& grid, const std::vector<std::string>& specs) {
    for (const std::string& spec : specs) {
        GridAxis a = parse_grid_axis(spec);
        if (a.name == "angle") grid.angle = a;
        else if (a.name == "height") grid.height = a;
        else if (a.name == "distance") grid.distance = a;
        else
            throw InvalidArgument("grid axis '" + spec +
                                  "': a reach grid has the axes angle (deg), height (cm), distance (cm)");
    }
}

namespace {

/// One clip per point of a three-axis grid — `make(v0, v1, v2, taken)` returns it, named uniquely
/// against `taken` — with the axes that vary as the parameter columns (grid value · scale).
template <class Make>
ParametricSet grid_set(const std::string& kind, const std::array<Column, 3>& axes, Make make) {
    for (const Column& a : axes) check_axis(*a.axis);
    const std::vector<Column> columns = varying({axes[0], axes[1], axes[2]});
    ParametricSet set;
    set.kind = kind;
    for (const Column& c : columns) {
        set.parameter_names.push_back(c.axis->name);
        set.parameter_units.push_back(c.unit);
    }
    const GridAxis &a0 = *axes[0].axis, &a1 = *axes[1].axis, &a2 = *axes[2].axis;
    set.parameters.resize(static_cast<Eigen::Index>(a0.count * a1.count * a2.count),
                          static_cast<Eigen::Index>(columns.size()));
    std::set<std::string> taken;
    Eigen::Index row = 0;
    for (std::size_t i = 0; i < a0.count; ++i)
        for (std::size_t j = 0; j < a1.count; ++j)
            for (std::size_t k = 0; k < a2.count; ++k, ++row) {
                const double values[3] = {a0.value(i), a1.value(j), a2.value(k)};
                set.clips.push_back(make(values[0], values[1], values[2], taken));
                for (std::size_t c = 0; c < columns.size(); ++c) {
                    const std::size_t axis = columns[c].axis == &a0 ? 0 : columns[c].axis == &a1 ? 1 : 2;
                    set.parameters(row, static_cast<Eigen::Index>(c)) = values[axis] * columns[c].scale;
                }
            }
    return set;
}

}  // namespace

ParametricSet generate_walk_set(const WalkGrid& grid) {
    // The speed and turn columns carry the extractors' names, units and definitions.
    return grid_set("walk", {{{&grid.speed, "cm/s", 100.0}, {&grid.turn, "rad", kDeg}, {&grid.stride, "cm", 100.0}}},
                    [&](double speed, double turn, double stride, std::set<std::string>& taken) {
                        WalkParams p;
                        p.speed_m_s = speed;
                        p.turn_deg = turn;
                        p.stride_m = stride;
                        WalkMotion m = generate_walk(p, grid.options);
                        std::string name =
                            "walk_s" + std::to_string(std::lround(100.0 * speed)) + "_t" + signed_int(turn, 3);
                        if (stride > 0.0) name += "_l" + std::to_string(std::lround(100.0 * stride));
                        m.clip.name = unique(name, taken);
                        return std::move(m.clip);
                    });
}

ParametricSet generate_reach_set(const ReachGrid& grid) {
    return grid_set("reach", {{{&grid.angle, "deg", 1.0}, {&grid.height, "cm", 1.0}, {&grid.distance, "cm", 1.0}}},
                    [&](double angle, double height, double distance, std::set<std::string>& taken) {
                        ReachParams p;
                        p.angle_deg = angle;
                        p.height_cm = height;
                        p.distance_cm = distance;
                        ReachMotion m = generate_reach(p, grid.options);
                        m.clip.name =
                            unique("reach_a" + signed_int(angle, 3) + "_h" + std::to_string(std::lround(height)) +
                                       "_d" + std::to_string(std::lround(distance)),
                                   taken);
                        return std::move(m.clip);
                    });
}

std::vector<std::filesystem::path> write_parametric_set(const std::filesystem::path& dir, const ParametricSet& set,
                                                        bool overwrite, int precision) {
    namespace fs = std::filesystem;
    if (set.clips.empty()) throw InvalidArgument("parametric set '" + set.kind + "' has no clips to write");
    if (set.parameters.rows() != static_cast<Eigen::Index>(set.clips.size()) ||
        set.parameters.cols() != static_cast<Eigen::Index>(set.parameter_names.size()) ||
        set.parameter_units.size() != set.parameter_names.size())
        throw InvalidArgument("parametric set '" + set.kind + "': parameter table does not match the clips");
    std::vector<fs::path> paths;
    for (const Clip& c : set.clips) paths.push_back(dir / (c.name + ".bvh"));
    paths.push_back(dir / "params.csv");
    if (!overwrite)
        for (const fs::path& p : paths)
            if (fs::exists(p)) throw Refused<IoError>(Remedy::Overwrite, p.string() + ": exists");
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) throw IoError("cannot create folder " + dir.string() + ": " + ec.message());
    BvhWriteOptions options;
    options.precision = precision;
    for (std::size_t i = 0; i < set.clips.size(); ++i) write_bvh(paths[i], set.clips[i], options);
    write_file_atomically(paths.back(), [&](std::ostream& os) {
        os << "sample";
        for (std::size_t c = 0; c < set.parameter_names.size(); ++c)
            os << ',' << set.parameter_names[c] << '[' << set.parameter_units[c] << ']';
        os << '\n';
        for (std::size_t i = 0; i < set.clips.size(); ++i) {
            os << set.clips[i].name;
            for (Eigen::Index c = 0; c < set.parameters.cols(); ++c)
                os << ',' << number(set.parameters(static_cast<Eigen::Index>(i), c));
            os << '\n';
        }
    });
    return paths;
}

}  // namespace mocapdb::procedural
