#include "mocapdb_json/report_json.hpp"

#include "json_fields.hpp"
#include "mocapdb_json/step_json.hpp"

namespace mocapdb::json {
namespace {

using fields::optional_number;
using fields::strings;

void report_figures(JsonWriter& j, const eval::PackedFigures& f) {
    j.key("clips").value(f.clips);
    j.key("frames").value(f.frames);
    j.key("bytes").value(static_cast<std::size_t>(f.bytes));
    j.key("float32_bytes").value(static_cast<std::size_t>(f.float32_bytes));
    j.key("ratio_float32").value(f.ratio_float32());
    j.key("motion_seconds").value(f.motion_seconds);
    j.key("bytes_per_second").value(f.bytes_per_second());
    j.key("bits_per_joint_frame").value(f.bits_per_joint_frame());
    j.key("max_cm").value(f.max_cm);
    j.key("p99_cm").value(f.p99_cm);
    j.key("rmse_cm").value(f.rmse_cm);
    j.key("encode_seconds").value(f.encode_seconds);
    j.key("stream_mb_per_second").value(f.stream_mb_per_second());
    j.key("raw_windows").value(f.raw_windows);
    j.key("pack_attempts").value(f.attempts);
    write_parts(j, f.parts);
}

}  // namespace

void write_collection_report(JsonWriter& j, const std::string& db, const eval::CollectionReport& r,
                             const eval::CollectionAcl& ref) {
    j.begin_object();
    j.key("file").value(db);
    j.key("clips").value(r.clips);
    j.key("frames").value(r.frames);
    j.key("groups").value(r.groups);
    j.key("motion_seconds").value(r.motion_seconds);
    j.key("float32_bytes").value(static_cast<std::size_t>(r.float32_bytes));
    j.key("threads").value(r.threads);
    j.key("random_poses").value(r.random_poses);
    j.key("targets").begin_array();
    for (std::size_t t = 0; t < r.targets.size(); ++t) {
        const eval::TargetFigures& tf = r.targets[t];
        j.begin_object();
        j.key("max_error_cm").value(tf.max_error_cm);
        report_figures(j, tf.total);
        j.key("decode_pose_us").value(tf.pose_microseconds);
        j.key("resident_bytes").value(static_cast<std::size_t>(tf.resident_bytes));
        j.key("poses_timed").value(tf.poses_timed);
        j.key("indexed_local_pose_us").value(tf.indexed_pose_microseconds);
        j.key("index_bytes").value(static_cast<std::size_t>(tf.index_bytes));
        j.key("acl");
        if (ref.given && ref.unusable.empty()) {
            const eval::AclComparison& c = ref.per_target[t];
            j.begin_object();
            optional_number(j, "bytes_at_max", c.bytes_at_max);
            optional_number(j, "smaller_at_max", c.smaller_at_max);
            optional_number(j, "bytes_at_rmse", c.bytes_at_rmse);
            optional_number(j, "smaller_at_rmse", c.smaller_at_rmse);
            j.key("max_lower_bound").value(c.max_lower_bound);
            j.key("rmse_lower_bound").value(c.rmse_lower_bound);
            j.end_object();
        } else {
            j.null();
        }
        j.key("group_figures").begin_array();
        for (const eval::GroupFigures& g : tf.groups) {
            j.begin_object();
            j.key("skeleton").value(g.skeleton);
            j.key("first_clip").value(g.first_clip);
            j.key("frame_rate").value(g.frame_rate);
            report_figures(j, g.figures);
            j.end_object();
        }
        j.end_array();
        j.end_object();
    }
    j.end_array();
    const eval::LosslessFigures& l = r.lossless;
    j.key("lossless").begin_object();
    j.key("bytes").value(static_cast<std::size_t>(l.bytes));
    j.key("channel_bytes").value(static_cast<std::size_t>(l.channel_bytes));
    j.key("float32_bytes").value(static_cast<std::size_t>(l.float32_bytes));
    j.key("ratio_float32").value(l.ratio_float32());
    j.key("gzip9_available").value(l.gzip_available);
    j.key("gzip9_bytes");
    if (l.gzip_available) j.value(static_cast<std::size_t>(l.gzip_bytes));
    else j.null();
    j.key("gzip9_ratio_float32");
    if (l.gzip_available) j.value(l.gzip_ratio_float32());
    else j.null();
    j.key("source_text_bytes");
    if (l.gzip_available) j.value(static_cast<std::size_t>(l.source_text_bytes));
    else j.null();
    j.key("gzip9_unavailable_reason").value(l.gzip_reason);
    j.key("sources_found").value(l.sources_found);
    j.key("sources_missing").value(l.sources_missing);
    j.key("sources_changed").value(l.sources_changed);
    j.end_object();
    j.key("reference");
    if (!ref.given) {
        j.null();
    } else {
        j.begin_object();
        j.key("files").begin_array();
        for (const auto& f : ref.table.files) j.value(f.string());
        j.end_array();
        j.key("comparable").value(ref.unusable.empty());
        j.key("reason").value(ref.unusable);
        strings(j, "clips_missing", ref.acl.missing);
        j.key("settings").begin_array();
        for (const eval::AclSetting& s : ref.acl.settings) {
            j.begin_object();
            j.key("precision_cm").value(s.precision_cm);
            j.key("bytes").value(static_cast<std::size_t>(s.bytes));
            j.key("max_cm").value(s.max_cm);
            j.key("rmse_cm").value(s.rmse_cm);
            j.key("clips").value(s.clips);
            j.end_object();
        }
        j.end_array();
        j.end_object();
    }
    j.end_object();
}

void write_rate_report(JsonWriter& j, const std::string& set, const workflow::RateOutcome& r) {
    j.begin_object();
    j.key("set").value(set);
    j.key("dims").begin_array();
    for (auto d : r.report.dims) j.value(static_cast<long long>(d));
    j.end_array();
    j.key("raw_bytes").value(static_cast<long long>(r.report.raw_bytes));
    j.key("raw_clip_bytes").value(static_cast<long long>(r.clip_bytes));
    j.key("side_bytes").value(static_cast<long long>(r.report.side_bytes));
    j.key("seconds_of_motion").value(r.seconds);
    write_rate_rows(j, r);
    j.end_object();
}

void write_rate_rows(JsonWriter& j, const workflow::RateOutcome& o) {
    const compression::RateReport& r = o.report;
    j.key("rows").begin_array();
    for (const compression::RateRow& row : r.rows) {
        j.begin_object();
        j.key("method").value(row.method);
        j.key("target_cm").value(row.target_cm);
        j.key("target_met").value(row.target_met);
        j.key("ranks").begin_array();
        for (long long k : row.ranks) j.value(k);
        j.end_array();
        j.key("setting").value(row.setting);
        j.key("bytes").value(static_cast<long long>(row.bytes));
        j.key("ratio").value(row.ratio);
        j.key("ratio_clips").value(static_cast<double>(o.clip_bytes) / static_cast<double>(row.bytes));
        j.key("bytes_per_second").value(static_cast<double>(row.bytes) / o.seconds);
        j.key("bits_per_joint_frame")
            .value(8.0 * static_cast<double>(row.bytes) /
                   (static_cast<double>(o.joints) * static_cast<double>(r.dims[1] * r.dims[2])));
        write_joint_error(j, row.stats);
        j.key("precompute_s").value(row.precompute_s);
        j.key("us_per_pose").value(row.us_per_pose);
        j.key("access").value(row.access);
        j.end_object();
    }
    j.end_array();
}

}  // namespace mocapdb::json
