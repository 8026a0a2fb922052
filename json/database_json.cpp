#include "mocapdb_json/database_json.hpp"

#include "json_fields.hpp"
#include "mocapdb/dataset/dropout_repair.hpp"

namespace mocapdb::json {

void write_database_info(JsonWriter& j, const std::string& file, const workflow::DatabaseSummary& d) {
    const std::vector<ClipRecord>& clips = d.clips;
    const std::optional<PackedTierRecord>& tier = d.packed;
    j.begin_object();
    j.key("file").value(file);
    j.key("format").value("mocapdb");
    j.key("format_version").value(d.format_version);
    j.key("file_bytes").value(static_cast<std::size_t>(d.file_bytes));
    j.key("clip_count").value(clips.size());
    j.key("total_frames").value(d.total_frames);
    j.key("total_seconds").value(d.total_seconds);
    j.key("clips").begin_array();
    for (std::size_t i = 0; i < clips.size(); ++i) {
        const ClipRecord& c = clips[i];
        const std::optional<workflow::PackedClipEntry>& packed = d.packed_clips[i];
        j.begin_object();
        j.key("id").value(c.id);
        j.key("frames").value(c.frames);
        j.key("frame_rate").value(c.frame_rate);
        j.key("duration").value(c.duration());
        j.key("channels").value(c.channels);
        j.key("skeleton").value(c.skeleton);
        j.key("source_file").value(c.source.file_name);
        j.key("source_format").value(c.source.format);
        j.key("source_sha256").value(c.source.sha256);
        j.key("source_skeleton_file").value(c.source.skeleton_file);
        j.key("subject").value(c.source.subject);
        j.key("description").value(c.source.description);
        fields::strings(j, "labels", c.source.labels);
        j.key("stored_bytes").value(static_cast<std::size_t>(c.stored_bytes));
        j.key("tiers").begin_array();
        if (c.lossless) j.value("lossless");
        if (packed) j.value("packed");
        j.end_array();
        j.key("lossless_bytes").value(static_cast<std::size_t>(c.stored_bytes));
        if (packed) {
            j.key("packed_group").value(packed->group);
            j.key("packed_payload_bytes").value(static_cast<std::size_t>(packed->clip.payload_bytes));
            j.key("packed_max_cm").value(packed->clip.max_cm);
        } else {
            j.key("packed_group").null();
            j.key("packed_payload_bytes").null();
            j.key("packed_max_cm").null();
        }
        j.end_object();
    }
    j.end_array();
    j.key("skeletons").begin_array();
    for (const workflow::SkeletonSummary& s : d.skeletons) {
        j.begin_object();
        j.key("id").value(s.id);
        j.key("source_file").value(s.source_file);
        j.key("joints").value(s.joints);
        j.key("channels").value(s.channels);
        j.end_object();
    }
    j.end_array();
    j.key("sets").begin_array();
    for (const SetRecord& s : d.sets) {
        j.begin_object();
        j.key("name").value(s.name);
        j.key("samples").value(s.samples);
        fields::strings(j, "parameters", s.parameter_names);
        j.key("parameter_source").value(s.parameter_source);
        j.key("aligned").value(s.aligned);
        j.key("tensor_dims").begin_array().value("sample").value("time").value("dof").end_array();
        fields::shape_or_null(j, "tensor_shape", s.aligned, s.tensor_shape);
        j.key("tensor_stored_bytes").value(static_cast<std::size_t>(s.tensor_stored_bytes));
        j.key("model").value(s.model);
        fields::shape_or_null(j, "model_ranks", s.model, s.model_ranks);
        j.key("model_stored_bytes").value(static_cast<std::size_t>(s.model_stored_bytes));
        j.end_object();
    }
    j.end_array();
    if (tier) {
        j.key("packed").begin_object();
        j.key("max_error_cm").value(tier->max_error_cm);
        j.key("bytes").value(static_cast<std::size_t>(tier->bytes));
        j.key("clips").value(tier->clips);
        j.key("frames").value(tier->frames);
        j.key("max_cm").value(tier->max_cm);
        j.key("p99_cm").value(tier->p99_cm);
        j.key("rmse_cm").value(tier->rmse_cm);
        j.key("groups").begin_array();
        for (const PackedGroupRecord& g : tier->groups) {
            j.begin_object();
            j.key("name").value(g.name);
            j.key("skeleton").value(g.skeleton);
            j.key("frame_rate").value(g.frame_rate);
            j.key("clips").value(g.clips.size());
            j.key("frames").value(g.frames);
            j.key("bytes").value(static_cast<std::size_t>(g.bytes));
            j.key("stored_bytes").value(static_cast<std::size_t>(g.stored_bytes));
            j.key("max_cm").value(g.max_cm);
            j.end_object();
        }
        j.end_array();
        j.end_object();
    } else {
        j.key("packed").null();
    }
    j.end_object();
}

void write_set_list(JsonWriter& j, const std::vector<SetRecord>& sets) {
    j.begin_array();
    for (const SetRecord& s : sets) {
        j.begin_object().key("name").value(s.name).key("samples").value(s.samples);
        j.key("parameters").begin_array();
        for (const auto& p : s.parameter_names) j.value(p);
        j.end_array().key("aligned").value(s.aligned).key("model").value(s.model);
        fields::shape_or_null(j, "model_ranks", s.model, s.model_ranks);
        j.end_object();
    }
    j.end_array();
}

void write_set_show(JsonWriter& j, const MotionSet& set, const std::vector<std::string>& labels,
                    const std::optional<AlignedSet>& aligned,
                    const std::optional<synthesis::PredictorChoice>& predictor,
                    const std::optional<synthesis::EdgeWarning>& edge_warning) {
    j.begin_object();
    j.key("name").value(set.name);
    j.key("parameter_source").value(set.parameter_source);
    j.key("parameters").begin_array();
    for (std::size_t p = 0; p < set.parameter_names.size(); ++p) {
        j.begin_object().key("name").value(set.parameter_names[p]).key("unit").value(set.parameter_units[p]);
        if (set.parameter_periods.size() != 0)
            j.key("period").value(set.parameter_periods(static_cast<Eigen::Index>(p)));
        if (is_categorical(set, p)) fields::strings(j, "levels", set.parameter_levels[p]);  // values: level indices
        j.end_object();
    }
    j.end_array();
    j.key("aligned").value(aligned.has_value());
    if (aligned) {
        j.key("method").value(aligned->method);
        j.key("frames").value(static_cast<long long>(aligned->frames()));
        j.key("dofs").value(static_cast<long long>(aligned->dofs()));
        j.key("reference").value(aligned->reference);
    }
    j.key("predictor");
    if (predictor) fields::predictor_choice(j, *predictor);
    else j.null();
    j.key("reliability_warning");
    if (edge_warning) fields::edge_warning(j, *edge_warning);
    else j.null();
    j.key("samples").begin_array();
    for (std::size_t i = 0; i < set.samples.size(); ++i) {
        const SampleRef& s = set.samples[i];
        j.begin_object().key("label").value(labels[i]).key("clip").value(s.clip);
        j.key("begin").value(s.begin).key("end").value(s.end);
        j.key("values").begin_array();
        for (Eigen::Index p = 0; p < set.parameters.cols(); ++p)
            j.value(set.parameters(static_cast<Eigen::Index>(i), p));
        j.end_array().end_object();
    }
    j.end_array();
    j.key("dropouts_checked").value(set.dropouts_checked);
    fields::repairs(j, set.repairs);
    j.end_object();
}

}  // namespace mocapdb::json
