// mocapdb.WindowSampler (Database.sampler): random training windows as numpy batches.
#include "mocapdb/workflow/window_sampler.hpp"

#include <pybind11/stl.h>

#include <algorithm>
#include <limits>
#include <memory>
#include <mutex>
#include <optional>

#include "arrays.hpp"
#include "bindings.hpp"
#include "database_handle.hpp"

namespace mocapdb::python {
namespace {

struct SamplerHandle {
    std::shared_ptr<const Database> db;  ///< kept open while the sampler lives
    std::unique_ptr<workflow::WindowSampler> sampler;
    std::mutex busy;  ///< batches of one sampler from several threads take turns
};

workflow::WindowValues values_of(const std::string& text) {
    if (text == "pose_vectors") return workflow::WindowValues::PoseVectors;
    if (text == "joint_positions") return workflow::WindowValues::JointPositions;
    throw InvalidArgument("values: expected 'pose_vectors' or 'joint_positions', got '" + text + "'");
}

workflow::WindowSource source_of(const std::string& text) {
    if (text == "auto") return workflow::WindowSource::Auto;
    if (text == "packed") return workflow::WindowSource::Packed;
    if (text == "lossless") return workflow::WindowSource::Lossless;
    throw InvalidArgument("source: expected 'auto', 'packed' or 'lossless', got '" + text + "'");
}

/// The next batch into out (B x L x V) and refs (may be null). The packed path reads only the
/// sampler's own decoders, so it runs without the GIL; the lossless path reads the (not thread-safe)
/// database and keeps it.
void next_batch(SamplerHandle& h, double* out, workflow::WindowRef* refs) {
    if (h.sampler->from_packed()) {
        py::gil_scoped_release release;
        const std::lock_guard<std::mutex> lock(h.busy);
        h.sampler->next(out, refs);
    } else {
        const std::lock_guard<std::mutex> lock(h.busy);
        h.sampler->next(out, refs);
    }
}

/// A Python integer (numpy's included, bool not) at least `minimum`: TypeError / InvalidArgument (a
/// ValueError) naming the argument otherwise, rather than pybind11's list of signatures.
std::uint64_t integer_arg(const py::handle& value, const char* name, std::uint64_t minimum) {
    if (PyBool_Check(value.ptr()) || !PyIndex_Check(value.ptr()))
        throw py::type_error(std::string("sampler: ") + name + " must be an integer, got " +
                             std::string(py::str(py::type::of(value).attr("__name__"))));
    const py::int_ number(py::reinterpret_steal<py::object>(PyNumber_Index(value.ptr())));
    if (number < py::int_(minimum))
        throw InvalidArgument(std::string("sampler: ") + name + " must be at least " + std::to_string(minimum) + ", got " +
                              std::string(py::str(static_cast<const py::object&>(number))));
    if (number > py::int_(std::numeric_limits<std::uint64_t>::max()))
        throw InvalidArgument(std::string("sampler: ") + name + " must be less than 2**64, got " + std::string(py::str(static_cast<const py::object&>(number))));
    return number.cast<std::uint64_t>();
}

std::string text_arg(const py::handle& value, const char* name) {
    if (!py::isinstance<py::str>(value))
        throw py::type_error(std::string("sampler: ") + name + " must be a str, got " +
                             std::string(py::str(py::type::of(value).attr("__name__"))));
    return value.cast<std::string>();
}

/// None (every clip), one name or pattern, or an iterable of them.
std::vector<std::string> clips_arg(const py::handle& value) {
    if (value.is_none()) return {};
    if (py::isinstance<py::str>(value)) return {value.cast<std::string>()};
    if (!py::isinstance<py::iterable>(value))
        throw py::type_error("sampler: clips must be None, a str or a list of str, got " +
                             std::string(py::str(py::type::of(value).attr("__name__"))));
    std::vector<std::string> out;
    for (const py::handle item : value) out.push_back(text_arg(item, "clips[i]"));
    return out;
}

/// Counts the selected clips that give no window in a ShortClipsWarning.
void warn_short_clips(const workflow::WindowSampler& s) {
    const auto& ids = s.short_clip_ids();
    if (ids.empty()) return;
    const std::string message = std::to_string(ids.size()) + " of " + std::to_string(ids.size() + s.clip_ids().size()) +
                                " selected clips are shorter than the window (" + std::to_string(s.options().length) +
                                " frames) and give no windows, e.g. '" + ids.front() + "'";
    const py::object category = py::module_::import("mocapdb._core").attr("ShortClipsWarning");
    if (PyErr_WarnEx(category.ptr(), message.c_str(), 2) != 0) throw py::error_already_set();
}

Array batch_array(const SamplerHandle& h, std::size_t windows) {
    const auto& o = h.sampler->options();
    return Array({windows, o.length, h.sampler->values_per_frame()});
}

}  // namespace

void bind_sampler(py::module_& m) {
    py::class_<SamplerHandle, std::shared_ptr<SamplerHandle>>(
        m, "WindowSampler",
        "Random windows of consecutive source frames for training: batches (B, L, V) of pose vectors (V = D) "
        "or joint positions (V = 3 J, x y z per joint), each window in its own canonical frame (first frame's "
        "root at the origin facing +Z). Decoded from the packed tier when it holds every selected clip (within "
        "its max_error_cm), else from the lossless clips. The same database, options and seed give the same "
        "batches. An endless iterator of batches; one sampler per thread (from the packed tier a batch is "
        "made without the GIL, so other threads run meanwhile)." "\n\nExample:\n    >>> sampler = db.sampler(length=64, batch=32, seed=1)\n    >>> batch = next(sampler)              # (32, 64, D)")
        .def(py::init([](const DatabaseHandle& db, const py::object& length, const py::object& batch, const py::object& seed,
                         const py::object& values, const py::object& clips, const py::object& source,
                         const py::object& cache_clips) {
                 workflow::WindowSamplerOptions o;
                 o.length = integer_arg(length, "length", 1);
                 o.batch = integer_arg(batch, "batch", 1);
                 o.seed = integer_arg(seed, "seed", 0);
                 o.values = values_of(text_arg(values, "values"));
                 o.clips = clips_arg(clips);
                 o.source = source_of(text_arg(source, "source"));
                 o.cache_clips = integer_arg(cache_clips, "cache_clips", 1);
                 auto h = std::make_shared<SamplerHandle>();
                 db.get();  // refuses a closed database
                 h->db = db.db;
                 h->sampler = std::make_unique<workflow::WindowSampler>(*h->db, o);
                 warn_short_clips(*h->sampler);
                 return h;
             }),
             py::arg("db"), py::arg("length") = 64, py::arg("batch") = 32, py::arg("seed") = 0,
             py::arg("values") = "pose_vectors", py::arg("clips") = py::none(), py::arg("source") = "auto",
             py::arg("cache_clips") = 256,
             "length L frames per window, batch B windows, values 'pose_vectors' or 'joint_positions', clips: ids or "
             "fnmatch patterns (default every clip; they must share one rig and frame rate), source 'auto', "
             "'packed' or 'lossless'; cache_clips: lossless clips kept decoded.")
        .def(
            "next",
            [](SamplerHandle& h) {
                Array out = batch_array(h, h.sampler->options().batch);
                next_batch(h, out.mutable_data(), nullptr);
                return out;
            },
            "The next batch (B, L, V).")
        .def(
            "next_with_windows",
            [](SamplerHandle& h) {
                const std::size_t b = h.sampler->options().batch;
                Array out = batch_array(h, b);
                std::vector<workflow::WindowRef> refs(b);
                next_batch(h, out.mutable_data(), refs.data());
                py::list windows;
                for (const auto& r : refs) windows.append(py::make_tuple(h.sampler->clip_ids()[r.clip], r.begin));
                return py::make_tuple(out, windows);
            },
            "The next batch and where each window comes from: (array (B, L, V), [(clip name, first frame), ...]).")
        .def(
            "window",
            [](SamplerHandle& h, const std::string& clip, const py::object& first) {
                const std::size_t begin = integer_arg(first, "begin", 0);
                const std::lock_guard<std::mutex> lock(h.busy);
                const auto& ids = h.sampler->clip_ids();
                const auto it = std::find(ids.begin(), ids.end(), clip);
                if (it == ids.end()) throw py::key_error("window: clip '" + clip + "' is not among the sampler's clips");
                Array out({h.sampler->options().length, h.sampler->values_per_frame()});
                h.sampler->window({static_cast<std::size_t>(it - ids.begin()), begin}, out.mutable_data());
                return out;
            },
            py::arg("clip"), py::arg("begin"), "One given window (L, V): frames [begin, begin + L) of a clip.")
        .def("__iter__", [](const std::shared_ptr<SamplerHandle>& h) { return h; })
        .def("__next__", [](SamplerHandle& h) {
            Array out = batch_array(h, h.sampler->options().batch);
            next_batch(h, out.mutable_data(), nullptr);
            return out;
        })
        .def_property_readonly("length", [](const SamplerHandle& h) { return h.sampler->options().length; }, "L.")
        .def_property_readonly("batch", [](const SamplerHandle& h) { return h.sampler->options().batch; }, "B.")
        .def_property_readonly("values_per_frame", [](const SamplerHandle& h) { return h.sampler->values_per_frame(); }, "V.")
        .def_property_readonly("clips", [](const SamplerHandle& h) { return h.sampler->clip_ids(); },
                               "Names of the clips windows are drawn from (those with at least L frames).")
        .def_property_readonly("short_clips", [](const SamplerHandle& h) { return h.sampler->short_clip_ids(); },
                               "Names of the selected clips shorter than L frames: they give no windows (a "
                               "ShortClipsWarning counted them).")
        .def_property_readonly("window_count", [](const SamplerHandle& h) { return h.sampler->window_count(); },
                               "Distinct windows: sum over clips of F - L + 1.")
        .def_property_readonly("frame_rate", [](const SamplerHandle& h) { return h.sampler->frame_rate(); }, "Hz of the clips.")
        .def_property_readonly("from_packed", [](const SamplerHandle& h) { return h.sampler->from_packed(); },
                               "True when decoding from the packed tier.")
        .def_property_readonly("joint_names", [](const SamplerHandle& h) { return h.sampler->joint_names(); },
                               "The rig's joints: the order of joint_positions' triples.");
}

}  // namespace mocapdb::python
