#include "mocapdb_json/step_json.hpp"

#include <optional>

#include "json_fields.hpp"
#include "mocapdb/tensor/tucker.hpp"
#include "mocapdb_json/set_evaluation_json.hpp"

namespace mocapdb::json {
namespace {

using fields::optional_number;
using fields::strings;

const char* segmentation_name(Segmentation s) {
    switch (s) {
        case Segmentation::GaitCycles: return "gait_cycles";
        case Segmentation::Windows: return "windows";
        case Segmentation::Flights: return "flights";
        case Segmentation::Auto: return "auto";
        case Segmentation::WholeClips: break;
    }
    return "whole_clips";
}

void packed_figures(JsonWriter& j, std::uint64_t bytes, std::uint64_t float32, double ratio_float32, std::size_t clips,
                    std::size_t frames, double max_cm, double p99_cm, double rmse_cm) {
    j.key("bytes").value(static_cast<std::size_t>(bytes));
    j.key("float32_bytes").value(static_cast<std::size_t>(float32));
    j.key("ratio_float32").value(ratio_float32);
    j.key("clips").value(clips);
    j.key("frames").value(frames);
    j.key("max_cm").value(max_cm);
    j.key("p99_cm").value(p99_cm);
    j.key("rmse_cm").value(rmse_cm);
}

}  // namespace

void write_parts(JsonWriter& j, const packing::ByteParts& parts) {
    j.key("parts").begin_object();
    for (const packing::BytePart& p : parts) j.key(p.name).value(static_cast<std::size_t>(p.bytes));
    j.end_object();
}

void write_joint_error(JsonWriter& j, const compression::JointErrorStats& e) {
    j.key("dof_rmse").value(e.dof_rmse);
    j.key("rmse_cm").value(e.rmse_cm);
    j.key("mean_cm").value(e.mean_cm);
    j.key("max_cm").value(e.max_cm);
    j.key("p99_cm").value(e.p99_cm);
    j.key("worst").begin_object();
    j.key("sample").value(static_cast<long long>(e.worst.sample));
    j.key("frame").value(static_cast<long long>(e.worst.frame));
    j.key("joint").value(e.worst.joint);
    j.end_object();
}

void write_import(JsonWriter& j, const std::string& db, const workflow::ImportOutcome& o) {
    const workflow::ImportSummary& s = o.summary;
    j.begin_object();
    j.key("file").value(db);
    j.key("files").value(s.files);
    j.key("added").value(s.added);
    j.key("skipped").value(s.skipped);
    j.key("failed").value(s.failed);
    j.key("frames").value(s.frames);
    j.key("seconds_of_motion").value(s.seconds);
    j.key("bytes_read").value(static_cast<std::size_t>(s.bytes_read));
    j.key("clips_in_db").value(o.clips_in_db);
    j.key("file_bytes").value(static_cast<std::size_t>(o.file_bytes));
    j.key("seconds").value(o.seconds);
    std::vector<std::string> errors, warnings;
    for (const workflow::ImportMessage& m : o.messages)
        (m.kind == workflow::ImportMessage::Kind::Error ? errors : warnings).push_back(m.text);
    strings(j, "errors", errors);
    strings(j, "warnings", warnings);
    strings(j, "not_added", o.not_added);
    j.end_object();
}

void write_set(JsonWriter& j, const workflow::SetOutcome& o) {
    const MotionSet& set = o.set;
    j.begin_object();
    j.key("set").value(set.name);
    j.key("samples").value(set.samples.size());
    j.key("clips").value(o.clips);
    strings(j, "skipped", o.skipped);
    j.key("segmentation").value(segmentation_name(o.segmentation));
    strings(j, "parameter_names", set.parameter_names);
    j.key("parameters").begin_array();
    for (Eigen::Index n = 0; n < set.parameters.rows(); ++n) {
        j.begin_array();
        for (Eigen::Index k = 0; k < set.parameters.cols(); ++k) j.value(set.parameters(n, k));
        j.end_array();
    }
    j.end_array();
    j.key("repaired_runs").value(set.repairs.size());
    std::vector<std::string> labels;  // twins: groups of samples showing the same frames
    for (const SampleRef& s : set.samples) labels.push_back(sample_label(s, 0));
    write_twins(j, o.twins, labels);
    j.end_object();
}

void write_alignment(JsonWriter& j, const std::string& set, const workflow::AlignOutcome& o) {
    j.begin_object();
    j.key("set").value(set);
    j.key("samples").value(static_cast<long long>(o.aligned.samples()));
    j.key("frames").value(static_cast<long long>(o.aligned.frames()));
    j.key("dofs").value(static_cast<long long>(o.aligned.dofs()));
    j.key("reference").value(static_cast<long long>(o.aligned.reference));
    j.key("mean_distance_cm").value(o.distance);
    j.key("seconds").value(o.seconds);
    strings(j, "labels", o.labels);
    optional_number(j, "phase_min", o.phase ? std::optional<double>(o.phase->min) : std::nullopt);
    optional_number(j, "phase_mean", o.phase ? std::optional<double>(o.phase->mean) : std::nullopt);
    j.end_object();
}

void write_compression(JsonWriter& j, const std::string& set, const workflow::CompressOutcome& o) {
    const tensor::TuckerModel& t = o.model.tucker;
    j.begin_object();
    j.key("set").value(set);
    j.key("criterion").value(o.criterion);
    j.key("target_met").value(o.target_met);
    j.key("method").value(tensor::to_string(t.method));
    j.key("status").value(tensor::to_string(t.status));
    j.key("iterations").value(t.iterations);
    j.key("dims").begin_array();
    for (Eigen::Index d : o.dims) j.value(static_cast<long long>(d));
    j.end_array();
    j.key("ranks").begin_array();
    for (Eigen::Index r : t.ranks) j.value(static_cast<long long>(r));
    j.end_array();
    j.key("raw_bytes").value(static_cast<long long>(o.raw_bytes));
    j.key("bytes").value(static_cast<long long>(o.bytes));
    j.key("ratio").value(o.ratio());
    j.key("file_bytes").value(static_cast<long long>(o.stored_bytes));
    j.key("relative_error").value(1.0 - t.fit);
    j.key("relative_error_bound").value(t.error_bound / t.data_norm);
    write_joint_error(j, o.stats);
    j.key("load_s").value(o.load_s);
    j.key("bases_s").value(o.bases_s);
    j.key("search_s").value(o.search_s);
    j.key("precompute_s").value(o.fit_s);
    j.key("kernel_s").value(o.kernel_s);
    j.key("kernel_stored").value(o.kernel_stored);
    j.key("kernel_variogram");
    if (o.kernel_stored) j.value(o.kernel_variogram);
    else j.null();
    j.key("kernel_status");
    if (o.kernel_stored) j.value(kriging::to_string(o.kernel_status));
    else j.null();
    j.key("kernel_fit_samples");
    if (o.kernel_stored) j.value(static_cast<long long>(o.kernel_fit_samples));
    else j.null();
    j.key("predictor");
    if (o.kernel_predictor) fields::predictor_choice(j, *o.kernel_predictor);
    else j.null();
    if (o.kernel_edge_warning) {  // absent without a calibration (the demo report holds no nulls)
        j.key("reliability_warning");
        fields::edge_warning(j, *o.kernel_edge_warning);
    }
    j.key("us_per_pose").value(o.us_per_pose);
    j.key("store_s").value(o.store_s);
    j.key("total_s").value(o.total_s);
    j.end_object();
}

void write_pack(JsonWriter& j, const std::string& db, const workflow::PackDatabaseOutcome& o) {
    const PackedTierRecord& t = o.tier;
    j.begin_object();
    j.key("file").value(db);
    j.key("max_error_cm").value(t.max_error_cm);
    packed_figures(j, t.bytes, o.float32_bytes, o.ratio_float32(), t.clips, t.frames, t.max_cm, t.p99_cm, t.rmse_cm);
    j.key("motion_seconds").value(o.motion_seconds);
    j.key("bytes_per_second").value(o.bytes_per_second());
    j.key("replaced").value(o.replaced);
    j.key("dropped_lossless_clips").value(o.dropped_lossless);
    j.key("file_bytes").value(static_cast<std::size_t>(o.file_bytes));
    j.key("seconds").value(o.seconds);
    write_parts(j, o.parts);
    j.key("budget");
    if (o.budget) {
        j.begin_object();
        j.key("max_bytes").value(static_cast<std::size_t>(o.budget->max_bytes));
        j.key("max_error_cm").value(t.max_error_cm);
        j.key("tried").begin_array();
        for (const workflow::PackDatabaseOutcome::Budget::Try& e : o.budget->tried) {
            j.begin_object();
            j.key("max_error_cm").value(e.max_error_cm);
            j.key("bytes");
            if (e.bytes > 0 || e.fits) j.value(static_cast<std::size_t>(e.bytes));
            else j.null();
            j.key("fits").value(e.fits);
            j.end_object();
        }
        j.end_array();
        j.end_object();
    } else {
        j.null();
    }
    j.key("groups").begin_array();
    for (std::size_t g = 0; g < t.groups.size(); ++g) {
        const PackedGroupRecord& r = t.groups[g];
        j.begin_object();
        j.key("name").value(r.name);
        j.key("path").value("/packed/" + r.name);
        j.key("skeleton").value(r.skeleton);
        j.key("frame_rate").value(r.frame_rate);
        packed_figures(j, r.bytes, o.group_float32_bytes.at(g), o.group_ratio_float32(g), r.clips.size(), r.frames,
                       r.max_cm, r.p99_cm, r.rmse_cm);
        j.key("seconds").value(o.group_seconds.at(g));
        j.key("format").value(o.group_formats.at(g) == packing::PackFormat::Runtime ? "runtime" : "archive");
        j.key("window").value(o.group_windows.at(g));
        write_parts(j, o.group_parts.at(g));
        j.end_object();
    }
    j.end_array();
    j.end_object();
}

void write_dropped_lossless(JsonWriter& j, const std::string& db, std::size_t dropped) {
    j.begin_object();
    j.key("file").value(db);
    j.key("dropped_lossless_clips").value(dropped);
    j.end_object();
}

}  // namespace mocapdb::json
