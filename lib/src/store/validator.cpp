// mocapdb validate: every object of the file against the schema mirror of the file's format version,
// then the content rules the mirror cannot express (clip columns against skeletons, set samples
// against clips, aligned tensors against sets, models against aligned tensors), reporting violations
// instead of throwing.
#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <unordered_map>

#include "h5/file.hpp"
#include "layout.hpp"
#include "h5/quiet.hpp"
#include "mocapdb/core/error.hpp"
#include "mocapdb/motion/pose_vector.hpp"
#include "mocapdb/packing/group_decoder.hpp"
#include "packed_codec.hpp"
#include "mocapdb/store/database.hpp"
#include "mocapdb/store/validate.hpp"
#include "root.hpp"
#include "schema.hpp"
#include "segments.hpp"
#include "schema_text.hpp"

namespace mocapdb {
namespace {

using store::AttributeSpec;
using store::Extent;
using store::JsonValue;
using store::ObjectSpec;
using store::ValueRules;
using store::h5::ObjectType;

using Bindings = std::vector<std::pair<std::string, std::string>>;  // placeholder -> link name

class Validator {
public:
    Validator(const store::h5::File& file, const store::Schema& schema, const ValidateOptions& options,
              ValidationReport& report)
        : f_(file), schema_(schema), options_(options), report_(report) {}

    void run() {
        if (options_.progress) {
            try {
                progress_total_ = 2 * f_.children(store::kClips).size();
            } catch (const Error&) {
                progress_total_ = 0;  // reported by visit()
            }
        }
        visit("/", {});
        check_required();
    }

    /// One clip checked (by the structure pass, then by the content pass).
    void progress_step(const std::string& clip) {
        if (options_.progress) options_.progress({++progress_done_, std::max(progress_total_, progress_done_), clip});
    }

    void add(const std::string& path, const std::string& message) {
        if (report_.violations.size() < options_.max_violations) {
            report_.violations.push_back({path, message});
        } else {
            report_.truncated = true;
        }
    }

private:
    const store::h5::File& f_;
    const store::Schema& schema_;
    const ValidateOptions& options_;
    ValidationReport& report_;
    const std::string clips_prefix_ = std::string(store::kClips) + "/";
    std::uint64_t progress_done_ = 0;
    std::uint64_t progress_total_ = 0;
    // symbol key -> (extent, where it was bound)
    std::map<std::string, std::pair<std::uint64_t, std::string>> symbols_;
    // pattern index -> concrete paths matched
    std::map<std::size_t, std::vector<std::string>> matched_;

    std::optional<std::size_t> match(const std::string& path, Bindings& bindings) const {
        const auto parts = store::split_path(path);
        for (std::size_t i = 0; i < schema_.objects.size(); ++i) {
            const auto& seg = schema_.objects[i].segments;
            if (seg.size() != parts.size()) continue;
            Bindings b;
            bool ok = true;
            for (std::size_t k = 0; k < seg.size() && ok; ++k) {
                if (store::is_placeholder(seg[k])) {
                    b.emplace_back(seg[k], parts[k]);
                } else {
                    ok = seg[k] == parts[k];
                }
            }
            if (ok) {
                bindings = b;
                return i;
            }
        }
        return std::nullopt;
    }

    static std::string child(const std::string& parent, const std::string& name) {
        return parent == "/" ? "/" + name : parent + "/" + name;
    }

