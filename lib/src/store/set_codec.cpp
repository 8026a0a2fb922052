#include "set_codec.hpp"

#include <algorithm>
#include <cmath>

#include "layout.hpp"
#include "read_checks.hpp"
#include "mocapdb/store/store_error.hpp"

namespace mocapdb::store {

void write_set(h5::File& file, const MotionSet& set) {
    const std::string g = set_path(set.name);
    file.create_group(g, "motion_set");
    file.write_string_attribute(g, "parameter_source", set.parameter_source);
    const std::uint64_t n = set.samples.size();
    std::vector<std::string> clips;
    std::vector<std::int64_t> frames;
    for (const SampleRef& s : set.samples) {
        clips.push_back(s.clip);
        frames.push_back(static_cast<std::int64_t>(s.begin));
        frames.push_back(static_cast<std::int64_t>(s.end));
    }
    file.write_strings(g + "/sample_clip", clips, "sample", "");
    file.write_array(g + "/sample_frames", frames.data(), {n, 2}, {"sample", "range"}, "frame");
    file.write_strings(g + "/parameter_name", set.parameter_names, "parameter", "");
    file.write_strings(g + "/parameter_unit", set.parameter_units, "parameter", "");
    const std::vector<double> parameters = to_c_order(set.parameters);
    file.write_array(g + "/parameters", parameters.data(), {n, static_cast<std::uint64_t>(set.parameters.cols())},
                     {"sample", "parameter"}, "parameter_unit");
    if (set.parameter_periods.size() != 0 && (set.parameter_periods.array() > 0.0).any()) {
        // Periodic parameters (format-v3.md §6); absent = every parameter linear.
        const std::vector<double> periods(set.parameter_periods.data(),
                                          set.parameter_periods.data() + set.parameter_periods.size());
        file.write_array(g + "/parameter_period", periods.data(), {static_cast<std::uint64_t>(periods.size())},
                         {"parameter"}, "parameter_unit");
    }
    if (!parameter_level_counts(set).empty()) {
        // Categorical parameters (format-v4.md §6): level counts (0 = numeric) and the names, concatenated.
        std::vector<std::int64_t> counts;
        std::vector<std::string> names;
        for (const auto& levels : set.parameter_levels) {
            counts.push_back(static_cast<std::int64_t>(levels.size()));
            names.insert(names.end(), levels.begin(), levels.end());
        }
        file.write_array(g + "/parameter_level_count", counts.data(), {static_cast<std::uint64_t>(counts.size())},
                         {"parameter"}, "");
        file.write_strings(g + "/parameter_level", names, "level", "");
    }
    if (set.dropouts_checked) {
        // The dropout check's outcome (format-v3.md §6.1); the datasets only when something was repaired.
        const std::string r = repairs_path(set.name);
        file.create_group(r, "dropout_repairs");
        file.write_int_attribute(r, "runs", static_cast<std::int64_t>(set.repairs.size()));
        if (!set.repairs.empty()) {
            std::vector<std::string> clip, joint;
            std::vector<std::int64_t> range;
            for (const RepairedFrames& x : set.repairs) {
                clip.push_back(x.clip);
                joint.push_back(x.joint);
                range.push_back(static_cast<std::int64_t>(x.begin));
                range.push_back(static_cast<std::int64_t>(x.end));
            }
            file.write_strings(r + "/clip", clip, "run", "");
            file.write_strings(r + "/joint", joint, "run", "");
            file.write_array(r + "/frames", range.data(), {static_cast<std::uint64_t>(set.repairs.size()), 2},
                             {"run", "range"}, "frame");
        }
    }
}

MotionSet read_set(const h5::File& file, const std::string& name) {
    const std::string g = set_path(name);
    if (file.type_of(g) != h5::ObjectType::Group) throw StoreError(file.name(), g, "no such motion set");
    MotionSet set;
    set.name = name;
    set.parameter_source = file.read_string_attribute(g, "parameter_source");
    const auto clips = file.read_strings(g + "/sample_clip");
    const std::uint64_t n = clips.size();
    const auto frames = file.read_array<std::int64_t>(g + "/sample_frames", 2);
    expect_shape(file, g + "/sample_frames", {n, 2}, "(one (begin, end) row per sample_clip)", frames.shape);
    for (std::size_t i = 0; i < n; ++i) {
        const std::int64_t b = frames.data[2 * i], e = frames.data[2 * i + 1];
        if (b < 0 || e < b)
            throw StoreError(file.name(), g + "/sample_frames",
                             "sample " + std::to_string(i) + ": expected 0 <= begin <= end, found [" +
                                 std::to_string(b) + ", " + std::to_string(e) + ")");
        set.samples.push_back({clips[i], static_cast<std::size_t>(b), static_cast<std::size_t>(e)});
    }
    set.parameter_names = file.read_strings(g + "/parameter_name");
    const std::uint64_t p = set.parameter_names.size();
    set.parameter_units = file.read_strings(g + "/parameter_unit");
    if (set.parameter_units.size() != p)
        shape_error(file, g + "/parameter_unit", {p}, "(one unit per parameter_name)", {set.parameter_units.size()});
    const auto params = file.read_array<double>(g + "/parameters", 2);
    expect_shape(file, g + "/parameters", {n, p}, "(samples by parameters)", params.shape);
    expect_finite(file, g + "/parameters", params.data);
    set.parameters = from_c_order(params.data, static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(p));
    if (file.type_of(g + "/parameter_period") == h5::ObjectType::Dataset) {
        const auto periods = file.read_array<double>(g + "/parameter_period", 1);
        expect_shape(file, g + "/parameter_period", {p}, "(one period per parameter_name)", periods.shape);
        expect_finite(file, g + "/parameter_period", periods.data);
        for (std::size_t k = 0; k < periods.data.size(); ++k)
            if (periods.data[k] < 0.0)
                throw StoreError(file.name(), g + "/parameter_period",
                                 "parameter " + std::to_string(k) +
                                     ": expected a period >= 0 (0 = not periodic), found " +
                                     std::to_string(periods.data[k]));
        set.parameter_periods = Eigen::Map<const VecX>(periods.data.data(), static_cast<Eigen::Index>(p));
    }
    if (file.type_of(g + "/parameter_level_count") == h5::ObjectType::Dataset) {
        const std::string where = g + "/parameter_level_count";
        const auto counts = file.read_array<std::int64_t>(where, 1);
        expect_shape(file, where, {p}, "(one level count per parameter_name)", counts.shape);
        const auto names = file.read_strings(g + "/parameter_level");
        std::size_t next = 0;
        for (std::size_t k = 0; k < counts.data.size(); ++k) {
            const std::int64_t c = counts.data[k];
            if (c == 1 || c < 0 || next + static_cast<std::size_t>(c) > names.size())
                throw StoreError(
                    file.name(), where,
                    "parameter " + std::to_string(k) + ": expected 0 (numeric) or >= 2 levels within the " +
                        std::to_string(names.size()) + " names of parameter_level, found " + std::to_string(c));
            set.parameter_levels.emplace_back(
                names.begin() + static_cast<std::ptrdiff_t>(next),
                names.begin() + static_cast<std::ptrdiff_t>(next + static_cast<std::size_t>(c)));
            next += static_cast<std::size_t>(c);
        }
        if (next != names.size())
            shape_error(file, g + "/parameter_level", {next}, "(the sum of parameter_level_count)", {names.size()});
        for (std::size_t k = 0; k < set.parameter_levels.size(); ++k) {
            const double levels = static_cast<double>(set.parameter_levels[k].size());
            const auto col = set.parameters.col(static_cast<Eigen::Index>(k));
            for (Eigen::Index i = 0; levels > 0 && i < col.size(); ++i)
                if (col(i) < 0.0 || col(i) >= levels || col(i) != std::floor(col(i)))
                    throw StoreError(file.name(), g + "/parameters",
                                     "sample " + std::to_string(i) + ", categorical parameter " + std::to_string(k) +
                                         ": expected a level index 0 to " +
                                         std::to_string(static_cast<long long>(levels) - 1) + ", found " +
                                         std::to_string(col(i)));
        }
    }
    // Sets stored before the dropout check have no repairs group: taken as stored, unrepaired.
    const std::string r = repairs_path(name);
    if (file.type_of(r) == h5::ObjectType::Group) {
        set.dropouts_checked = true;
        const std::int64_t runs = file.read_int_attribute(r, "runs");
        if (runs < 0)
            throw StoreError(file.name(), r, "attribute 'runs': expected >= 0, found " + std::to_string(runs));
        if (runs > 0) {
            const auto clip = file.read_strings(r + "/clip");
            const auto joint = file.read_strings(r + "/joint");
            const auto range = file.read_array<std::int64_t>(r + "/frames", 2);
            const auto count = static_cast<std::uint64_t>(runs);
            const std::string why = "(attribute 'runs' = " + std::to_string(runs) + ")";
            if (clip.size() != count) shape_error(file, r + "/clip", {count}, why, {clip.size()});
            if (joint.size() != count) shape_error(file, r + "/joint", {count}, why, {joint.size()});
            expect_shape(file, r + "/frames", {count, 2}, why, range.shape);
            for (std::size_t i = 0; i < count; ++i) {
                const std::int64_t b = range.data[2 * i], e = range.data[2 * i + 1];
                if (b < 0 || e <= b)
                    throw StoreError(file.name(), r + "/frames",
                                     "run " + std::to_string(i) + ": expected 0 <= begin < end, found [" +
                                         std::to_string(b) + ", " + std::to_string(e) + ")");
                set.repairs.push_back({clip[i], joint[i], static_cast<std::size_t>(b), static_cast<std::size_t>(e)});
            }
        }
    }
    return set;
}

void write_aligned(h5::File& file, const std::string& set, const AlignedSet& a) {
    const std::string g = aligned_path(set);
    file.create_group(g, "aligned_set");
    file.write_string_attribute(g, "method", a.method);
    file.write_int_attribute(g, "reference", static_cast<std::int64_t>(a.reference));
    const auto n = static_cast<std::uint64_t>(a.samples()), t = static_cast<std::uint64_t>(a.frames()),
               d = static_cast<std::uint64_t>(a.dofs());
    file.write_array(g + "/tensor", a.tensor.data(), c_order_shape(a.tensor), {"sample", "time", "dof"}, "pose");
    // warps is T by N, column-major: its buffer is the C-order (sample, time) array.
    file.write_array(g + "/warps", a.warps.data(), {n, t}, {"sample", "time"}, "frame");
    // Stored beside the warps for readers of the file (the synthesis kriges these increments).
    const MatX increments = a.inverse_warp_increments();
    file.write_array(g + "/inverse_warp_increments", increments.data(), {n, t - 1}, {"sample", "time_step"}, "frame");
    file.write_array(g + "/mean", a.mean.data(), {d}, {"dof"}, "pose");
    file.write_array(g + "/scale", a.scale.data(), {d}, {"dof"}, "pose");
    std::vector<double> translation, yaw;
    for (const Canonicalization& c : a.canonical) {
        translation.insert(translation.end(), {c.translation.x(), c.translation.y(), c.translation.z()});
        yaw.push_back(c.yaw);
    }
    file.write_array(g + "/canonical_translation", translation.data(), {n, 3}, {"sample", "xyz"}, "cm");
    file.write_array(g + "/canonical_yaw", yaw.data(), {n}, {"sample"}, "rad");
}

namespace {

// The warps (T by N) and the stored increments, which must equal their differences. `why` names the
// tensor's shape the expected shapes come from.
MatX read_warps(const h5::File& file, const std::string& g, std::uint64_t n, std::uint64_t t, const std::string& why) {
    const auto warps = file.read_array<double>(g + "/warps", 2);
    expect_shape(file, g + "/warps", {n, t}, why, warps.shape);
    expect_finite(file, g + "/warps", warps.data);
    MatX out = Eigen::Map<const MatX>(warps.data.data(), static_cast<Eigen::Index>(t), static_cast<Eigen::Index>(n));
    const auto increments = file.read_array<double>(g + "/inverse_warp_increments", 2);
    expect_shape(file, g + "/inverse_warp_increments", {n, t - 1}, why, increments.shape);
    const Eigen::Map<const MatX> stored(increments.data.data(), static_cast<Eigen::Index>(t - 1),
                                        static_cast<Eigen::Index>(n));
    const MatX differences = out.bottomRows(out.rows() - 1) - out.topRows(out.rows() - 1);
    const double mismatch = (stored - differences).cwiseAbs().maxCoeff();
    if (!(mismatch <= 1e-9 * std::max(1.0, out.cwiseAbs().maxCoeff())))
        throw StoreError(
            file.name(), g + "/inverse_warp_increments",
            "expected warps[:, 1:] - warps[:, :-1], found values differing by up to " + std::to_string(mismatch));
    return out;
}

std::string tensor_why(const std::string& g, const h5::Shape& shape) {
    return "(tensor " + g + "/tensor is " + h5::shape_text(shape) + " = (sample, time, dof))";
}

}  // namespace

AlignedSet read_aligned(const h5::File& file, const std::string& set) {
    const std::string g = aligned_path(set);
    AlignedSet a;
    a.method = file.read_string_attribute(g, "method");
    const std::int64_t reference = file.read_int_attribute(g, "reference");
    const auto tensor = file.read_array<double>(g + "/tensor", 3);
    const std::uint64_t n = tensor.shape[0], t = tensor.shape[1], d = tensor.shape[2];
    expect_finite(file, g + "/tensor", tensor.data);
    if (reference < 0 || static_cast<std::uint64_t>(reference) >= std::max<std::uint64_t>(n, 1))
        throw StoreError(file.name(), g,
                         "attribute 'reference': expected a sample index in [0, " + std::to_string(n) + "), found " +
                             std::to_string(reference));
    a.reference = static_cast<std::size_t>(reference);
    a.tensor = Tensor3(static_cast<Eigen::Index>(d), static_cast<Eigen::Index>(t), static_cast<Eigen::Index>(n));
    std::copy(tensor.data.begin(), tensor.data.end(), a.tensor.data());
    const std::string why = tensor_why(g, tensor.shape);
    a.warps = read_warps(file, g, n, t, why);
    const auto mean = file.read_array<double>(g + "/mean", 1);
    expect_shape(file, g + "/mean", {d}, why, mean.shape);
    expect_finite(file, g + "/mean", mean.data);
    a.mean = Eigen::Map<const VecX>(mean.data.data(), static_cast<Eigen::Index>(d));
    const auto scale = file.read_array<double>(g + "/scale", 1);
    expect_shape(file, g + "/scale", {d}, why, scale.shape);
    expect_finite(file, g + "/scale", scale.data);
    a.scale = Eigen::Map<const VecX>(scale.data.data(), static_cast<Eigen::Index>(d));
    const auto translation = file.read_array<double>(g + "/canonical_translation", 2);
    expect_shape(file, g + "/canonical_translation", {n, 3}, why, translation.shape);
    expect_finite(file, g + "/canonical_translation", translation.data);
    const auto yaw = file.read_array<double>(g + "/canonical_yaw", 1);
    expect_shape(file, g + "/canonical_yaw", {n}, why, yaw.shape);
    expect_finite(file, g + "/canonical_yaw", yaw.data);
    for (std::size_t s = 0; s < n; ++s) {
        Canonicalization c;
        c.translation = Vec3(translation.data[3 * s], translation.data[3 * s + 1], translation.data[3 * s + 2]);
        c.yaw = yaw.data[s];
        a.canonical.push_back(c);
    }
    return a;
}

AlignedTiming read_aligned_timing(const h5::File& file, const std::string& set) {
    const std::string g = aligned_path(set);
    // The tensor's header only (dtype and shape, as read_aligned's read would check them): no values.
    const h5::DatasetInfo info = file.dataset_info(g + "/tensor");
    if (info.dtype != "float64")
        throw StoreError(file.name(), g + "/tensor", "expected dtype float64, found " + info.dtype);
    if (info.shape.size() != 3)
        throw StoreError(file.name(), g + "/tensor",
                         "expected 3 dimensions, found shape " + h5::shape_text(info.shape));
    const std::uint64_t n = info.shape[0], t = info.shape[1], d = info.shape[2];
    AlignedTiming a;
    a.dof_count = static_cast<Eigen::Index>(d);
    a.warps = read_warps(file, g, n, t, tensor_why(g, info.shape));
    return a;
}

}  // namespace mocapdb::store
