#pragma once
// Members the documents of json/ share (private to the target): a number or null, a list of strings,
// a vector of numbers, a shape or null, a set's repaired dropouts, a chosen predictor. Each writes into the open JSON
// object or array of `j`.
#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "mocapdb/dataset/motion_set.hpp"
#include "mocapdb/synthesis/edge_warning.hpp"
#include "mocapdb/synthesis/predictor_choice.hpp"
#include "mocapdb_json/json_writer.hpp"

namespace mocapdb::json::fields {

inline void optional_number(JsonWriter& j, const char* key, const std::optional<double>& v) { j.key(key).value(v); }

inline void strings(JsonWriter& j, const char* key, const std::vector<std::string>& v) {
    j.key(key).begin_array();
    for (const std::string& s : v) j.value(s);
    j.end_array();
}

/// An array of the vector's values (no key: after key() or inside an array).
inline void numbers(JsonWriter& j, const Eigen::VectorXd& v) {
    j.begin_array();
    for (Eigen::Index k = 0; k < v.size(); ++k) j.value(v(k));
    j.end_array();
}

/// "key": [the vector's values].
inline void numbers(JsonWriter& j, const char* key, const Eigen::VectorXd& v) { numbers(j.key(key), v); }

/// "key": [a, b, c] when `present`, else "key": null.
inline void shape_or_null(JsonWriter& j, const char* key, bool present, const std::array<std::size_t, 3>& v) {
    j.key(key);
    if (!present) {
        j.null();
        return;
    }
    j.begin_array();
    for (std::size_t e : v) j.value(e);
    j.end_array();
}

/// "repairs": [{clip, joint, begin, end}] (frames [begin, end) of each repaired run).
inline void repairs(JsonWriter& j, const std::vector<RepairedFrames>& runs) {
    j.key("repairs").begin_array();
    for (const RepairedFrames& r : runs) {
        j.begin_object().key("clip").value(r.clip).key("joint").value(r.joint);
        j.key("begin").value(r.begin).key("end").value(r.end).end_object();
    }
    j.end_array();
}

/// A calibrated reliability threshold (synthesis/edge_warning.hpp) as an object (no key: after key()).
inline void edge_warning(JsonWriter& j, const synthesis::EdgeWarning& w) {
    j.begin_object();
    j.key("variance_ratio").value(w.variance_ratio);
    j.key("rho_threshold").value(synthesis::rho_threshold(w));
    j.key("beyond_sd").value(w.beyond_sd);
    j.key("tolerance_share").value(w.tolerance_share);
    j.key("probes").value(static_cast<long long>(w.probes));
    j.key("misses").value(static_cast<long long>(w.misses));
    j.key("detection").value(w.detection);
    j.key("false_alarms").value(w.false_alarms);
    j.key("neighbours").value(static_cast<long long>(w.neighbours));
    j.key("votes").value(static_cast<long long>(w.votes));
    j.end_object();
}

/// {chosen, folds, samples, cv_rms: {name: value}} of a cross-validated predictor (no key: after key()).
inline void predictor_choice(JsonWriter& j, const synthesis::PredictorChoice& c) {
    j.begin_object().key("chosen").value(synthesis::to_string(c.chosen));
    j.key("folds").value(c.folds).key("samples").value(c.samples);
    j.key("members").begin_array();
    for (const synthesis::Predictor p : c.members()) j.value(synthesis::to_string(p));
    j.end_array();
    j.key("cv_rms").begin_object();
    for (const synthesis::PredictorScore& s : c.scores) j.key(synthesis::to_string(s.predictor)).value(s.cv_rms);
    j.end_object();
    j.key("cv_se").begin_object();
    for (const synthesis::PredictorScore& s : c.scores) j.key(synthesis::to_string(s.predictor)).value(s.cv_se);
    j.end_object().end_object();
}

}  // namespace mocapdb::json::fields
