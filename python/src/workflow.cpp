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
#include "json_dict.hpp"
#include "progress.hpp"
#include "mocapdb/eval/collection_acl.hpp"
#include "mocapdb_json/report_json.hpp"
#include "mocapdb_json/step_json.hpp"
#include "mocapdb/eval/collection_report.hpp"
#include "mocapdb/workflow/pack_collection.hpp"
#include "mocapdb/workflow/clip_import.hpp"
#include "mocapdb/workflow/set_alignment.hpp"
#include "mocapdb/workflow/set_compression.hpp"
#include "mocapdb/workflow/set_creation.hpp"

namespace mocapdb::python {
namespace {

py::object import_files(const std::filesystem::path& db, const std::vector<std::filesystem::path>& inputs,
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
    json::JsonWriter j;
    json::write_import(j, db.string(), o);
    return to_python(j.tree());
}

py::object create_set(const std::filesystem::path& db, const std::string& name, const std::vector<std::string>& clips,
                      std::optional<std::vector<std::string>> extract, std::optional<std::filesystem::path> params_csv,
                      std::optional<std::map<std::string, double>> periodic, const std::string& segment,
                      std::optional<std::vector<std::string>> feet, bool replace,
                      std::optional<std::map<std::string, std::string>> categories) {
    workflow::SetRequest r;
    r.name = name;
    r.clips = clips;
    if (extract) r.extract = *extract;
    if (params_csv) r.params_csv = *params_csv;
    if (periodic)
        for (const auto& [p, period] : *periodic) r.periodic.emplace_back(p, period);
    r.segment = segment;
    if (feet) r.feet = *feet;
    if (categories)
        for (const auto& [p, pattern] : *categories) r.categories.emplace_back(p, pattern);
    r.replace = replace;
    workflow::SetOutcome o;
    {
        py::gil_scoped_release release;
        o = workflow::create_set(db, r);
    }
    json::JsonWriter j;
    json::write_set(j, o);
    return to_python(j.tree());
}

py::object pack(const std::filesystem::path& db, std::optional<double> max_error_cm,
                std::optional<std::uint64_t> max_bytes, int threads, bool replace, bool drop_lossless,
                const std::string& format) {
    if (max_error_cm && max_bytes) throw InvalidArgument("pack: give max_error_cm or max_bytes, not both");
    if (max_bytes && *max_bytes == 0) throw InvalidArgument("pack: max_bytes must be >= 1");
    if (format != "runtime" && format != "archive")
        throw InvalidArgument("pack: format must be 'runtime' or 'archive', got '" + format + "'");
    workflow::PackDatabaseOptions options;
    options.format = format == "archive" ? packing::PackFormat::Archive : packing::PackFormat::Runtime;
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
    json::JsonWriter j;
    json::write_pack(j, db.string(), o);
    return to_python(j.tree());
}

py::object align(const std::filesystem::path& db, const std::string& set, Eigen::Index frames,
                 const std::string& method, const std::string& reference) {
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
    json::JsonWriter j;
    json::write_alignment(j, set, o);
    return to_python(j.tree());
}

tensor::TuckerMethod tucker_method(const std::string& name) {
    if (name == "hosvd") return tensor::TuckerMethod::Hosvd;
    if (name == "sthosvd") return tensor::TuckerMethod::StHosvd;
    if (name == "hooi") return tensor::TuckerMethod::Hooi;
    throw InvalidArgument("method: expected 'hosvd', 'sthosvd' or 'hooi', got '" + name + "'");
}

py::object compress(const std::filesystem::path& db, const std::string& set,
                    std::optional<std::array<Eigen::Index, 3>> ranks, double max_error_cm, std::optional<double> rmse,
                    std::optional<double> ratio, const std::string& method, int max_iterations,
                    const py::object& progress) {
    PythonProgress report(progress);
    workflow::CompressRequest r;
    r.progress = report.callback();
    r.kernel_progress = report.callback();
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
    report.rethrow();
    json::JsonWriter j;
    json::write_compression(j, set, o);
    return to_python(j.tree());
}

py::object collection_report_dict(const std::filesystem::path& path, const std::vector<double>& max_error_cm,
                                  int threads, const std::vector<std::filesystem::path>& source_dirs,
                                  const std::vector<std::string>& references, std::size_t poses) {
    eval::CollectionReportOptions options;
    options.max_error_cm = max_error_cm;
    options.threads = threads;
    options.random_poses = poses;
    options.source_dirs = source_dirs;
    eval::CollectionAcl reference = eval::read_collection_acl(references);
    const Database db(path);
    eval::CollectionReport r;
    {
        py::gil_scoped_release release;
        r = eval::collection_report(db, options);
    }
    eval::compare_collection_with_acl(reference, r);
    json::JsonWriter j;
    json::write_collection_report(j, path.string(), r, reference);
    return to_python(j.tree());
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
          "'skipped', 'failed', 'frames', 'clips_in_db', 'file_bytes', 'errors', 'warnings', 'not_added', ...}: the "
          "keys of `mocapdb import --json`."
          "\n\nExample:\n    >>> mocapdb.import_files('walks.h5', ['cmu-asfamc/16_11.amc'])['added']");
    m.def(
        "create_set", &create_set, py::arg("db"), py::arg("name"), py::arg("clips"), py::arg("extract") = py::none(),
        py::arg("params_csv") = py::none(), py::arg("periodic") = py::none(), py::arg("segment") = "auto",
        py::arg("feet") = py::none(), py::arg("replace") = false, py::arg("categories") = py::none(),
        "`mocapdb set create`: a motion set of the stored clips matching `clips` (ids or fnmatch patterns), "
        "its parameters measured by the `extract` extractors (e.g. ['turn', 'speed']) and/or read from `params_csv` "
        "(a column of level names is categorical); categories: {name: regex} categorical parameters whose level is "
        "the regex's first group in the clip id; periodic: {name: period}; segment: 'auto', 'none', 'gait[:N]' or 'window:LENGTH[:HOP]'. Committed. Returns "
        "{'set', 'samples', 'clips', 'skipped', 'segmentation', 'parameter_names', 'parameters', 'repaired_runs'}."
        "\n\nExample:\n    >>> mocapdb.create_set('walks.h5', 'walks', ['16_*'], extract=['turn', 'speed'])['samples']");
    m.def("align", &align, py::arg("db"), py::arg("set"), py::arg("frames") = 100, py::arg("method") = "dtw",
          py::arg("reference") = "",
          "`mocapdb align`: the set's samples time-aligned to `frames` aligned frames (method 'dtw' or 'linear'; "
          "reference: a sample label, default the library's choice) and stored (committed). Returns {'samples', "
          "'frames', 'dofs', 'reference', 'mean_distance_cm', 'labels', 'phase_min', 'phase_mean', ...}."
          "\n\nExample:\n    >>> mocapdb.align('walks.h5', 'walks', frames=40)['samples']");
    m.def(
        "compress", &compress, py::arg("db"), py::arg("set"), py::arg("ranks") = py::none(),
        py::arg("max_error_cm") = 0.0, py::arg("rmse") = py::none(), py::arg("ratio") = py::none(),
        py::arg("method") = "hosvd", py::arg("max_iterations") = 50, py::arg("progress") = py::none(),
        "`mocapdb compress`: the aligned set's Tucker model at explicit ranks (R1, R2, R3), or the smallest "
        "ranks meeting max_error_cm (default 1 cm), rmse or ratio; method 'hosvd', 'sthosvd' or 'hooi'. The model "
        "and its synthesis kernel are stored (committed). progress: None or a callable progress(done, total, "
        "item) called as the steps advance (item 'kernel': the kernel's candidate variograms; 'kernel system': "
        "columns of its factorized system; else the rank search); an exception it raises is raised when "
        "compress returns. Returns the keys of `mocapdb compress --json` "
        "(criterion, target_met, ranks, bytes, ratio, max_cm, p99_cm, rmse_cm, ...)."
        "\n\nExample:\n    >>> mocapdb.compress('walks.h5', 'walks', max_error_cm=1.0)['ranks']"
        "\n    >>> mocapdb.compress('walks.h5', 'walks', progress=lambda done, total, item: print(item, done, total))");
    m.def(
        "pack", &pack, py::arg("db"), py::arg("max_error_cm") = py::none(), py::arg("max_bytes") = py::none(),
        py::arg("threads") = 2, py::arg("replace") = false, py::arg("drop_lossless") = false,
        py::arg("format") = "runtime",
        "`mocapdb pack`: every clip packed with max FK joint error <= max_error_cm (cm, default 1), or with "
        "max_bytes at the smallest max error whose bytes fit max_bytes (not both), stored as the packed tier "
        "(committed); format 'runtime' (a pose decodes in about a microsecond) or 'archive' (smallest). Returns the keys of `mocapdb pack --json` (bytes, max_error_cm, max_cm, p99_cm, rmse_cm, "
        "clips, frames, parts: bytes per kind of stored data summing to bytes, budget: None or {max_bytes, "
        "max_error_cm, tried}, groups: [{name, bytes, parts, ...}], ...)."
        "\n\nExample:\n    >>> mocapdb.pack('walks.h5', max_error_cm=1.0)['bytes']");
    m.def(
        "collection_report", &collection_report_dict, py::arg("db"),
        py::arg("max_error_cm") = std::vector<double>{1.0, 0.5, 0.1, 0.03, 0.01}, py::arg("threads") = 2,
        py::arg("source_dirs") = std::vector<std::filesystem::path>{},
        py::arg("references") = std::vector<std::string>{}, py::arg("poses") = 0,
        "`mocapdb report --collection` (nothing is stored): the lossless tier's bytes and, per bound E, "
        "the packed bytes (with 'parts'), and measured errors; beside ACL when `references` names its per-clip "
        "tables; `poses` cold random poses timed per E (0: none). Returns the keys of `mocapdb report "
        "--collection --json`: {'clips', 'frames', 'groups', 'float32_bytes', 'lossless': {'bytes' (file bytes "
        "spent on the clips), 'channel_bytes', ...}, 'targets': [{'max_error_cm', 'bytes', 'parts', 'max_cm', "
        "'acl', ...}], 'reference'}."
        "\n\nExample:\n    >>> report = mocapdb.collection_report('walks.h5', max_error_cm=[1.0])\n    >>> report['targets'][0]['bytes']");
}

}  // namespace mocapdb::python
