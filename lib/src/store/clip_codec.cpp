#include "clip_codec.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <tuple>

#include "layout.hpp"
#include "mocapdb/packing/lossless_channels.hpp"
#include "mocapdb/store/store_error.hpp"

namespace mocapdb::store {
namespace {

const char* const kPackedCodec = "decimal-zstd-1";

std::array<std::uint64_t, 4> section_sizes(const h5::File& file, const std::string& path) {
    const std::vector<std::int64_t> v = file.read_ints_attribute(path, "section_bytes");
    std::array<std::uint64_t, 4> out{};
    if (v.size() != out.size())
        throw StoreError(file.name(), path,
                         "attribute 'section_bytes': expected 4 values, found " + std::to_string(v.size()));
    for (std::size_t i = 0; i < out.size(); ++i) {
        if (v[i] < 0) throw StoreError(file.name(), path, "attribute 'section_bytes': expected values >= 0");
        out[i] = static_cast<std::uint64_t>(v[i]);
    }
    return out;
}

// The packed form's frames and channels (attributes frames and channel_scale), checked.
std::pair<std::size_t, std::size_t> packed_shape(const h5::File& file, const std::string& path) {
    const std::int64_t frames = file.read_int_attribute(path, "frames");
    if (frames < 1)
        throw StoreError(file.name(), path, "attribute 'frames': expected >= 1, found " + std::to_string(frames));
    const h5::AttributeInfo scale = file.attribute_info(path, "channel_scale");
    if (scale.shape.size() != 1)
        throw StoreError(file.name(), path,
                         "attribute 'channel_scale': expected one dimension, found " + h5::shape_text(scale.shape));
    return {static_cast<std::size_t>(frames), static_cast<std::size_t>(scale.shape[0])};
}

}  // namespace

void write_clip(h5::File& file, const std::string& id, const Clip& clip, const std::string& skeleton_id,
                const ClipSource& source) {
    const std::string g = clip_path(id);
    file.create_group(g, "clip");
    file.write_string_attribute(g, "skeleton", skeleton_id);
    file.write_double_attribute(g, "frame_rate", clip.frame_rate);
    file.write_string_attribute(g, "source_file", source.file_name);
    file.write_string_attribute(g, "source_format", source.format);
    file.write_string_attribute(g, "source_sha256", source.sha256);
    if (!source.skeleton_file.empty()) file.write_string_attribute(g, "source_skeleton_file", source.skeleton_file);
    if (!source.subject.empty()) file.write_string_attribute(g, "subject", source.subject);
    if (!source.description.empty()) file.write_string_attribute(g, "description", source.description);
    if (!source.labels.empty()) file.write_strings_attribute(g, "labels", source.labels);
    // Exact to the bit (packing::pack_channels verifies its own output), in a few bytes per value.
    const packing::PackedChannels p = packing::pack_channels(clip.channels, packing::reader_scales(*clip.skeleton));
    const std::string d = g + "/" + kPackedChannels;
    file.write_compressed_bytes(d, p.bytes, "byte", "zstd");
    file.write_string_attribute(d, "codec", kPackedCodec);
    file.write_int_attribute(d, "frames", static_cast<std::int64_t>(p.frames));
    file.write_doubles_attribute(d, "channel_scale", p.scale);
    file.write_ints_attribute(d, "channel_decimals", p.decimals);
    file.write_ints_attribute(d, "channel_predictor", p.predictor);
    file.write_ints_attribute(d, "section_bytes", {p.section_bytes.begin(), p.section_bytes.end()});
}

bool lossless_dropped(const h5::File& file, const std::string& id) {
    const std::string g = clip_path(id);
    return file.has_attribute(g, kLosslessAttribute) &&
           file.read_string_attribute(g, kLosslessAttribute) == kLosslessDroppedValue;
}

std::string clip_channels_path(const h5::File& file, const std::string& id) {
    const std::string plain = clip_path(id) + "/channels";
    const std::string packed = clip_path(id) + "/" + kPackedChannels;
    const bool has_plain = file.type_of(plain) != h5::ObjectType::None;
    const bool has_packed = file.type_of(packed) != h5::ObjectType::None;
    if (!has_plain && !has_packed && lossless_dropped(file, id))
        throw StoreError(file.name(), clip_path(id),
                         "the clip's lossless channels were dropped when the database was packed; it is stored in "
                         "the packed tier only");
    if (has_plain == has_packed)
        throw StoreError(file.name(), clip_path(id),
                         "expected one of the datasets '" + kPackedChannels + "' and 'channels', found " +
                             (has_plain ? "both" : "neither"));
    return has_packed ? packed : plain;
}

void drop_lossless_channels(h5::File& file, const std::string& id) {
    const ClipRecord r = read_clip_record(file, id);
    if (!r.lossless) throw StoreError(file.name(), clip_path(id), "the clip's lossless channels are already dropped");
    const std::string g = clip_path(id);
    file.unlink(clip_channels_path(file, id));
    file.write_string_attribute(g, kLosslessAttribute, kLosslessDroppedValue);
    file.write_int_attribute(g, "frames", static_cast<std::int64_t>(r.frames));
    file.write_int_attribute(g, "channels", static_cast<std::int64_t>(r.channels));
}

ClipRecord read_clip_record(const h5::File& file, const std::string& id) {
    // One open of the group for its attributes and one listing of its links: this runs for every
    // clip when a database is listed (3 000 clips: a few hundred ms, not seconds).
    const std::string g = clip_path(id);
    if (!file.link_exists(g)) throw StoreError(file.name(), g, "no such clip");
    const h5::Attributes a = file.read_attributes(g);
    if (a.type != h5::ObjectType::Group) throw StoreError(file.name(), g, "no such clip");
    ClipRecord r;
    r.id = id;
    r.skeleton = file.string_attribute(a, "skeleton");
    r.frame_rate = file.double_attribute(a, "frame_rate");
    if (!(r.frame_rate > 0.0) || !std::isfinite(r.frame_rate))
        throw StoreError(file.name(), g,
                         "attribute 'frame_rate': expected a positive number, found " + std::to_string(r.frame_rate));
    r.source.file_name = file.string_attribute(a, "source_file");
    r.source.format = file.string_attribute(a, "source_format");
    r.source.sha256 = file.string_attribute(a, "source_sha256");
    if (a.has("source_skeleton_file")) r.source.skeleton_file = file.string_attribute(a, "source_skeleton_file");
    if (a.has("subject")) r.source.subject = file.string_attribute(a, "subject");
    if (a.has("description")) r.source.description = file.string_attribute(a, "description");
    if (a.has("labels")) r.source.labels = file.strings_attribute(a, "labels");
    const std::vector<std::string> links = file.children(g);
    const auto has_link = [&](const std::string& name) {
        return std::find(links.begin(), links.end(), name) != links.end();
    };
    if (a.has(kLosslessAttribute) && file.string_attribute(a, kLosslessAttribute) == kLosslessDroppedValue) {
        const std::int64_t frames = file.int_attribute(a, "frames");
        const std::int64_t channels = file.int_attribute(a, "channels");
        if (frames < 1 || channels < 1)
            throw StoreError(
                file.name(), g,
                "attributes 'frames' and 'channels' of a clip without lossless channels: expected >= 1, found " +
                    std::to_string(frames) + " and " + std::to_string(channels));
        if (has_link("channels") || has_link(kPackedChannels))
            throw StoreError(file.name(), g, "attribute 'lossless' says \"dropped\" but a channel dataset is present");
        r.frames = static_cast<std::size_t>(frames);
        r.channels = static_cast<std::size_t>(channels);
        r.lossless = false;
        return r;
    }
    const bool has_plain = has_link("channels");
    const bool has_packed = has_link(kPackedChannels);
    if (has_plain == has_packed)
        throw StoreError(file.name(), g,
                         "expected one of the datasets '" + kPackedChannels + "' and 'channels', found " +
                             (has_plain ? "both" : "neither"));
    if (has_packed) {
        const std::string packed = g + "/" + kPackedChannels;
        const h5::DatasetInfo info = file.dataset_info(packed);
        if (info.dtype != "uint8" || info.shape.size() != 1)
            throw StoreError(file.name(), packed,
                             "expected uint8 (byte), found " + info.dtype + " " + h5::shape_text(info.shape));
        const h5::Attributes pa = file.read_attributes(packed);
        const std::int64_t frames = file.int_attribute(pa, "frames");
        if (frames < 1)
            throw StoreError(file.name(), packed, "attribute 'frames': expected >= 1, found " + std::to_string(frames));
        const h5::AttributeInfo* scale = pa.find_info("channel_scale");
        if (scale == nullptr) throw StoreError(file.name(), packed, "missing attribute 'channel_scale'");
        if (scale->shape.size() != 1)
            throw StoreError(
                file.name(), packed,
                "attribute 'channel_scale': expected one dimension, found " + h5::shape_text(scale->shape));
        r.frames = static_cast<std::size_t>(frames);
        r.channels = static_cast<std::size_t>(scale->shape[0]);
        r.stored_bytes = info.stored_bytes;
        return r;
    }
    const h5::DatasetInfo info = file.dataset_info(g + "/channels");
    if (info.dtype != "float64" || info.shape.size() != 2)
        throw StoreError(file.name(), g + "/channels",
                         "expected float64 (frame, channel), found " + info.dtype + " " + h5::shape_text(info.shape));
    r.frames = static_cast<std::size_t>(info.shape[0]);
    r.channels = static_cast<std::size_t>(info.shape[1]);
    r.stored_bytes = info.stored_bytes;
    return r;
}

FrameMatrix read_clip_channels(const h5::File& file, const std::string& id, std::size_t channels) {
    const std::string path = clip_channels_path(file, id);
    if (path == clip_path(id) + "/" + kPackedChannels) return read_packed_channels(file, path, channels);
    auto a = file.read_array<double>(path, 2);
    if (a.shape[1] != channels)
        throw StoreError(file.name(), path,
                         "expected " + std::to_string(channels) +
                             " columns (the channels of its skeleton), found shape " + h5::shape_text(a.shape));
    if (a.shape[0] == 0)
        throw StoreError(file.name(), path, "expected at least one frame, found shape " + h5::shape_text(a.shape));
    return Eigen::Map<const FrameMatrix>(a.data.data(), static_cast<Eigen::Index>(a.shape[0]),
                                         static_cast<Eigen::Index>(a.shape[1]));
}

FrameMatrix read_packed_channels(const h5::File& file, const std::string& path, std::size_t channels) {
    const std::string codec = file.read_string_attribute(path, "codec");
    if (codec != kPackedCodec)
        throw StoreError(file.name(), path,
                         "attribute 'codec': expected \"" + std::string(kPackedCodec) + "\", found \"" + codec + "\"");
    packing::PackedChannels p;
    std::size_t columns = 0;
    std::tie(p.frames, columns) = packed_shape(file, path);
    if (columns != channels)
        throw StoreError(file.name(), path,
                         "expected " + std::to_string(channels) + " channels (the channels of its skeleton), found " +
                             std::to_string(columns));
    p.scale = file.read_doubles_attribute(path, "channel_scale");
    p.decimals = file.read_ints_attribute(path, "channel_decimals");
    p.predictor = file.read_ints_attribute(path, "channel_predictor");
    p.section_bytes = section_sizes(file, path);
    p.bytes = file.read_array<std::uint8_t>(path, 1).data;  // ChecksumError on a corrupted chunk
    try {
        return packing::unpack_channels(p);
    } catch (const StoreError&) {
        throw;
    } catch (const Error& e) {
        throw StoreError(file.name(), path, e.what());
    }
}

}  // namespace mocapdb::store
