#include "mocapdb_json/clip_json.hpp"

#include "mocapdb/motion/figure_height.hpp"

namespace mocapdb::json {

void write_clip_info(JsonWriter& j, const std::string& file, const Clip& clip) {
    const Skeleton& s = *clip.skeleton;
    j.begin_object();
    j.key("file").value(file);
    j.key("frames").value(clip.frame_count());
    j.key("frame_rate").value(clip.frame_rate);
    j.key("duration").value(clip.duration());
    j.key("channels").value(s.channel_count());
    if (clip.frame_count() > 0) j.key("figure_height_cm").value(figure_height(s, clip.frame(0)));
    else j.key("figure_height_cm").null();  // no frame to measure
    j.key("root").value(s.joint(0).name);
    j.key("motion_root").value(s.joint(s.motion_root()).name);
    j.key("position_channels").value(to_string(s.position_channels()));
    j.key("joints").begin_array();
    for (const Joint& joint : s.joints()) {
        j.begin_object();
        j.key("name").value(joint.name);
        if (joint.parent < 0) {
            j.key("parent").null();
        } else {
            j.key("parent").value(s.joint(static_cast<std::size_t>(joint.parent)).name);
        }
        j.key("end_site").value(joint.end_site);
        j.key("offset_cm").begin_array();
        for (int a = 0; a < 3; ++a) j.value(joint.offset[a]);
        j.end_array();
        j.key("channels").begin_array();
        for (ChannelType c : joint.channels) j.value(to_string(c));
        j.end_array();
        j.end_object();
    }
    j.end_array();
    j.end_object();
}

void write_generated_set(JsonWriter& j, const std::string& folder, const procedural::ParametricSet& set,
                         const std::vector<std::filesystem::path>& paths) {
    j.begin_object().key("kind").value(set.kind).key("folder").value(folder);
    j.key("params_csv").value(paths.back().string());
    j.key("parameters").begin_array();
    for (std::size_t p = 0; p < set.parameter_names.size(); ++p)
        j.begin_object()
            .key("name")
            .value(set.parameter_names[p])
            .key("unit")
            .value(set.parameter_units[p])
            .end_object();
    j.end_array().key("clips").begin_array();
    for (std::size_t i = 0; i < set.clips.size(); ++i) {
        j.begin_object().key("name").value(set.clips[i].name).key("file").value(paths[i].string());
        j.key("frames").value(static_cast<long long>(set.clips[i].frame_count()));
        j.key("frame_rate").value(set.clips[i].frame_rate);
        j.key("values").begin_array();
        for (Eigen::Index p = 0; p < set.parameters.cols(); ++p)
            j.value(set.parameters(static_cast<Eigen::Index>(i), p));
        j.end_array().end_object();
    }
    j.end_array().end_object();
}

}  // namespace mocapdb::json
