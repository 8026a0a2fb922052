#include "clip_codec.hpp"

#include <cmath>

#include "layout.hpp"
#include "mocapdb/store/store_error.hpp"

namespace mocapdb::store {

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
    // FrameMatrix is row-major: its buffer is the C-order (frame, channel) array.
    file.write_array(g + "/channels", clip.channels.data(),
                     {static_cast<std::uint64_t>(clip.channels.rows()), static_cast<std::uint64_t>(clip.channels.cols())},
                     {"frame", "channel"}, "cm|rad");
}

ClipRecord read_clip_record(const h5::File& file, const std::string& id) {
    const std::string g = clip_path(id);
    if (file.type_of(g) != h5::ObjectType::Group) throw StoreError(file.name(), g, "no such clip");
    ClipRecord r;
    r.id = id;
    r.skeleton = file.read_string_attribute(g, "skeleton");
    r.frame_rate = file.read_double_attribute(g, "frame_rate");
    if (!(r.frame_rate > 0.0) || !std::isfinite(r.frame_rate))
        throw StoreError(file.name(), g, "attribute 'frame_rate': expected a positive number, found " +
                                             std::to_string(r.frame_rate));
    r.source.file_name = file.read_string_attribute(g, "source_file");
    r.source.format = file.read_string_attribute(g, "source_format");
    r.source.sha256 = file.read_string_attribute(g, "source_sha256");
    if (file.has_attribute(g, "source_skeleton_file"))
        r.source.skeleton_file = file.read_string_attribute(g, "source_skeleton_file");
    if (file.has_attribute(g, "subject")) r.source.subject = file.read_string_attribute(g, "subject");
    if (file.has_attribute(g, "description")) r.source.description = file.read_string_attribute(g, "description");
    if (file.has_attribute(g, "labels")) r.source.labels = file.read_strings_attribute(g, "labels");
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
    const std::string path = clip_path(id) + "/channels";
    auto a = file.read_array<double>(path, 2);
    if (a.shape[1] != channels)
        throw StoreError(file.name(), path,
                         "expected " + std::to_string(channels) + " columns (the channels of its skeleton), found shape " +
                             h5::shape_text(a.shape));
    if (a.shape[0] == 0) throw StoreError(file.name(), path, "expected at least one frame, found shape " + h5::shape_text(a.shape));
    return Eigen::Map<const FrameMatrix>(a.data.data(), static_cast<Eigen::Index>(a.shape[0]),
                                         static_cast<Eigen::Index>(a.shape[1]));
}

}  // namespace mocapdb::store
