#include "mocapdb_json/view_json.hpp"

#include <algorithm>

#include "json_fields.hpp"

namespace mocapdb::json {
namespace {

using fields::numbers;

void rig(JsonWriter& j, const workflow::RigView& r) {
    j.key("joints").begin_array();
    for (std::size_t k = 0; k < r.names.size(); ++k)
        j.begin_object()
            .key("name")
            .value(r.names[k])
            .key("parent")
            .value(r.parents[k])
            .key("end_site")
            .value(static_cast<bool>(r.end_sites[k]))
            .end_object();
    j.end_array();
}

void frames(JsonWriter& j, const workflow::ClipPositions& p) {
    j.key("frame_rate").value(p.frame_rate);
    j.key("begin").value(p.begin);
    j.key("frames").value(p.frames);
    rig(j, p.rig);
}

}  // namespace

void write_clip_list(JsonWriter& j, const std::string& db, const std::vector<ClipRecord>& clips,
                     const std::optional<PackedTierRecord>& packed) {
    j.begin_object();
    j.key("database").value(db);
    j.key("packed_max_error_cm");
    if (packed) j.value(packed->max_error_cm);
    else j.null();
    j.key("clips").begin_array();
    for (const ClipRecord& c : clips) {
        j.begin_object();
        j.key("id").value(c.id).key("skeleton").value(c.skeleton).key("format").value(c.source.format);
        j.key("frames").value(c.frames).key("frame_rate").value(c.frame_rate).key("duration_s").value(c.duration());
        j.end_object();
    }
    j.end_array().end_object();
}

void write_clip_positions(JsonWriter& j, const std::string& clip, const workflow::ClipPositions& p) {
    j.begin_object().key("clip").value(clip);
    frames(j, p);
    j.end_object();
}

void write_packed_comparison(JsonWriter& j, const std::string& clip, const workflow::PackedComparison& c) {
    j.begin_object().key("clip").value(clip);
    frames(j, c.source);
    j.key("tier_max_error_cm").value(c.tier_max_error_cm);
    j.key("max_cm").value(c.max_cm).key("rmse_cm").value(c.rmse_cm);
    j.key("worst_frame").value(c.worst_frame).key("worst_joint").value(c.worst_joint);
    j.end_object();
}

void write_set_views(JsonWriter& j, const std::vector<SetView>& sets) {
    j.begin_object().key("sets").begin_array();
    for (const SetView& v : sets) {
        const MotionSet& s = v.set;
        j.begin_object().key("name").value(s.name).key("samples").value(s.samples.size());
        j.key("aligned").value(v.aligned).key("model").value(v.model ? "compressed" : "naive");
        j.key("parameters").begin_array();
        for (std::size_t p = 0; p < s.parameter_names.size(); ++p) {
            const auto col = s.parameters.col(static_cast<Eigen::Index>(p));
            j.begin_object().key("name").value(s.parameter_names[p]).key("unit").value(s.parameter_units[p]);
            j.key("min").value(col.minCoeff()).key("max").value(col.maxCoeff()).end_object();
        }
        j.end_array();
        j.key("values").begin_array();
        for (Eigen::Index n = 0; n < s.parameters.rows(); ++n) {
            j.begin_array();
            for (Eigen::Index k = 0; k < s.parameters.cols(); ++k) j.value(s.parameters(n, k));
            j.end_array();
        }
        j.end_array();
        j.key("labels").begin_array();
        for (const SampleRef& r : s.samples) j.value(r.clip);
        j.end_array().end_object();
    }
    j.end_array().end_object();
}

void write_synthesis_view(JsonWriter& j, const SynthesisView& s, const workflow::ClipPositions& p) {
    j.begin_object().key("set").value(s.set).key("model").value(s.model);
    j.key("parameters").begin_array();
    for (std::size_t k = 0; k < s.names.size(); ++k) {
        const Eigen::Index i = static_cast<Eigen::Index>(k);
        j.begin_object().key("name").value(s.names[k]).key("unit").value(s.units[k]);
        j.key("requested").value(s.outcome.requested(i)).key("measured");
        if (s.outcome.measured.size() == s.outcome.requested.size()) j.value(s.outcome.measured(i));
        else j.null();
        j.end_object();
    }
    j.end_array();
    j.key("reliability").value(s.outcome.reliability).key("inside").value(s.inside);
    j.key("warnings").begin_object();
    j.key("low_reliability").value(s.warnings.low_reliability).key("kernel_fit").value(s.warnings.kernel_fit);
    j.key("reliability_threshold").value(synthesis::rho_threshold(s.warnings.threshold));
    j.key("calibrated").value(s.warnings.calibrated).key("flagged").value(s.warnings.flagged());
    j.key("missed").begin_array();
    for (const workflow::ParameterMiss& m : s.warnings.misses) j.value(static_cast<long long>(m.parameter));
    j.end_array();
    j.key("regularized").value(s.warnings.regularized).key("jittered").value(s.warnings.jittered).end_object();
    j.key("duration_s").value(s.outcome.clip.duration()).key("seconds").value(s.outcome.seconds);
    frames(j, p);
    j.end_object();
}

void write_reliability_slice(JsonWriter& j, const std::string& set, const std::vector<std::string>& names,
                             const workflow::SliceAxis& x, const workflow::SliceAxis& y,
                             const workflow::ReliabilityMap& map) {
    j.begin_object().key("set").value(set);
    for (const auto* a : {&x, &y}) {
        j.key(a == &x ? "x" : "y").begin_object();
        j.key("parameter").value(names[static_cast<std::size_t>(a->axis)]);
        j.key("lo").value(a->lo).key("hi").value(a->hi).key("count").value(static_cast<long long>(a->count));
        j.end_object();
    }
    numbers(j, "rho", map.rho);
    j.key("fraction_trusted").value(map.fraction_trusted).end_object();
}

void write_error(JsonWriter& j, const std::string& message) {
    j.begin_object().key("error").value(message).end_object();
}

}  // namespace mocapdb::json
