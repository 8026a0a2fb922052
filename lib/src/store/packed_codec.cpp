#include "packed_codec.hpp"

#include <algorithm>
#include <cmath>

#include "layout.hpp"
#include "mocapdb/store/store_error.hpp"

namespace mocapdb::store {
namespace {

double figure(const h5::File& file, const std::string& path, const char* name, bool positive) {
    const double v = file.read_double_attribute(path, name);
    if (!std::isfinite(v) || v < 0.0 || (positive && v == 0.0))
        throw StoreError(file.name(), path,
                         std::string("attribute '") + name + "': expected a finite number " +
                             (positive ? "> 0" : ">= 0") + ", found " + std::to_string(v));
    return v;
}

std::size_t count(const h5::File& file, const std::string& path, const char* name) {
    const std::int64_t v = file.read_int_attribute(path, name);
    if (v < 0)
        throw StoreError(file.name(), path,
                         std::string("attribute '") + name + "': expected >= 0, found " + std::to_string(v));
    return static_cast<std::size_t>(v);
}

void expect_rows(const h5::File& file, const std::string& path, const h5::Shape& shape, std::size_t n,
                 const std::string& clip_path) {
    if (shape.empty() || shape[0] != n)
        throw StoreError(file.name(), path,
                         "expected " + std::to_string(n) + " rows (one per clip of " + clip_path + "), found shape " +
                             h5::shape_text(shape));
}

}  // namespace

std::string packed_group_codec(const std::vector<std::uint8_t>& bytes) {
    if (bytes.size() < 5 || bytes[0] != 'M' || bytes[1] != 'D' || bytes[2] != 'B' || bytes[3] != 'P')
        throw Error("packed group bytes: no 'MDBP' magic");
    switch (bytes[4]) {
        case 4: return kPackedGroupCodecRuntime;
        case 3: return kPackedGroupCodec;
        case 2: return kPackedGroupCodecV2;
        default: throw Error("packed group bytes: version " + std::to_string(bytes[4]) + ", expected 2, 3 or 4");
    }
}

void write_packed(h5::File& file, const PackedTierRecord& tier,
                  const std::vector<std::vector<std::uint8_t>>& group_bytes) {
    file.create_group(kPacked, "packed");
    file.write_double_attribute(kPacked, "max_error_cm", tier.max_error_cm);
    file.write_int_attribute(kPacked, "bytes", static_cast<std::int64_t>(tier.bytes));
    file.write_int_attribute(kPacked, "clips", static_cast<std::int64_t>(tier.clips));
    file.write_int_attribute(kPacked, "frames", static_cast<std::int64_t>(tier.frames));
    file.write_double_attribute(kPacked, "max_cm", tier.max_cm);
    file.write_double_attribute(kPacked, "p99_cm", tier.p99_cm);
    file.write_double_attribute(kPacked, "rmse_cm", tier.rmse_cm);
    for (std::size_t i = 0; i < tier.groups.size(); ++i) {
        const PackedGroupRecord& r = tier.groups[i];
        const std::string g = packed_group_path(r.name);
        file.create_group(g, "packed_group");
        file.write_string_attribute(g, "skeleton", r.skeleton);
        file.write_double_attribute(g, "frame_rate", r.frame_rate);
        file.write_int_attribute(g, "frames", static_cast<std::int64_t>(r.frames));
        file.write_double_attribute(g, "max_cm", r.max_cm);
        file.write_double_attribute(g, "p99_cm", r.p99_cm);
        file.write_double_attribute(g, "rmse_cm", r.rmse_cm);
        file.write_compressed_bytes(g + "/bytes", group_bytes[i], "byte", "");
        file.write_string_attribute(g + "/bytes", "codec", packed_group_codec(group_bytes[i]));
        const std::size_t n = r.clips.size();
        std::vector<std::string> ids;
        std::vector<std::int64_t> frames, payload;
        std::vector<double> errors;  // C order (clip, statistic)
        for (const PackedClipRecord& c : r.clips) {
            ids.push_back(c.id);
            frames.push_back(static_cast<std::int64_t>(c.frames));
            payload.push_back(static_cast<std::int64_t>(c.payload_bytes));
            errors.insert(errors.end(), {c.max_cm, c.p99_cm, c.rmse_cm});
        }
        file.write_strings(g + "/clip", ids, "clip", "");
        file.write_array(g + "/clip_frames", frames.data(), {n}, {"clip"}, "");
        file.write_array(g + "/clip_payload_bytes", payload.data(), {n}, {"clip"}, "byte");
        file.write_array(g + "/clip_error", errors.data(), {n, 3}, {"clip", "statistic"}, "cm");
    }
}

PackedTierRecord read_packed_record(const h5::File& file) {
    PackedTierRecord t;
    if (file.type_of(kPacked) != h5::ObjectType::Group)
        throw StoreError(file.name(), kPacked, "expected a group of kind 'packed'");
    t.max_error_cm = figure(file, kPacked, "max_error_cm", true);
    t.bytes = count(file, kPacked, "bytes");
    t.clips = count(file, kPacked, "clips");
    t.frames = count(file, kPacked, "frames");
    t.max_cm = figure(file, kPacked, "max_cm", false);
    t.p99_cm = figure(file, kPacked, "p99_cm", false);
    t.rmse_cm = figure(file, kPacked, "rmse_cm", false);
    for (const std::string& name : file.children(kPacked)) {
        const std::string g = packed_group_path(name);
        if (file.type_of(g) != h5::ObjectType::Group)
            throw StoreError(file.name(), g, "expected a group of kind 'packed_group', found another object");
        PackedGroupRecord r;
        r.name = name;
        r.skeleton = file.read_string_attribute(g, "skeleton");
        r.frame_rate = figure(file, g, "frame_rate", true);
        r.frames = count(file, g, "frames");
        r.max_cm = figure(file, g, "max_cm", false);
        r.p99_cm = figure(file, g, "p99_cm", false);
        r.rmse_cm = figure(file, g, "rmse_cm", false);
        const h5::DatasetInfo bytes = file.dataset_info(g + "/bytes");
        if (bytes.dtype != "uint8" || bytes.shape.size() != 1)
            throw StoreError(file.name(), g + "/bytes",
                             "expected uint8 (byte), found " + bytes.dtype + " " + h5::shape_text(bytes.shape));
        const std::string codec = file.read_string_attribute(g + "/bytes", "codec");
        if (codec != kPackedGroupCodecRuntime && codec != kPackedGroupCodec && codec != kPackedGroupCodecV2)
            throw StoreError(file.name(), g + "/bytes",
                             "attribute 'codec': expected \"" + kPackedGroupCodecRuntime + "\", \"" +
                                 kPackedGroupCodec + "\" or \"" + kPackedGroupCodecV2 + "\", found \"" + codec + "\"");
        r.bytes = bytes.shape[0];
        r.stored_bytes = bytes.stored_bytes;
        const std::vector<std::string> ids = file.read_strings(g + "/clip");
        const std::size_t n = ids.size();
        const auto frames = file.read_array<std::int64_t>(g + "/clip_frames", 1);
        expect_rows(file, g + "/clip_frames", frames.shape, n, g + "/clip");
        const auto payload = file.read_array<std::int64_t>(g + "/clip_payload_bytes", 1);
        expect_rows(file, g + "/clip_payload_bytes", payload.shape, n, g + "/clip");
        const auto errors = file.read_array<double>(g + "/clip_error", 2);
        expect_rows(file, g + "/clip_error", errors.shape, n, g + "/clip");
        if (errors.shape[1] != 3)
            throw StoreError(file.name(), g + "/clip_error",
                             "expected shape (N, 3) (max, p99, rmse per clip), found " + h5::shape_text(errors.shape));
        for (const std::string& d : {std::string("/clip"), std::string("/clip_frames"),
                                     std::string("/clip_payload_bytes"), std::string("/clip_error")})
            r.stored_bytes += file.dataset_info(g + d).stored_bytes;
        for (std::size_t i = 0; i < n; ++i) {
            PackedClipRecord c;
            c.id = ids[i];
            if (frames.data[i] < 1)
                throw StoreError(
                    file.name(), g + "/clip_frames",
                    "expected >= 1, found " + std::to_string(frames.data[i]) + " at element " + std::to_string(i));
            if (payload.data[i] < 0)
                throw StoreError(
                    file.name(), g + "/clip_payload_bytes",
                    "expected >= 0, found " + std::to_string(payload.data[i]) + " at element " + std::to_string(i));
            c.frames = static_cast<std::size_t>(frames.data[i]);
            c.payload_bytes = static_cast<std::uint64_t>(payload.data[i]);
            c.max_cm = errors.data[3 * i];
            c.p99_cm = errors.data[3 * i + 1];
            c.rmse_cm = errors.data[3 * i + 2];
            for (double x : {c.max_cm, c.p99_cm, c.rmse_cm})
                if (!std::isfinite(x) || x < 0.0)
                    throw StoreError(
                        file.name(), g + "/clip_error",
                        "expected finite values >= 0, found " + std::to_string(x) + " in row " + std::to_string(i));
            r.clips.push_back(std::move(c));
        }
        t.groups.push_back(std::move(r));
    }
    // g0, g1, ..., g10 in the order they were written.
    std::sort(t.groups.begin(), t.groups.end(), [](const PackedGroupRecord& a, const PackedGroupRecord& b) {
        return a.name.size() != b.name.size() ? a.name.size() < b.name.size() : a.name < b.name;
    });
    return t;
}

std::vector<std::uint8_t> read_packed_bytes(const h5::File& file, const std::string& group) {
    return file.read_array<std::uint8_t>(packed_group_path(group) + "/bytes", 1).data;
}

}  // namespace mocapdb::store
