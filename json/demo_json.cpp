#include "mocapdb_json/demo_json.hpp"

#include "json_fields.hpp"
#include "mocapdb_json/report_json.hpp"
#include "mocapdb_json/step_json.hpp"

namespace mocapdb::json {
namespace {

void write_import_stage(JsonWriter& j, const workflow::ImportOutcome& imported) {
    j.key("import").begin_object();
    j.key("files").value(imported.summary.files).key("clips").value(imported.summary.added);
    j.key("frames").value(imported.summary.frames).key("seconds_of_motion").value(imported.summary.seconds);
    j.key("bytes_read").value(static_cast<long long>(imported.summary.bytes_read));
    j.key("seconds").value(imported.seconds).end_object();
}

void write_set_stage(JsonWriter& j, const std::string& set_name, const MotionSet& set) {
    const auto& names = set.parameter_names;
    const auto& units = set.parameter_units;
    j.key("set").begin_object();
    j.key("name").value(set_name).key("parameter_source").value(set.parameter_source);
    j.key("samples").value(set.samples.size());
    j.key("parameters").begin_array();
    for (std::size_t p = 0; p < names.size(); ++p)
        j.begin_object().key("name").value(names[p]).key("unit").value(units[p]).end_object();
    j.end_array();
    j.key("values").begin_array();
    for (Eigen::Index n = 0; n < set.parameters.rows(); ++n) {
        j.begin_array();
        for (Eigen::Index k = 0; k < set.parameters.cols(); ++k) j.value(set.parameters(n, k));
        j.end_array();
    }
    j.end_array().end_object();
}

void write_align_stage(JsonWriter& j, const workflow::AlignOutcome& aligned) {
    j.key("align").begin_object();
    j.key("method").value(aligned.aligned.method).key("frames").value(static_cast<long long>(aligned.aligned.frames()));
    j.key("dofs").value(static_cast<long long>(aligned.aligned.dofs()));
    j.key("reference").value(aligned.labels[aligned.aligned.reference]);
    j.key("mean_distance_cm").value(aligned.distance).key("seconds").value(aligned.seconds).end_object();
}

void write_rate_stage(JsonWriter& j, const workflow::RateOutcome& rate, double seconds) {
    j.key("rate_distortion").begin_object();
    j.key("raw_bytes").value(static_cast<long long>(rate.report.raw_bytes));
    j.key("side_bytes").value(static_cast<long long>(rate.report.side_bytes));
    j.key("seconds_of_motion").value(rate.seconds);
    write_rate_rows(j, rate);
    j.key("seconds").value(seconds).end_object();
}

void write_synthesis_stage(JsonWriter& j, const DemoSyntheses& s) {
    const kriging::VariogramModel& vg = s.variogram;
    j.key("synthesis").begin_object();
    j.key("model").value(s.model).key("precompute_s").value(s.precompute_s);
    j.key("load_s").value(s.load_s).key("measured_with").value(s.measured_with);
    j.key("variogram").begin_object().key("p").value(vg.paper_p()).key("nugget").value(vg.nugget);
    j.key("sill").value(vg.sill).key("range").value(vg.range).end_object();
    j.key("motions").begin_array();
    for (const DemoSynthesis& m : s.motions) {
        j.begin_object();
        j.key("file").value(m.file).key("where").value(m.where).key("inside").value(m.inside);
        j.key("requested");
        fields::numbers(j, m.outcome.requested);
        if (m.measured.size() == m.outcome.requested.size()) {
            j.key("measured");
            fields::numbers(j, m.measured);
        }
        j.key("reliability").value(m.outcome.reliability);
        j.key("frames").value(m.outcome.clip.frame_count()).key("frame_rate").value(m.outcome.clip.frame_rate);
        j.key("duration_s").value(m.outcome.clip.duration());
        j.key("clamped_increments").value(static_cast<long long>(m.outcome.timing.clamped));
        j.key("seconds").value(m.outcome.seconds);
        j.end_object();
    }
    j.end_array().end_object();
}

void write_map_stage(JsonWriter& j, const DemoMap& m) {
    j.key("reliability_map").begin_object();
    j.key("file").value("reliability.svg");
    j.key("x").value(m.x).key("y").value(m.y);
    j.key("x_range").begin_array().value(m.x_lo).value(m.x_hi).end_array();
    j.key("y_range").begin_array().value(m.y_lo).value(m.y_hi).end_array();
    j.key("cells").value(static_cast<long long>(m.map.rho.size()));
    j.key("min").value(m.map.rho_min).key("mean").value(m.map.rho_mean).key("max").value(m.map.rho_max);
    j.key("fraction_ge_0_85").value(m.map.fraction_trusted).end_object();
}

}  // namespace

void write_demo_report(JsonWriter& j, const DemoReport& r) {
    j.begin_object();
    j.key("mode").value(r.mode);
    j.key("out").value(r.out);
    j.key("database").value(r.database);
    write_import_stage(j, r.imported);
    write_set_stage(j, r.set_name, r.set.set);
    write_align_stage(j, r.aligned);
    j.key("compress");
    write_compression(j, r.set_name, r.compressed);
    write_rate_stage(j, r.rate, r.rate_s);
    write_synthesis_stage(j, r.synthesis);
    if (r.map) write_map_stage(j, *r.map);
    j.key("timings_s").begin_object();
    j.key("generate").value(r.generate_s).key("import").value(r.imported.seconds).key("align").value(r.aligned.seconds);
    j.key("compress").value(r.compressed.total_s).key("rate_distortion").value(r.rate_s);
    j.key("model").value(r.synthesis.load_s);
    j.key("total").value(r.total_s).end_object();
    j.end_object();
}

}  // namespace mocapdb::json