    void visit(const std::string& path, const Bindings& /*parent*/) {
        ++report_.objects;
        Bindings bindings;
        const auto index = match(path, bindings);
        ObjectType type;
        try {
            type = f_.type_of(path);
        } catch (const Error& e) {
            add(path, e.what());
            return;
        }
        if (!index) {
            add(path, std::string("unexpected ") + (type == ObjectType::Group ? "group" : "object") +
                          " (not part of format version " + std::to_string(schema_.format_version) + ")");
            return;
        }
        const ObjectSpec& spec = schema_.objects[*index];
        if (spec.group != (type == ObjectType::Group) || (!spec.group && type != ObjectType::Dataset)) {
            add(path, std::string("expected a ") + (spec.group ? "group" : "dataset") + ", found " +
                          (type == ObjectType::Group     ? "a group"
                           : type == ObjectType::Dataset ? "a dataset"
                                                         : "another kind of object"));
            return;
        }
        matched_[*index].push_back(path);
        try {
            check_attributes(path, spec, bindings);
            if (!spec.group) check_dataset(path, spec, bindings);
        } catch (const Error& e) {
            add(path, e.what());
        }
        if (spec.group) {
            std::vector<std::string> names;
            try {
                names = f_.children(path);
            } catch (const Error& e) {
                add(path, e.what());
            }
            for (const std::string& name : names) visit(child(path, name), bindings);
        }
        if (path.size() > clips_prefix_.size() && path.compare(0, clips_prefix_.size(), clips_prefix_) == 0 &&
            path.find('/', clips_prefix_.size()) == std::string::npos)
            progress_step(path.substr(clips_prefix_.size()));
    }

    void check_required() {
        for (std::size_t i = 0; i < schema_.objects.size(); ++i) {
            const ObjectSpec& spec = schema_.objects[i];
            if (!spec.required) continue;
            // Instances of the parent pattern must contain this object.
            std::vector<std::string> parents;
            if (spec.segments.size() <= 1) {
                parents.push_back("/");
            } else {
                for (std::size_t p = 0; p < schema_.objects.size(); ++p) {
                    const auto& seg = schema_.objects[p].segments;
                    if (seg.size() + 1 == spec.segments.size() &&
                        std::equal(seg.begin(), seg.end(), spec.segments.begin()))
                        for (const std::string& m : matched_[p]) parents.push_back(m);
                }
            }
            for (const std::string& parent : parents) {
                const std::string path = spec.segments.empty() ? "/" : child(parent, spec.segments.back());
                if (!f_.exists(path))
                    add(path, std::string("missing ") + (spec.group ? "group" : "dataset") + " (format version " +
                                  std::to_string(schema_.format_version) + " requires it" +
                                  (spec.group ? ", kind '" + spec.kind + "')" : ", " + spec.dtype + ")"));
            }
        }
    }

    std::string key_of(const std::string& symbol, const Bindings& b) const {
        std::string k = symbol;
        for (const auto& [name, value] : b) k += "|" + name + "=" + value;
        return k;
    }

    void bind(const std::string& path, const std::string& what, const Extent& e, std::uint64_t found,
              const Bindings& b) {
        if (e.symbol.empty()) {
            if (found != e.value)
                add(path, what + ": expected " + std::to_string(e.value) + ", found " + std::to_string(found));
            return;
        }
        const std::string key = key_of(e.symbol, b);
        const auto it = symbols_.find(key);
        if (it == symbols_.end()) {
            symbols_.emplace(key, std::make_pair(found, path + " " + what));
        } else if (it->second.first != found) {
            add(path, what + ": expected " + std::to_string(it->second.first) + " (" + e.symbol + " as in " +
                          it->second.second + "), found " + std::to_string(found));
        }
    }

    static std::string shape_spec_text(const std::vector<Extent>& shape) {
        if (shape.empty()) return "scalar";
        std::string out = "(";
        for (std::size_t k = 0; k < shape.size(); ++k)
            out += (k ? ", " : "") + (shape[k].symbol.empty() ? std::to_string(shape[k].value) : shape[k].symbol);
        return out + (shape.size() == 1 ? ",)" : ")");
    }

