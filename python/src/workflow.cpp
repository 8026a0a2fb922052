// The workflow steps (the CLI's import, set create, align, compress, pack, report) as functions on a
// database path. Each commits atomically and returns a dict whose keys are those of the matching
// `mocapdb ... --json` output, so scripts can move between the two.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <array>
#include <map>
#include <optional>

#include "arrays.hpp"
#include "bindings.hpp"
#include "mocapdb/eval/collection_report.hpp"
#include "mocapdb/workflow/pack_collection.hpp"
#include "mocapdb/workflow/clip_import.hpp"
#include "mocapdb/workflow/set_alignment.hpp"
#include "mocapdb/workflow/set_compression.hpp"
#include "mocapdb/workflow/set_creation.hpp"

namespace mocapdb::python {
namespace {

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

py::dict import_files(const std::filesystem::path& db, const std::vector<std::filesystem::path>& inputs,
                      std::optional<std::filesystem::path> asf, std::optional<double> frame_rate, bool strict,
                      bool keep_going, bool force) {
    workflow::ImportOptions options;
    if (asf) options.asf = *asf;
    options.frame_rate = frame_rate;
    options.strict = strict;
    options.keep_going = keep_going;
    workflow::ImportOutcome o;
    {
        py::gil_scoped_release release;
        o = workflow::import_clips(db, inputs, options, force);
    }
    // The readers' warnings reach Python as warnings, as read_clip's do.
    for (const workflow::ImportMessage& m : o.messages)
        if (m.kind == workflow::ImportMessage::Kind::Warning && PyErr_WarnEx(PyExc_UserWarning, m.text.c_str(), 1) != 0)
            throw py::error_already_set();
    py::dict d;
    d["files"] = o.summary.files;
    d["added"] = o.summary.added;
    d["skipped"] = o.summary.skipped;
    d["failed"] = o.summary.failed;
    d["frames"] = o.summary.frames;
    d["seconds_of_motion"] = o.summary.seconds;
    d["clips_in_db"] = o.clips_in_db;
    d["file_bytes"] = o.file_bytes;
    d["seconds"] = o.seconds;
    std::vector<std::string> errors;
    for (const workflow::ImportMessage& m : o.messages)
        if (m.kind == workflow::ImportMessage::Kind::Error) errors.push_back(m.text);
    d["errors"] = errors;
    d["not_added"] = o.not_added;
    return d;
}

py::dict create_set(const std::filesystem::path& db, const std::string& name, const std::vector<std::string>& clips,
                    std::optional<std::vector<std::string>> extract, std::optional<std::filesystem::path> params_csv,
                    std::optional<std::map<std::string, double>> periodic, const std::string& segment,
                    std::optional<std::vector<std::string>> feet, bool replace) {
    workflow::SetRequest r;
    r.name = name;
    r.clips = clips;
    if (extract) r.extract = *extract;
    if (params_csv) r.params_csv = *params_csv;
    if (periodic)
        for (const auto& [p, period] : *periodic) r.periodic.emplace_back(p, period);
    r.segment = segment;
    if (feet) r.feet = *feet;
    r.replace = replace;
    workflow::SetOutcome o;
    {
        py::gil_scoped_release release;
        o = workflow::create_set(db, r);
    }
    py::dict d;
    d["set"] = o.set.name;
    d["samples"] = o.set.samples.size();
    d["clips"] = o.clips;
    d["skipped"] = o.skipped;
    d["segmentation"] = segmentation_name(o.segmentation);
    d["parameter_names"] = o.set.parameter_names;
    d["parameters"] = copy_rows(o.set.parameters);
    d["repaired_runs"] = o.set.repairs.size();
    return d;
}

py::dict parts_dict(const packing::ByteParts& parts) {
    py::dict d;  // insertion order: the parts' order
    for (const packing::BytePart& p : parts) d[py::str(p.name)] = p.bytes;
    return d;
}

py::dict pack(const std::filesystem::path& db, std::optional<double> max_error_cm, std::optional<std::uint64_t> max_bytes,
              int threads, bool replace, bool drop_lossless) {
    if (max_error_cm && max_bytes) throw InvalidArgument("pack: give max_error_cm or max_bytes, not both");
    if (max_bytes && *max_bytes == 0) throw InvalidArgument("pack: max_bytes must be >= 1");
    workflow::PackDatabaseOptions options;
    options.max_error_cm = max_error_cm.value_or(1.0);
    options.max_bytes = max_bytes.value_or(0);
    options.threads = threads;
    options.replace = replace;
    options.drop_lossless = drop_lossless;
    workflow::PackDatabaseOutcome o;
    {
        py::gil_scoped_release release;
        o = workflow::pack_database(db, options);
    }
    const PackedTierRecord& t = o.tier;
    py::dict d;
    d["file"] = db.string();
    d["max_error_cm"] = t.max_error_cm;
    d["bytes"] = t.bytes;
    d["float32_bytes"] = o.float32_bytes;
    d["ratio_float32"] = o.ratio_float32();
    d["clips"] = t.clips;
    d["frames"] = t.frames;
    d["max_cm"] = t.max_cm;
    d["p99_cm"] = t.p99_cm;
    d["rmse_cm"] = t.rmse_cm;
    d["motion_seconds"] = o.motion_seconds;
    d["replaced"] = o.replaced;
    d["dropped_lossless_clips"] = o.dropped_lossless;
    d["file_bytes"] = o.file_bytes;
    d["seconds"] = o.seconds;
    d["parts"] = parts_dict(o.parts);
    py::list group_parts;
    for (const packing::ByteParts& g : o.group_parts) group_parts.append(parts_dict(g));
    d["group_parts"] = group_parts;
    if (o.budget) {
        py::dict budget;
        budget["max_bytes"] = o.budget->max_bytes;
        budget["max_error_cm"] = t.max_error_cm;
        py::list tried;
        for (const workflow::PackDatabaseOutcome::Budget::Try& e : o.budget->tried)
            tried.append(py::dict(py::arg("max_error_cm") = e.max_error_cm,
                                  py::arg("bytes") = e.bytes > 0 || e.fits ? py::object(py::int_(e.bytes)) : py::none(),
                                  py::arg("fits") = e.fits));
        budget["tried"] = tried;
        d["budget"] = budget;
    } else {
        d["budget"] = py::none();
    }
    d["tier"] = t;
    return d;
}

py::dict align(const std::filesystem::path& db, const std::string& set, Eigen::Index frames, const std::string& method,
               const std::string& reference) {
    workflow::AlignRequest r;
    r.set = set;
    r.frames = frames;
    r.method = method;
    r.reference = reference;
    workflow::AlignOutcome o;
    {
        py::gil_scoped_release release;
        o = workflow::align_set(db, r);
    }
    py::dict d;
    d["set"] = set;
    d["samples"] = o.aligned.samples();
    d["frames"] = o.aligned.frames();
    d["dofs"] = o.aligned.dofs();
    d["reference"] = o.aligned.reference;
    d["mean_distance_cm"] = o.distance;
    d["seconds"] = o.seconds;
    d["labels"] = o.labels;
    if (o.phase) {
        d["phase_min"] = o.phase->min;
        d["phase_mean"] = o.phase->mean;
    }
    return d;
}

tensor::TuckerMethod tucker_method(const std::string& name) {
    if (name == "hosvd") return tensor::TuckerMethod::Hosvd;
    if (name == "sthosvd") return tensor::TuckerMethod::StHosvd;
    if (name == "hooi") return tensor::TuckerMethod::Hooi;
    throw InvalidArgument("method: expected 'hosvd', 'sthosvd' or 'hooi', got '" + name + "'");
}

py::dict compress(const std::filesystem::path& db, const std::string& set, std::optional<std::array<Eigen::Index, 3>> ranks,
                  double max_error_cm, std::optional<double> rmse, std::optional<double> ratio, const std::string& method,
                  int max_iterations) {
    workflow::CompressRequest r;
    r.set = set;
    r.ranks = ranks;
    r.max_error_cm = max_error_cm;
    r.rmse = rmse.value_or(-1.0);
    r.ratio = ratio.value_or(0.0);
    r.method = tucker_method(method);
    r.max_iterations = max_iterations;
    workflow::CompressOutcome o;
    {
        py::gil_scoped_release release;
        o = workflow::compress_set(db, r);
    }
    const tensor::TuckerModel& t = o.model.tucker;
    py::dict d;
    d["set"] = set;
    d["criterion"] = o.criterion;
    d["target_met"] = o.target_met;
    d["method"] = tensor::to_string(t.method);
    d["dims"] = py::make_tuple(o.dims[0], o.dims[1], o.dims[2]);
    d["ranks"] = py::make_tuple(t.ranks[0], t.ranks[1], t.ranks[2]);
    d["raw_bytes"] = o.raw_bytes;
    d["bytes"] = o.bytes;
    d["ratio"] = o.ratio();
    d["file_bytes"] = o.stored_bytes;
    d["dof_rmse"] = o.stats.dof_rmse;
    d["rmse_cm"] = o.stats.rmse_cm;
    d["mean_cm"] = o.stats.mean_cm;
    d["max_cm"] = o.stats.max_cm;
    d["p99_cm"] = o.stats.p99_cm;
    d["kernel_stored"] = o.kernel_stored;
    d["total_s"] = o.total_s;
    return d;
}

py::dict packed_figures(const eval::PackedFigures& f) {
    py::dict d;
    d["clips"] = f.clips;
    d["frames"] = f.frames;
    d["bytes"] = f.bytes;
    d["float32_bytes"] = f.float32_bytes;
    d["ratio_float32"] = f.ratio_float32();
    d["max_cm"] = f.max_cm;
    d["p99_cm"] = f.p99_cm;
    d["rmse_cm"] = f.rmse_cm;
    d["parts"] = parts_dict(f.parts);
    return d;
}

py::dict collection_report_dict(const std::filesystem::path& path, const std::vector<double>& max_error_cm, int threads,
                                const std::vector<std::filesystem::path>& source_dirs) {
    eval::CollectionReportOptions options;
    options.max_error_cm = max_error_cm;
    options.threads = threads;
    options.random_poses = 0;
    options.source_dirs = source_dirs;
    const Database db(path);
    eval::CollectionReport r;
    {
        py::gil_scoped_release release;
        r = eval::collection_report(db, options);
    }
    py::dict d;
    d["clips"] = r.clips;
    d["frames"] = r.frames;
    d["groups"] = r.groups;
    d["motion_seconds"] = r.motion_seconds;
    d["float32_bytes"] = r.float32_bytes;
    py::dict lossless;
    lossless["bytes"] = r.lossless.bytes;
    lossless["channel_bytes"] = r.lossless.channel_bytes;
    lossless["float32_bytes"] = r.lossless.float32_bytes;
    lossless["ratio_float32"] = r.lossless.ratio_float32();
    if (r.lossless.gzip_available) lossless["gzip_bytes"] = r.lossless.gzip_bytes;
    d["lossless"] = lossless;
    py::list targets;
    for (const eval::TargetFigures& t : r.targets) {
        py::dict target = packed_figures(t.total);
        target["max_error_cm"] = t.max_error_cm;
        target["resident_bytes"] = t.resident_bytes;
        targets.append(target);
    }
    d["targets"] = targets;
    return d;
}

}  // namespace

void bind_workflow(py::module_& m) {
    m.def("import_files", &import_files, py::arg("db"), py::arg("inputs"), py::arg("asf") = py::none(),
          py::arg("frame_rate") = py::none(), py::arg("strict") = false, py::arg("keep_going") = false,
          py::arg("force") = false,
          "`mocapdb import`: the BVH and AMC files found under `inputs` (files or folders) stored losslessly in "
          "`db` (appended; a new file when absent, or replaced when force=True); files already stored (same "
          "SHA-256) are skipped. keep_going: a file that cannot be read is reported in 'errors' instead of "
          "stopping everything. Readers' warnings become UserWarnings. Committed. Returns {'files', 'added', "
          "'skipped', 'failed', 'frames', 'clips_in_db', 'file_bytes', 'errors', 'not_added', ...}." "\n\nExample:\n    >>> mocapdb.import_files('walks.h5', ['cmu-asfamc/16_11.amc'])['added']");
    m.def("create_set", &create_set, py::arg("db"), py::arg("name"), py::arg("clips"), py::arg("extract") = py::none(),
          py::arg("params_csv") = py::none(), py::arg("periodic") = py::none(), py::arg("segment") = "auto",
          py::arg("feet") = py::none(), py::arg("replace") = false,
          "`mocapdb set create`: a motion set of the stored clips matching `clips` (ids or fnmatch patterns), "
          "its parameters measured by the `extract` extractors (e.g. ['turn', 'speed']) or read from `params_csv`; "
          "periodic: {name: period}; segment: 'auto', 'none', 'gait[:N]' or 'window:LENGTH[:HOP]'. Committed. Returns "
          "{'set', 'samples', 'clips', 'skipped', 'segmentation', 'parameter_names', 'parameters', 'repaired_runs'}." "\n\nExample:\n    >>> mocapdb.create_set('walks.h5', 'walks', ['16_*'], extract=['turn', 'speed'])['samples']");
    m.def("align", &align, py::arg("db"), py::arg("set"), py::arg("frames") = 100, py::arg("method") = "dtw",
          py::arg("reference") = "",
          "`mocapdb align`: the set's samples time-aligned to `frames` aligned frames (method 'dtw' or 'linear'; "
          "reference: a sample label, default the library's choice) and stored (committed). Returns {'samples', "
          "'frames', 'dofs', 'reference', 'mean_distance_cm', 'labels', 'phase_min', 'phase_mean', ...}." "\n\nExample:\n    >>> mocapdb.align('walks.h5', 'walks', frames=40)['samples']");
    m.def("compress", &compress, py::arg("db"), py::arg("set"), py::arg("ranks") = py::none(), py::arg("max_error_cm") = 0.0,
          py::arg("rmse") = py::none(), py::arg("ratio") = py::none(), py::arg("method") = "hosvd",
          py::arg("max_iterations") = 50,
          "`mocapdb compress`: the aligned set's Tucker model at explicit ranks (R1, R2, R3), or the smallest "
          "ranks meeting max_error_cm (default 1 cm), rmse or ratio; method 'hosvd', 'sthosvd' or 'hooi'. The model "
          "and its synthesis kernel are stored (committed). Returns the keys of `mocapdb compress --json` "
          "(criterion, target_met, ranks, bytes, ratio, max_cm, p99_cm, rmse_cm, ...)." "\n\nExample:\n    >>> mocapdb.compress('walks.h5', 'walks', max_error_cm=1.0)['ranks']");
    m.def("pack", &pack, py::arg("db"), py::arg("max_error_cm") = py::none(), py::arg("max_bytes") = py::none(),
          py::arg("threads") = 2, py::arg("replace") = false, py::arg("drop_lossless") = false,
          "`mocapdb pack`: every clip packed with max FK joint error <= max_error_cm (cm, default 1), or with "
          "max_bytes at the smallest max error whose bytes fit max_bytes (not both), stored as the packed tier "
          "(committed). Returns the keys of `mocapdb pack --json` (bytes, max_error_cm, max_cm, p99_cm, rmse_cm, "
          "clips, frames, parts: bytes per kind of stored data summing to bytes, budget: None or {max_bytes, "
          "max_error_cm, tried}, ...), 'group_parts' (per group) and 'tier', the PackedTier." "\n\nExample:\n    >>> mocapdb.pack('walks.h5', max_error_cm=1.0)['bytes']");
    m.def("collection_report", &collection_report_dict, py::arg("db"), py::arg("max_error_cm") = std::vector<double>{1.0, 0.5, 0.1, 0.03, 0.01},
          py::arg("threads") = 2, py::arg("source_dirs") = std::vector<std::filesystem::path>{},
          "`mocapdb report` on a whole collection (nothing is stored): the lossless tier's bytes and, per bound E, "
          "the packed bytes (with 'parts'), and measured errors. Returns {'clips', 'frames', 'groups', 'motion_seconds', "
          "'float32_bytes', 'lossless': {'bytes' (file bytes spent on the clips), 'channel_bytes', ...}, 'targets': "
          "[{'max_error_cm', 'bytes', 'parts', 'max_cm', ...}]}." "\n\nExample:\n    >>> report = mocapdb.collection_report('walks.h5', max_error_cm=[1.0])\n    >>> report['targets'][0]['bytes']");
}

}  // namespace mocapdb::python
