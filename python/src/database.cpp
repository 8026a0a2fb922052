// mocapdb.Database (mocapdb.open): what a database file holds, its clips from either tier, its sets
// and their synthesis models.
#include "mocapdb/store/database.hpp"

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <memory>
#include <optional>

#include "arrays.hpp"
#include "bindings.hpp"
#include "database_handle.hpp"
#include "model_handle.hpp"
#include "progress.hpp"
#include "mocapdb/workflow/load_model.hpp"

namespace mocapdb::python {
namespace {

void bind_records(py::module_& m) {
    py::class_<ClipRecord>(m, "ClipInfo",
                           "A stored clip's record (no motion read)."
                           "\n\nExample:\n    >>> [(c.name, c.frames) for c in db.clips()]")
        .def_readonly("name", &ClipRecord::id, "The clip id (the source file's stem, made unique).")
        .def_readonly("skeleton", &ClipRecord::skeleton, "Skeleton id.")
        .def_readonly("frames", &ClipRecord::frames, "F, frames of the clip.")
        .def_readonly("channels", &ClipRecord::channels, "C, channels per frame.")
        .def_readonly("frame_rate", &ClipRecord::frame_rate, "Hz.")
        .def_property_readonly("duration", &ClipRecord::duration, "Seconds from the first to the last frame.")
        .def_readonly("stored_bytes", &ClipRecord::stored_bytes, "Bytes of its lossless channels in the file.")
        .def_readonly("lossless", &ClipRecord::lossless,
                      "False when only the packed tier holds it (pack --drop-lossless).")
        .def_property_readonly(
            "source_file", [](const ClipRecord& r) { return r.source.file_name; },
            "The source file's name (no folders).")
        .def_property_readonly(
            "format", [](const ClipRecord& r) { return r.source.format; }, "'bvh' or 'amc'.")
        .def_property_readonly(
            "sha256", [](const ClipRecord& r) { return r.source.sha256; }, "Of the source file's bytes.")
        .def_property_readonly(
            "subject", [](const ClipRecord& r) { return r.source.subject; },
            "From the import manifest (empty without).")
        .def_property_readonly(
            "description", [](const ClipRecord& r) { return r.source.description; }, "From the import manifest.")
        .def_property_readonly(
            "labels", [](const ClipRecord& r) { return r.source.labels; }, "From the import manifest.")
        .def("__repr__", [](const ClipRecord& r) {
            return "<mocapdb.ClipInfo '" + r.id + "' " + std::to_string(r.frames) + " frames at " +
                   std::to_string(r.frame_rate) + " Hz>";
        });

    py::class_<SetRecord>(m, "SetInfo",
                          "A motion set's record."
                          "\n\nExample:\n    >>> [s.name for s in db.sets()]")
        .def_readonly("name", &SetRecord::name, "The set's name.")
        .def_readonly("samples", &SetRecord::samples, "N.")
        .def_readonly("parameter_names", &SetRecord::parameter_names, "The P control parameters.")
        .def_readonly("parameter_source", &SetRecord::parameter_source, "'extract:turn,speed', 'csv:FILE', ...")
        .def_readonly("aligned", &SetRecord::aligned, "The samples are time-aligned (mocapdb align).")
        .def_property_readonly(
            "tensor_shape",
            [](const SetRecord& s) { return py::make_tuple(s.tensor_shape[0], s.tensor_shape[1], s.tensor_shape[2]); },
            "(N, T, D) of the aligned tensor; zeros when not aligned.")
        .def_readonly("model", &SetRecord::model, "A Tucker model is stored (mocapdb compress).")
        .def_property_readonly(
            "model_ranks",
            [](const SetRecord& s) { return py::make_tuple(s.model_ranks[0], s.model_ranks[1], s.model_ranks[2]); },
            "(R1, R2, R3); zeros without a model.")
        .def("__repr__", [](const SetRecord& s) {
            return "<mocapdb.SetInfo '" + s.name + "' " + std::to_string(s.samples) + " samples" +
                   (s.aligned ? ", aligned" : "") + (s.model ? ", model" : "") + ">";
        });

    py::class_<SampleRef>(
        m, "Sample",
        "One sample of a motion set: frames [begin, end) of a clip."
        "\n\nExample:\n    >>> s = db.set('walks').samples[0]\n    >>> db.clip(s.clip, begin=s.begin, end=s.end)")
        .def_readonly("clip", &SampleRef::clip, "The clip's name.")
        .def_readonly("begin", &SampleRef::begin, "First frame.")
        .def_readonly("end", &SampleRef::end, "One past the last frame.")
        .def("__repr__", [](const SampleRef& s) {
            return "<mocapdb.Sample " + s.clip + "[" + std::to_string(s.begin) + ":" + std::to_string(s.end) + "]>";
        });

    py::class_<MotionSet>(
        m, "MotionSet",
        "A motion set: samples with control parameters."
        "\n\nExample:\n    >>> walks = db.set('walks')\n    >>> walks.parameter_names, len(walks.samples)")
        .def_readonly("name", &MotionSet::name, "The set's name.")
        .def_readonly("samples", &MotionSet::samples, "The N Samples, in order.")
        .def_readonly("parameter_names", &MotionSet::parameter_names, "The P control parameters.")
        .def_readonly("parameter_units", &MotionSet::parameter_units, "Their units ('rad', 'cm/s', ...).")
        .def_readonly("parameter_source", &MotionSet::parameter_source,
                      "How they were obtained ('extract:turn,speed', 'csv:FILE', joined by '; ').")
        .def_readonly("parameter_levels", &MotionSet::parameter_levels,
                      "Per parameter its level names (a categorical parameter, whose column holds level indices), "
                      "[] for a numeric one; [] when none is categorical.")
        .def_property_readonly(
            "parameters", [](const MotionSet& s) { return copy_rows(s.parameters); },
            "(N, P) control parameters of the samples.");

    py::class_<PackedClipRecord>(m, "PackedClip",
                                 "A clip of the packed tier and its measured errors (cm)."
                                 "\n\nExample:\n    >>> [(c.name, c.max_cm) for c in db.packed().groups[0].clips]")
        .def_readonly("name", &PackedClipRecord::id, "The clip's name.")
        .def_readonly("frames", &PackedClipRecord::frames, "F.")
        .def_readonly("payload_bytes", &PackedClipRecord::payload_bytes,
                      "Its windows' coded bytes (the group's tables are shared).")
        .def_readonly("max_cm", &PackedClipRecord::max_cm, "Max FK joint error against the source, every frame.")
        .def_readonly("p99_cm", &PackedClipRecord::p99_cm, "99th percentile of the joint errors.")
        .def_readonly("rmse_cm", &PackedClipRecord::rmse_cm, "Root mean square joint error.");
    py::class_<PackedGroupRecord>(m, "PackedGroup",
                                  "Clips of one rig and frame rate packed together."
                                  "\n\nExample:\n    >>> [(g.name, len(g.clips)) for g in db.packed().groups]")
        .def_readonly("name", &PackedGroupRecord::name, "Its name under /packed ('g0', ...).")
        .def_readonly("skeleton", &PackedGroupRecord::skeleton, "Skeleton id of its first clip.")
        .def_readonly("frame_rate", &PackedGroupRecord::frame_rate, "Hz.")
        .def_readonly("bytes", &PackedGroupRecord::bytes, "Everything its decoder needs.")
        .def_readonly("frames", &PackedGroupRecord::frames, "Frames of its clips.")
        .def_readonly("max_cm", &PackedGroupRecord::max_cm, "Max FK joint error over its clips.")
        .def_readonly("p99_cm", &PackedGroupRecord::p99_cm, "99th percentile.")
        .def_readonly("rmse_cm", &PackedGroupRecord::rmse_cm, "Root mean square.")
        .def_readonly("clips", &PackedGroupRecord::clips, "Its PackedClips in packing order.");
    py::class_<PackedTierRecord>(m, "PackedTier",
                                 "The packed tier: every clip within max_error_cm (FK, every joint, cm)."
                                 "\n\nExample:\n    >>> tier = db.packed()\n    >>> tier.max_error_cm, tier.bytes")
        .def_readonly("max_error_cm", &PackedTierRecord::max_error_cm, "E, the bound.")
        .def_readonly("bytes", &PackedTierRecord::bytes, "Sum of the groups' bytes.")
        .def_readonly("clips", &PackedTierRecord::clips, "Clips in the tier.")
        .def_readonly("frames", &PackedTierRecord::frames, "Their frames.")
        .def_readonly("max_cm", &PackedTierRecord::max_cm, "Max FK joint error over the collection (<= max_error_cm).")
        .def_readonly("p99_cm", &PackedTierRecord::p99_cm, "99th percentile.")
        .def_readonly("rmse_cm", &PackedTierRecord::rmse_cm, "Root mean square.")
        .def_readonly("groups", &PackedTierRecord::groups, "Its PackedGroups.")
        .def("__repr__", [](const PackedTierRecord& t) {
            return "<mocapdb.PackedTier " + std::to_string(t.clips) + " clips, " + std::to_string(t.bytes) +
                   " bytes, max " + std::to_string(t.max_cm) + " cm>";
        });
}

std::shared_ptr<Clip> load_clip(const DatabaseHandle& h, const std::string& name, const std::string& tier,
                                std::size_t begin, std::optional<std::size_t> end) {
    const Database& db = h.get();
    if (tier == "packed")
        return std::make_shared<Clip>(db.load_clip_packed(name, begin, end.value_or(static_cast<std::size_t>(-1))));
    if (tier != "lossless") throw InvalidArgument("tier: expected 'lossless' or 'packed', got '" + tier + "'");
    Clip clip = db.load_clip(name);
    if (begin != 0 || end) clip = slice(clip, begin, std::min(end.value_or(clip.frame_count()), clip.frame_count()));
    return std::make_shared<Clip>(std::move(clip));
}

std::shared_ptr<ModelHandle> synthesis_model(const DatabaseHandle& h, const std::string& set, bool naive,
                                             const py::object& progress) {
    PythonProgress report(progress);
    std::shared_ptr<ModelHandle> model = load_model_handle(h.get(), set, naive, report.callback());
    report.rethrow();
    return model;
}

}  // namespace

void bind_database(py::module_& m) {
    bind_records(m);
    m.def(
        "copy_database",
        [](const std::filesystem::path& source, const std::filesystem::path& destination) {
            copy_database(source, destination);
        },
        py::arg("source"), py::arg("destination"),
        "Copies a database to a new path: its file and (format 4) the segments it links to, into "
        "'destination.d/' (a copy of the file alone would still read the original's segments). IoError when "
        "destination exists."
        "\n\nExample:\n    >>> mocapdb.copy_database('walks.h5', 'scratch.h5')");
    py::class_<DatabaseHandle, std::shared_ptr<DatabaseHandle>>(
        m, "Database",
        "A mocapdb database file, read-only (mocapdb.open). Writing steps (import_files, create_set, align, "
        "compress, pack) take the file's path and commit atomically; open the file again to see their result. "
        "Not thread-safe: use one Database per thread."
        "\n\nExample:\n    >>> with mocapdb.open('walks.h5') as db:\n    ...     clip = db.clip('16_11')")
        .def(py::init([](const std::filesystem::path& path) {
                 auto h = std::make_shared<DatabaseHandle>();
                 h->path = path;
                 h->db = std::make_shared<const Database>(path);
                 return h;
             }),
             py::arg("path"),
             "Opens a database read-only; StoreError for a file that is not one, IoError when missing.")
        .def_property_readonly(
            "path", [](const DatabaseHandle& h) { return h.path; }, "The file.")
        .def_property_readonly(
            "format_version", [](const DatabaseHandle& h) { return h.get().format_version(); },
            "The file format's version (schemas/).")
        .def_property_readonly(
            "file_size", [](const DatabaseHandle& h) { return h.get().file_size(); }, "Bytes.")
        .def(
            "clips", [](const DatabaseHandle& h) { return h.get().clips(); },
            "Every stored clip's ClipInfo, sorted by name."
            "\n\nExample:\n    >>> [c.name for c in db.clips()][:3]")
        .def("clip", &load_clip, py::arg("name"), py::arg("tier") = "lossless", py::arg("begin") = 0,
             py::arg("end") = py::none(),
             "A stored clip, frames [begin, end): tier 'lossless' (the source values exactly; a clip whose lossless "
             "channels were dropped comes from the packed tier) or 'packed' (decoded from the packed tier, within "
             "its max_error_cm, with the packed skeleton). NotFoundError (a KeyError) for a name it does not hold."
             "\n\nExample:\n    >>> clip = db.clip('16_11', tier='packed', begin=0, end=120)")
        .def(
            "skeletons", [](const DatabaseHandle& h) { return h.get().skeletons(); },
            "Skeleton ids."
            "\n\nExample:\n    >>> db.skeletons()")
        .def(
            "skeleton",
            [](const DatabaseHandle& h, const std::string& id) {
                return std::const_pointer_cast<Skeleton>(h.get().load_skeleton(id));
            },
            py::arg("id"),
            "A stored Skeleton."
            "\n\nExample:\n    >>> rig = db.skeleton(db.clips()[0].skeleton)")
        .def(
            "sets", [](const DatabaseHandle& h) { return h.get().sets(); },
            "Every motion set's SetInfo, sorted by name."
            "\n\nExample:\n    >>> [s.name for s in db.sets()]")
        .def(
            "set", [](const DatabaseHandle& h, const std::string& name) { return h.get().load_set(name); },
            py::arg("name"),
            "A MotionSet: its samples and control parameters."
            "\n\nExample:\n    >>> walks = db.set('walks')")
        .def(
            "packed", [](const DatabaseHandle& h) { return h.get().packed(); },
            "The PackedTier's records, or None when the file has none (mocapdb pack)."
            "\n\nExample:\n    >>> tier = db.packed()")
        .def("synthesis_model", &synthesis_model, py::arg("set"), py::arg("naive") = false,
             py::arg("progress") = py::none(),
             "The set's SynthesisModel: the stored Tucker model (mocapdb compress) with its stored kernel, or with "
             "naive=True kriging of the uncompressed aligned tensor (needs only mocapdb align). progress: None or "
             "a callable progress(done, total, item), called while a kernel that is not stored (naive=True, or a "
             "model compressed before kernels were) is fitted (item 'kernel') and while a kriging system that is "
             "not stored is factorized (item 'kernel system')."
             "\n\nExample:\n    >>> model = db.synthesis_model('walks')")
        .def(
            "close", [](DatabaseHandle& h) { h.db.reset(); },
            "Lets go of the file (samplers made from it keep their own view until they are dropped)."
            "\n\nExample:\n    >>> db.close()")
        .def("__enter__", [](const std::shared_ptr<DatabaseHandle>& h) { return h; })
        .def("__exit__", [](DatabaseHandle& h, py::args) { h.db.reset(); })
        .def("__repr__",
             [](const DatabaseHandle& h) {
                 return "<mocapdb.Database '" + h.path.string() + "'" + (h.db ? "" : " closed") + ">";
             })
        .def(py::pickle([](const DatabaseHandle& h) { return py::make_tuple(h.path); },  // reopened by path, read-only
                        [](const py::tuple& t) {
                            if (t.size() != 1) throw InvalidArgument("Database: not a pickled database's state");
                            auto h = std::make_shared<DatabaseHandle>();
                            h->path = t[0].cast<std::filesystem::path>();
                            h->db = std::make_shared<const Database>(h->path);
                            return h;
                        }));
}

}  // namespace mocapdb::python