    void check_value(const std::string& path, const std::string& what, const JsonValue& v, const ValueRules& r) {
        const bool number = v.type == JsonValue::Type::Number;
        if (r.value && r.value->dump() != v.dump())
            add(path, what + ": expected " + r.value->dump() + ", found " + v.dump());
        if (!r.one_of.empty() &&
            std::none_of(r.one_of.begin(), r.one_of.end(), [&](const JsonValue& x) { return x.dump() == v.dump(); })) {
            std::string allowed;
            for (const JsonValue& x : r.one_of) allowed += (allowed.empty() ? "" : ", ") + x.dump();
            add(path, what + ": expected one of " + allowed + ", found " + v.dump());
        }
        if (number && r.min && !(v.number >= *r.min))
            add(path, what + ": expected >= " + json_number(*r.min).dump() + ", found " + v.dump());
        if (number && r.exclusive_min && !(v.number > *r.exclusive_min))
            add(path, what + ": expected > " + json_number(*r.exclusive_min).dump() + ", found " + v.dump());
        if (number && !std::isfinite(v.number)) add(path, what + ": expected a finite number, found " + v.dump());
        if (r.pattern == "hex64") {
            const bool ok = v.type == JsonValue::Type::String && v.string.size() == 64 &&
                            std::all_of(v.string.begin(), v.string.end(),
                                        [](char c) { return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'); });
            if (!ok) add(path, what + ": expected 64 lowercase hex digits, found " + v.dump());
        }
        if (!r.ref.empty() && v.type == JsonValue::Type::String) {
            std::string target = r.ref;
            target.replace(target.find("{}"), 2, v.string);
            bool exists = false;
            try {
                exists = !v.string.empty() && v.string.find('/') == std::string::npos && f_.exists(target);
            } catch (const Error&) {}
            if (!exists) add(path, what + ": refers to " + target + ", which does not exist");
        }
    }

    static JsonValue json_string(const std::string& s) {
        JsonValue v;
        v.type = JsonValue::Type::String;
        v.string = s;
        return v;
    }
    static JsonValue json_number(double x) {
        JsonValue v;
        v.type = JsonValue::Type::Number;
        v.number = x;
        return v;
    }

    void check_attribute(const std::string& path, const std::string& name, const std::string& dtype,
                         const std::vector<Extent>& shape, const ValueRules& rules, const Bindings& b) {
        const std::string what = "attribute '" + name + "'";
        const store::h5::AttributeInfo info = f_.attribute_info(path, name);
        if (info.dtype != dtype || info.shape.size() != shape.size()) {
            add(path, what + ": expected " + dtype + " " + shape_spec_text(shape) + ", found " + info.dtype + " " +
                          store::h5::shape_text(info.shape));
            return;
        }
        for (std::size_t k = 0; k < shape.size(); ++k)
            bind(path, what + " axis " + std::to_string(k), shape[k], info.shape[k], b);
        if (!rules.any()) return;
        std::vector<JsonValue> values;
        if (dtype == "string") {
            if (shape.empty()) {
                values.push_back(json_string(f_.read_string_attribute(path, name)));
            } else {
                for (const std::string& s : f_.read_strings_attribute(path, name)) values.push_back(json_string(s));
            }
        } else if (dtype == "int64" && shape.empty()) {
            values.push_back(json_number(static_cast<double>(f_.read_int_attribute(path, name))));
        } else if (dtype == "int64") {
            for (const std::int64_t x : f_.read_ints_attribute(path, name))
                values.push_back(json_number(static_cast<double>(x)));
        } else if (dtype == "float64") {
            if (shape.empty()) {
                values.push_back(json_number(f_.read_double_attribute(path, name)));
            } else {
                for (double x : f_.read_doubles_attribute(path, name)) values.push_back(json_number(x));
            }
        }
        for (const JsonValue& v : values) check_value(path, what, v, rules);
    }

    void check_attributes(const std::string& path, const ObjectSpec& spec, const Bindings& b) {
        const std::vector<std::string> present = f_.attribute_names(path);
        auto has = [&](const std::string& name) {
            return std::find(present.begin(), present.end(), name) != present.end();
        };
        for (const std::string& name : present) {
            if (!schema_.user_attribute_prefix.empty() && name.rfind(schema_.user_attribute_prefix, 0) == 0) continue;
            const bool known = std::any_of(spec.attributes.begin(), spec.attributes.end(),
                                           [&](const AttributeSpec& a) { return a.name == name; }) ||
                               (!spec.group && (name == "dims" || name == "units"));
            if (!known)
                add(path, "unexpected attribute '" + name + "' (not part of format version " +
                              std::to_string(schema_.format_version) + "; user attributes must start with '" +
                              schema_.user_attribute_prefix + "')");
        }
        for (const AttributeSpec& a : spec.attributes) {
            if (!has(a.name)) {
                if (a.required)
                    add(path, "missing attribute '" + a.name + "' (expected " + a.dtype + " " +
                                  shape_spec_text(a.shape) + ")");
                continue;
            }
            check_attribute(path, a.name, a.dtype, a.shape, a.rules, b);
        }
        if (spec.group) return;
        ValueRules dims_rule;
        JsonValue dims;
        dims.type = JsonValue::Type::Array;
        for (const std::string& d : spec.dims) dims.array.push_back(json_string(d));
        if (!has("dims")) {
            add(path, "missing attribute 'dims' (expected " + dims.dump() + ")");
        } else {
            const auto info = f_.attribute_info(path, "dims");
            if (info.dtype != "string" || info.shape.size() != 1) {
                add(path, "attribute 'dims': expected string (" + std::to_string(spec.dims.size()) + ",), found " +
                              info.dtype + " " + store::h5::shape_text(info.shape));
            } else {
                JsonValue found;
                found.type = JsonValue::Type::Array;
                for (const std::string& d : f_.read_strings_attribute(path, "dims"))
                    found.array.push_back(json_string(d));
                if (found.dump() != dims.dump())
                    add(path, "attribute 'dims': expected " + dims.dump() + ", found " + found.dump());
            }
        }
        ValueRules units_rule;
        units_rule.value = json_string(spec.units);
        if (!has("units")) {
            add(path, "missing attribute 'units' (expected \"" + spec.units + "\")");
        } else {
            check_attribute(path, "units", "string", {}, units_rule, b);
        }
    }

    std::vector<JsonValue> element_values(const std::string& path, const std::string& dtype) {
        std::vector<JsonValue> out;
        if (dtype == "string" || dtype == "fixed-string") {
            for (const std::string& s : f_.read_strings(path)) out.push_back(json_string(s));
        } else if (dtype == "float64") {
            const auto a = f_.read_array<double>(path, static_cast<std::size_t>(f_.dataset_info(path).shape.size()));
            for (double x : a.data) out.push_back(json_number(x));
        } else if (dtype == "int64") {
            const auto a = f_.read_array<std::int64_t>(path, f_.dataset_info(path).shape.size());
            for (auto x : a.data) out.push_back(json_number(static_cast<double>(x)));
        } else if (dtype == "int32") {
            const auto a = f_.read_array<std::int32_t>(path, f_.dataset_info(path).shape.size());
            for (auto x : a.data) out.push_back(json_number(x));
        } else if (dtype == "uint8") {
            const auto a = f_.read_array<std::uint8_t>(path, f_.dataset_info(path).shape.size());
            for (auto x : a.data) out.push_back(json_number(x));
        }
        return out;
    }

    void check_dataset(const std::string& path, const ObjectSpec& spec, const Bindings& b) {
        const store::h5::DatasetInfo info = f_.dataset_info(path);
        if (info.dtype != spec.dtype || info.shape.size() != spec.shape.size()) {
            add(path, "expected " + spec.dtype + " " + shape_spec_text(spec.shape) + " " + dims_text(spec.dims) +
                          ", found " + info.dtype + " " + store::h5::shape_text(info.shape));
            return;
        }
        for (std::size_t k = 0; k < spec.shape.size(); ++k)
            bind(path, "axis " + std::to_string(k) + " ('" + spec.dims[k] + "')", spec.shape[k], info.shape[k], b);
        std::uint64_t count = 1;
        for (auto e : info.shape) count *= e;
        if (count > 0) {
            std::vector<std::string> missing;
            for (const std::string& filter : spec.filters)
                if (std::find(info.filters.begin(), info.filters.end(), filter) == info.filters.end())
                    missing.push_back(filter);
            if (!missing.empty()) {
                std::string want, have;
                for (const auto& x : spec.filters) want += (want.empty() ? "" : ", ") + x;
                for (const auto& x : info.filters) have += (have.empty() ? "" : ", ") + x;
                add(path, "expected filters " + want + ", found " + (have.empty() ? std::string("none") : have));
            }
        }
        // Reading everything verifies the checksums.
        try {
            f_.read_and_discard(path);
            ++report_.datasets_read;
            if (spec.rules.any()) {
                std::size_t reported = 0;
                const std::size_t before = report_.violations.size();
                const auto values = element_values(path, spec.dtype);
                for (std::size_t k = 0; k < values.size() && reported < 3; ++k) {
                    check_value(path, "element " + std::to_string(k), values[k], spec.rules);
                    reported = report_.violations.size() - before;
                }
            }
        } catch (const Error& e) {
            add(path, e.what());
        }
    }

    static std::string dims_text(const std::vector<std::string>& dims) {
        std::string out = "dims (";
        for (std::size_t k = 0; k < dims.size(); ++k) out += (k ? ", " : "") + dims[k];
        return out + ")";
    }
};

// The packed tier: records readable, each clip packed once with its stored frame count, and each
// group's bytes parse with the clip count, frame counts and rate the records give.
void check_packed(const std::filesystem::path& file, const Database& db,
                  const std::map<std::string, ClipRecord>& records, Validator& v) {
    std::optional<PackedTierRecord> tier;
    try {
        tier = db.packed();
    } catch (const StoreError& e) {
        v.add(e.object_path().empty() ? store::kPacked : e.object_path(), e.message());
        return;
    }
    // A clip without lossless channels must be in the packed tier: it is its only copy.
    auto check_dropped = [&](const std::map<std::string, std::string>& packed_clips) {
        for (const auto& [id, r] : records)
            if (!r.lossless && packed_clips.count(id) == 0)
                v.add(store::clip_path(id),
                      "the clip's lossless channels were dropped but it is not in /packed: its motion is lost");
    };
    if (!tier) {
        check_dropped({});
        return;
    }
    store::h5::File f = store::h5::File::open(file, false);
    std::map<std::string, std::string> seen;
    std::size_t clips = 0, frames = 0;
    for (const PackedGroupRecord& g : tier->groups) {
        const std::string gpath = store::packed_group_path(g.name);
        std::size_t group_frames = 0;
        for (const PackedClipRecord& c : g.clips) {
            group_frames += c.frames;
            const auto [it, fresh] = seen.emplace(c.id, gpath);
            if (!fresh)
                v.add(gpath + "/clip", "clip '" + c.id + "' is packed in " + it->second + " too (expected once)");
            const auto r = records.find(c.id);
            if (r != records.end() && r->second.frames != c.frames)
                v.add(gpath + "/clip_frames", "clip '" + c.id + "': expected " + std::to_string(r->second.frames) +
                                                  " frames (as stored in /clips), found " + std::to_string(c.frames));
        }
        clips += g.clips.size();
        frames += group_frames;
        if (group_frames != g.frames)
            v.add(gpath, "attribute 'frames': expected " + std::to_string(group_frames) +
                             " (the sum of clip_frames), found " + std::to_string(g.frames));
        const std::string bpath = gpath + "/bytes";
        try {
            std::vector<std::uint8_t> group_bytes = store::read_packed_bytes(f, g.name);
            const std::string codec = f.read_string_attribute(bpath, "codec");
            if (codec != store::packed_group_codec(group_bytes))
                v.add(bpath, "attribute 'codec' is \"" + codec + "\", the bytes are \"" +
                                 store::packed_group_codec(group_bytes) + "\"");
            const packing::GroupDecoder decoder(std::move(group_bytes));
            if (decoder.clip_count() != g.clips.size()) {
                v.add(bpath, "the bytes hold " + std::to_string(decoder.clip_count()) + " clips, expected " +
                                 std::to_string(g.clips.size()) + " (" + gpath + "/clip)");
                continue;
            }
            if (decoder.frame_rate() != g.frame_rate)
                v.add(bpath, "the bytes are at " + std::to_string(decoder.frame_rate()) + " Hz, expected " +
                                 std::to_string(g.frame_rate) + " (attribute 'frame_rate' of " + gpath + ")");
            for (std::size_t i = 0; i < g.clips.size(); ++i)
                if (decoder.frame_count(i) != g.clips[i].frames)
                    v.add(bpath, "clip " + std::to_string(i) + " ('" + g.clips[i].id + "') has " +
                                     std::to_string(decoder.frame_count(i)) + " frames in the bytes, expected " +
                                     std::to_string(g.clips[i].frames) + " (" + gpath + "/clip_frames)");
        } catch (const StoreError& e) {
            v.add(e.object_path().empty() ? bpath : e.object_path(), e.message());
        } catch (const Error& e) {
            v.add(bpath, std::string("the bytes do not parse: ") + e.what());
        }
    }
    check_dropped(seen);
    std::uint64_t bytes = 0;
    for (const PackedGroupRecord& g : tier->groups) bytes += g.bytes;
    if (bytes != tier->bytes)
        v.add(store::kPacked, "attribute 'bytes': expected " + std::to_string(bytes) +
                                  " (the sum of the groups' bytes), found " + std::to_string(tier->bytes));
    if (clips != tier->clips)
        v.add(store::kPacked,
              "attribute 'clips': expected " + std::to_string(clips) + ", found " + std::to_string(tier->clips));
    if (frames != tier->frames)
        v.add(store::kPacked,
              "attribute 'frames': expected " + std::to_string(frames) + ", found " + std::to_string(tier->frames));
}

// Content rules beyond the mirror, through the same loaders the library uses.
void check_content(const std::filesystem::path& file, Validator& v) {
    Database db(file);
    std::unordered_map<std::string, std::string> sha;
    std::map<std::string, ClipRecord> records;
    for (const std::string& id : [&] {
             std::vector<std::string> ids;
             try {
                 for (const ClipRecord& r : db.clips()) {
                     ids.push_back(r.id);
                     records.emplace(r.id, r);
                 }
             } catch (const Error& e) {
                 v.add(store::kClips, e.what());
             }
             return ids;
         }()) {
        const std::string path = store::clip_path(id);
        try {
            const auto [it, fresh] = sha.emplace(records.at(id).source.sha256, id);
            if (!fresh)
                v.add(path, "attribute 'source_sha256' repeats clip " + it->second + " (expected unique sources)");
            db.load_clip(id);
        } catch (const StoreError& e) {
            v.add(e.object_path().empty() ? path : e.object_path(), e.message());
        } catch (const Error& e) {
            v.add(path, e.what());
        }
        v.progress_step(id);
    }
    for (const std::string& name : db.set_names()) {
        const std::string path = store::set_path(name);
        try {
            const MotionSet set = db.load_set(name);
            try {
                validate(set);
            } catch (const InvalidArgument& e) {
                v.add(path, e.what());
            }
            std::string skeleton;
            for (std::size_t i = 0; i < set.samples.size(); ++i) {
                const SampleRef& s = set.samples[i];
                const auto it = records.find(s.clip);
                if (it == records.end()) continue;  // reported by the ref rule
                if (s.end > it->second.frames)
                    v.add(path + "/sample_frames", "sample " + std::to_string(i) + ": [" + std::to_string(s.begin) +
                                                       ", " + std::to_string(s.end) + ") lies beyond clip '" + s.clip +
                                                       "' (" + std::to_string(it->second.frames) + " frames)");
                if (skeleton.empty()) skeleton = it->second.skeleton;
                if (it->second.skeleton != skeleton &&
                    !db.load_skeleton(it->second.skeleton)->same_structure(*db.load_skeleton(skeleton)))
                    v.add(path + "/sample_clip", "sample " + std::to_string(i) + ": clip '" + s.clip +
                                                     "' has skeleton '" + it->second.skeleton +
                                                     "', whose structure differs from sample 0's '" + skeleton +
                                                     "' (a set shares one skeleton structure)");
            }
            // The model's shapes against the aligned tensor (D, T, N; 1 <= R <= the dimension), its
            // values, and that it has an aligned tensor at all.
            try {
                db.load_model(name);
                db.load_kernel_fit(name);
            } catch (const StoreError& e) {
                v.add(e.object_path().empty() ? store::model_path(name) : e.object_path(), e.message());
            }
            const auto aligned = db.load_aligned(name);
            if (!aligned) continue;
            const std::string apath = store::aligned_path(name);
            try {
                validate(*aligned);
            } catch (const InvalidArgument& e) {
                v.add(apath, e.what());
            }
            if (static_cast<std::size_t>(aligned->samples()) != set.samples.size())
                v.add(apath + "/tensor", "expected " + std::to_string(set.samples.size()) +
                                             " samples (the set's), found " + std::to_string(aligned->samples()));
            if (!skeleton.empty()) {
                const std::size_t d = PoseLayout(*db.load_skeleton(skeleton)).dof_count();
                if (static_cast<std::size_t>(aligned->dofs()) != d)
                    v.add(apath + "/tensor", "expected " + std::to_string(d) + " dofs (pose vectors of skeleton '" +
                                                 skeleton + "'), found " + std::to_string(aligned->dofs()));
            }
        } catch (const StoreError& e) {
            v.add(e.object_path().empty() ? path : e.object_path(), e.message());
        } catch (const Error& e) {
            v.add(path, e.what());
        }
    }
    check_packed(file, db, records, v);
}

}  // namespace

const std::string& builtin_schema_json() { return builtin_schema_json(kDatabaseFormatVersion); }

const std::string& builtin_schema_json(int format_version) {
    static const std::map<int, std::string> texts = [] {
        std::map<int, std::string> out;
        for (int v = store::kOldestDatabaseFormatVersion; v <= kDatabaseFormatVersion; ++v)
            if (const char* text = store::schema_json_text(v)) out.emplace(v, text);
        return out;
    }();
    const auto it = texts.find(format_version);
    if (it == texts.end())
        throw InvalidArgument("builtin_schema_json: no schema mirror for format version " +
                              std::to_string(format_version) + " (this mocapdb reads versions " +
                              std::to_string(store::kOldestDatabaseFormatVersion) + " to " +
                              std::to_string(kDatabaseFormatVersion) + ")");
    return it->second;
}

ValidationReport validate_database(const std::filesystem::path& file, const ValidateOptions& options) {
    store::h5::QuietScope quiet;
    std::error_code ec;
    if (!std::filesystem::exists(file, ec)) throw IoError(file.string() + ": no such file");
    // A custom mirror is parsed first, so that a malformed one is refused whatever the file.
    std::optional<store::Schema> custom;
    if (!options.schema_json.empty()) custom = store::parse_schema(options.schema_json, "schema");
    ValidationReport report;
    store::h5::File f;
    int version = 0;
    try {
        f = store::h5::File::open(file, false);
        version = store::check_root(f);
        report.format_version = version;
    } catch (const StoreError& e) {
        report.violations.push_back({e.object_path().empty() ? "/" : e.object_path(), e.message()});
        return report;
    }
    // Format 4: every top-level object is an external link to a segment file that exists.
    if (version >= 4) {
        for (const std::string& path : store::top_level_objects(f)) {
            const auto target = f.external_target(path);
            if (!target) {
                report.violations.push_back({path,
                                             "expected an external link into a segment (format 4), found an object "
                                             "stored in the index"});
                continue;
            }
            const std::filesystem::path segment = store::segment_file(file, target->first);
            if (!is_hdf5_file(segment))
                report.violations.push_back(
                    {path, "links to segment '" + target->first + "', which " +
                               (std::filesystem::exists(segment, ec) ? "is not an HDF5 file" : "is missing") +
                               " (a database is its file and the folder " +
                               store::segment_dir(file.filename()).string() + " beside it)"});
            else if (target->second != path)
                report.violations.push_back(
                    {path, "links to " + target->second + " in its segment (expected the same path)"});
        }
        if (!report.ok()) return report;
    }
    // The mirror of the file's own version: a version-1 file is checked against format-v1.json.
    const store::Schema schema =
        custom ? *custom
               : store::parse_schema(builtin_schema_json(version), "format-v" + std::to_string(version) + ".json");
    Validator v(f, schema, options, report);
    v.run();
    f.close();
    // The structure must hold before the content rules can be read meaningfully.
    if (report.ok()) {
        try {
            check_content(file, v);
        } catch (const StoreError& e) {
            v.add(e.object_path().empty() ? "/" : e.object_path(), e.message());
        }
    }
    return report;
}

}  // namespace mocapdb
