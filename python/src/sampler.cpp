// mocapdb.WindowSampler (Database.sampler): random training windows as numpy batches.
#include "mocapdb/workflow/window_sampler.hpp"

#include <pybind11/stl.h>

#include <algorithm>
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
        "made without the GIL, so other threads run meanwhile).")
        .def(py::init([](const DatabaseHandle& db, std::size_t length, std::size_t batch, std::uint64_t seed,
                         const std::string& values, std::optional<std::vector<std::string>> clips, const std::string& source,
                         std::size_t cache_clips) {
                 workflow::WindowSamplerOptions o;
                 o.length = length;
                 o.batch = batch;
                 o.seed = seed;
                 o.values = values_of(values);
                 if (clips) o.clips = *clips;
                 o.source = source_of(source);
                 o.cache_clips = cache_clips;
                 auto h = std::make_shared<SamplerHandle>();
                 db.get();  // refuses a closed database
                 h->db = db.db;
                 h->sampler = std::make_unique<workflow::WindowSampler>(*h->db, o);
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
            [](SamplerHandle& h, const std::string& clip, std::size_t begin) {
                const std::lock_guard<std::mutex> lock(h.busy);
                const auto& ids = h.sampler->clip_ids();
                const auto it = std::find(ids.begin(), ids.end(), clip);
                if (it == ids.end()) throw InvalidArgument("window: clip '" + clip + "' is not among the sampler's clips");
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
        .def_property_readonly("window_count", [](const SamplerHandle& h) { return h.sampler->window_count(); },
                               "Distinct windows: sum over clips of F - L + 1.")
        .def_property_readonly("frame_rate", [](const SamplerHandle& h) { return h.sampler->frame_rate(); }, "Hz of the clips.")
        .def_property_readonly("from_packed", [](const SamplerHandle& h) { return h.sampler->from_packed(); },
                               "True when decoding from the packed tier.")
        .def_property_readonly("joint_names", [](const SamplerHandle& h) { return h.sampler->joint_names(); },
                               "The rig's joints: the order of joint_positions' triples.");
}

}  // namespace mocapdb::python
