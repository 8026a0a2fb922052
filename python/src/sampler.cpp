// mocapdb.WindowSampler (Database.sampler): random training windows as numpy batches.
#include "mocapdb/workflow/window_sampler.hpp"

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

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
    py::dtype dtype;
    bool f32 = true;                      ///< dtype is float32 (read without the GIL)
    std::uint64_t epoch = 0, worker = 0;  ///< the stream (set_epoch)
    std::mutex busy;                      ///< batches of one sampler from several threads take turns
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

const char* values_name(workflow::WindowValues v) {
    return v == workflow::WindowValues::PoseVectors ? "pose_vectors" : "joint_positions";
}

const char* source_name(workflow::WindowSource s) {
    return s == workflow::WindowSource::Packed ? "packed" : s == workflow::WindowSource::Lossless ? "lossless" : "auto";
}

/// A Python integer (numpy's included, bool not) at least `minimum`: TypeError / InvalidArgument (a
/// ValueError) naming the argument otherwise, rather than pybind11's list of signatures.
std::uint64_t integer_arg(const py::handle& value, const char* name, std::uint64_t minimum) {
    if (PyBool_Check(value.ptr()) || !PyIndex_Check(value.ptr()))
        throw py::type_error(std::string("sampler: ") + name + " must be an integer, got " +
                             std::string(py::str(py::type::of(value).attr("__name__"))));
    const py::int_ number(py::reinterpret_steal<py::object>(PyNumber_Index(value.ptr())));
    if (number < py::int_(minimum))
        throw InvalidArgument(std::string("sampler: ") + name + " must be at least " + std::to_string(minimum) +
                              ", got " + std::string(py::str(static_cast<const py::object&>(number))));
    if (number > py::int_(std::numeric_limits<std::uint64_t>::max()))
        throw InvalidArgument(std::string("sampler: ") + name + " must be less than 2**64, got " +
                              std::string(py::str(static_cast<const py::object&>(number))));
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

/// float32 or float64 from anything numpy takes as a dtype (np.float32, "float64", ...).
py::dtype dtype_arg(const py::handle& value) {
    py::dtype d;
    try {
        d = py::dtype::from_args(py::reinterpret_borrow<py::object>(value));
    } catch (const py::error_already_set&) {
        throw py::type_error("sampler: dtype must be numpy.float32 or numpy.float64, got " +
                             std::string(py::repr(value)));
    }
    if (!d.is(py::dtype::of<float>()) && !d.equal(py::dtype::of<float>()) && !d.equal(py::dtype::of<double>()))
        throw InvalidArgument("sampler: dtype must be float32 or float64, got " +
                              std::string(py::str(static_cast<const py::object&>(d))));
    return d;
}

bool single(const SamplerHandle& h) { return h.f32; }

/// A new batch array (windows, L, V) of the sampler's dtype, or `out` checked to be one.
py::array batch_array(const SamplerHandle& h, const py::object& out) {
    const auto& o = h.sampler->options();
    const std::vector<py::ssize_t> shape{static_cast<py::ssize_t>(o.batch), static_cast<py::ssize_t>(o.length),
                                         static_cast<py::ssize_t>(h.sampler->values_per_frame())};
    if (out.is_none()) return py::array(h.dtype, shape);
    if (!py::isinstance<py::array>(out)) throw py::type_error("next: out must be a numpy array");
    py::array a = py::reinterpret_borrow<py::array>(out);
    if (!a.dtype().equal(h.dtype) || a.ndim() != 3 || a.shape(0) != shape[0] || a.shape(1) != shape[1] ||
        a.shape(2) != shape[2] || !(a.flags() & py::array::c_style) || !a.writeable())
        throw InvalidArgument("next: out must be a writeable C-contiguous " +
                              std::string(py::str(static_cast<const py::object&>(h.dtype))) + " array of shape (" +
                              std::to_string(shape[0]) + ", " + std::to_string(shape[1]) + ", " +
                              std::to_string(shape[2]) + ")");
    return a;
}

/// The next batch into out (B x L x V of the sampler's dtype) and refs (B entries). The draw reads the
/// (not thread-safe) database under the GIL; the windows are written from decoded clips without it.
void next_batch(SamplerHandle& h, py::array& out, workflow::WindowRef* refs) {
    void* data = out.mutable_data();
    const std::size_t b = h.sampler->options().batch;
    py::gil_scoped_release release;
    const std::lock_guard<std::mutex> lock(h.busy);  // taken without the GIL: no deadlock with a waiting thread
    {
        py::gil_scoped_acquire acquire;
        h.sampler->draw(refs);
    }
    if (single(h)) h.sampler->fill(refs, b, static_cast<float*>(data));
    else h.sampler->fill(refs, b, static_cast<double*>(data));
}

/// Pickle's state: the database's path (reopened read-only), the options, the stream and its position.
py::tuple sampler_state(const SamplerHandle& h) {
    const auto& o = h.sampler->options();
    return py::make_tuple(h.db->path(), o.length, o.batch, o.seed, values_name(o.values), o.clips,
                          source_name(o.source), o.cache_clips, h.f32 ? "float32" : "float64", h.epoch, h.worker,
                          py::bytes(h.sampler->stream_state()), o.pad);
}

std::shared_ptr<SamplerHandle> sampler_from_state(const py::tuple& t) {
    if (t.size() != 13) throw InvalidArgument("WindowSampler: not a pickled sampler's state");
    workflow::WindowSamplerOptions o;
    o.length = t[1].cast<std::size_t>();
    o.batch = t[2].cast<std::size_t>();
    o.seed = t[3].cast<std::uint64_t>();
    o.values = values_of(t[4].cast<std::string>());
    o.clips = t[5].cast<std::vector<std::string>>();
    o.source = source_of(t[6].cast<std::string>());
    o.cache_clips = t[7].cast<std::size_t>();
    o.pad = t[12].cast<bool>();
    auto h = std::make_shared<SamplerHandle>();
    h->dtype = dtype_arg(t[8]);
    h->f32 = h->dtype.equal(py::dtype::of<float>());
    o.dtype = h->f32 ? workflow::WindowDType::Float32 : workflow::WindowDType::Float64;
    h->db = std::make_shared<const Database>(t[0].cast<std::filesystem::path>());
    h->sampler = std::make_unique<workflow::WindowSampler>(*h->db, o);
    h->epoch = t[9].cast<std::uint64_t>();
    h->worker = t[10].cast<std::uint64_t>();
    h->sampler->set_stream_state(t[11].cast<std::string>());
    return h;
}

py::array next_array(SamplerHandle& h, const py::object& out) {
    py::array batch = batch_array(h, out);
    std::vector<workflow::WindowRef> refs(h.sampler->options().batch);
    next_batch(h, batch, refs.data());
    return batch;
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
        "made without the GIL, so other threads run meanwhile)."
        "\n\nExample:\n    >>> sampler = db.sampler(length=64, batch=32, seed=1)\n    >>> batch = next(sampler)              # (32, 64, D)")
        .def(
            py::init([](const DatabaseHandle& db, const py::object& length, const py::object& batch,
                        const py::object& seed, const py::object& values, const py::object& clips,
                        const py::object& source, const py::object& cache_clips, const py::object& dtype,
                        const py::object& pad) {
                workflow::WindowSamplerOptions o;
                o.length = integer_arg(length, "length", 1);
                o.batch = integer_arg(batch, "batch", 1);
                o.seed = integer_arg(seed, "seed", 0);
                o.values = values_of(text_arg(values, "values"));
                o.clips = clips_arg(clips);
                o.source = source_of(text_arg(source, "source"));
                o.cache_clips = integer_arg(cache_clips, "cache_clips", 1);
                if (!PyBool_Check(pad.ptr()))
                    throw py::type_error("sampler: pad must be True or False, got " +
                                         std::string(py::str(py::type::of(pad).attr("__name__"))));
                o.pad = pad.cast<bool>();
                auto h = std::make_shared<SamplerHandle>();
                h->dtype = dtype_arg(dtype);
                h->f32 = h->dtype.equal(py::dtype::of<float>());
                o.dtype = single(*h) ? workflow::WindowDType::Float32 : workflow::WindowDType::Float64;
                db.get();  // refuses a closed database
                h->db = db.db;
                h->sampler = std::make_unique<workflow::WindowSampler>(*h->db, o);
                if (!o.pad) warn_short_clips(*h->sampler);
                return h;
            }),
            py::arg("db"), py::arg("length") = 64, py::arg("batch") = 32, py::arg("seed") = 0,
            py::arg("values") = "pose_vectors", py::arg("clips") = py::none(), py::arg("source") = "auto",
            py::arg("cache_clips") = 256, py::arg("dtype") = py::dtype::of<float>(), py::arg("pad") = false,
            "length L frames per window, batch B windows, values 'pose_vectors' or 'joint_positions', clips: ids or "
            "fnmatch patterns (default every clip; they must share one rig and frame rate), source 'auto', "
            "'packed' or 'lossless'; cache_clips: clips kept decoded (at least batch); dtype: numpy.float32 (default) or "
            "numpy.float64, the batches' and the decoded clips' element type; pad: clips shorter than L give one window "
            "each, from frame 0, its missing rows repeating the clip's last frame (else they give none and a "
            "ShortClipsWarning counts them).")
        .def("next", &next_array, py::arg("out") = py::none(),
             "The next batch (B, L, V) of the sampler's dtype, written into `out` when given (an array of that "
             "shape and dtype, reused across batches) or into a new array.\n\nExample:\n"
             "    >>> out = np.empty((sampler.batch, sampler.length, sampler.values_per_frame), np.float32)\n"
             "    >>> sampler.next(out=out) is out")
        .def(
            "next_with_windows",
            [](SamplerHandle& h) {
                const std::size_t b = h.sampler->options().batch;
                py::array out = batch_array(h, py::none());
                std::vector<workflow::WindowRef> refs(b);
                next_batch(h, out, refs.data());
                py::list windows;
                for (const auto& r : refs) windows.append(py::make_tuple(h.sampler->clip_ids()[r.clip], r.begin));
                return py::make_tuple(out, windows);
            },
            "The next batch and where each window comes from: (array (B, L, V), [(clip name, first frame), ...])."
            "\n\nExample:\n    >>> batch, windows = sampler.next_with_windows()")
        .def(
            "window",
            [](SamplerHandle& h, const std::string& clip, const py::object& first) {
                const std::size_t begin = integer_arg(first, "begin", 0);
                std::unique_lock<std::mutex> lock(h.busy, std::defer_lock);
                {
                    py::gil_scoped_release release;  // wait for another thread's batch without the GIL
                    lock.lock();
                }
                const auto& ids = h.sampler->clip_ids();
                const auto it = std::find(ids.begin(), ids.end(), clip);
                if (it == ids.end())
                    throw py::key_error("window: clip '" + clip + "' is not among the sampler's clips");
                py::array out(h.dtype,
                              std::vector<py::ssize_t>{static_cast<py::ssize_t>(h.sampler->options().length),
                                                       static_cast<py::ssize_t>(h.sampler->values_per_frame())});
                const workflow::WindowRef ref{static_cast<std::size_t>(it - ids.begin()), begin};
                if (single(h)) h.sampler->window(ref, static_cast<float*>(out.mutable_data()));
                else h.sampler->window(ref, static_cast<double*>(out.mutable_data()));
                return out;
            },
            py::arg("clip"), py::arg("begin"),
            "One given window (L, V): frames [begin, begin + L) of a clip; KeyError for a clip not among clips."
            "\n\nExample:\n    >>> w = sampler.window(sampler.clips[0], 10)")
        .def(
            "windows",
            [](SamplerHandle& h,
               const py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>& clip_indices,
               const py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>& begins) {
                if (clip_indices.ndim() != 1 || begins.ndim() != 1 || clip_indices.shape(0) != begins.shape(0))
                    throw InvalidArgument("windows: expected two 1-D integer arrays of one length");
                const std::size_t n = static_cast<std::size_t>(begins.shape(0)), clips = h.sampler->clip_ids().size();
                std::vector<workflow::WindowRef> refs(n);
                for (std::size_t i = 0; i < n; ++i) {
                    const std::int64_t c = clip_indices.at(static_cast<py::ssize_t>(i)),
                                       b = begins.at(static_cast<py::ssize_t>(i));
                    if (c < 0 || static_cast<std::size_t>(c) >= clips || b < 0)
                        throw InvalidArgument("windows: window " + std::to_string(i) + " (clip " + std::to_string(c) +
                                              ", frame " + std::to_string(b) + ") is not one of the sampler's");
                    refs[i] = {static_cast<std::size_t>(c), static_cast<std::size_t>(b)};
                }
                const std::size_t L = h.sampler->options().length, V = h.sampler->values_per_frame();
                py::array out(h.dtype,
                              std::vector<py::ssize_t>{static_cast<py::ssize_t>(n), static_cast<py::ssize_t>(L),
                                                       static_cast<py::ssize_t>(V)});
                char* data = static_cast<char*>(out.mutable_data());
                const std::size_t chunk = h.sampler->options().batch,
                                  bytes = L * V * static_cast<std::size_t>(h.dtype.itemsize());
                py::gil_scoped_release release;
                const std::lock_guard<std::mutex> lock(h.busy);
                for (std::size_t i = 0; i < n; i += chunk) {
                    const std::size_t k = std::min(chunk, n - i);
                    {
                        py::gil_scoped_acquire acquire;
                        h.sampler->load(refs.data() + i, k);
                    }
                    if (single(h)) h.sampler->fill(refs.data() + i, k, reinterpret_cast<float*>(data + i * bytes));
                    else h.sampler->fill(refs.data() + i, k, reinterpret_cast<double*>(data + i * bytes));
                }
                return out;
            },
            py::arg("clip_indices"), py::arg("begins"),
            "Given windows (N, L, V): window i is frames [begins[i], begins[i] + L) of clip clips[clip_indices[i]] "
            "(what a dataset without repeats asks for).\n\nExample:\n"
            "    >>> sampler.windows([0, 0, 1], [0, 10, 5]).shape   # (3, L, V)")
        .def_property_readonly(
            "window_counts", [](const SamplerHandle& h) { return h.sampler->window_counts(); },
            "Windows each clip offers (F - L + 1), in the order of clips.")
        .def(
            "set_epoch",
            [](SamplerHandle& h, const py::object& epoch, const py::object& worker) {
                const std::uint64_t e = integer_arg(epoch, "epoch", 0), w = integer_arg(worker, "worker", 0);
                py::gil_scoped_release release;  // a thread holding the lock may be waiting for the GIL
                const std::lock_guard<std::mutex> lock(h.busy);
                h.sampler->set_stream(e, w);
                h.epoch = e;
                h.worker = w;
            },
            py::arg("epoch"), py::arg("worker") = 0,
            "Restarts the draw on the stream of (seed, epoch, worker): the same three give the same batches, "
            "another epoch or worker other ones (a data loader's workers each take their own). A new sampler "
            "draws stream (seed, 0, 0).\n\nExample:\n    >>> sampler.set_epoch(3, worker=1)\n"
            "    >>> batch = sampler.next()   # the first batch of epoch 3 for worker 1")
        .def_property_readonly(
            "epoch", [](const SamplerHandle& h) { return h.epoch; }, "The epoch of set_epoch (0 at first).")
        .def_property_readonly(
            "worker", [](const SamplerHandle& h) { return h.worker; }, "The worker of set_epoch (0 at first).")
        .def(py::pickle(&sampler_state, &sampler_from_state))
        .def("__iter__", [](const std::shared_ptr<SamplerHandle>& h) { return h; })
        .def("__next__", [](SamplerHandle& h) { return next_array(h, py::none()); })
        .def_property_readonly(
            "dtype", [](const SamplerHandle& h) { return h.dtype; }, "The batches' numpy dtype.")
        .def_property_readonly(
            "cache_bytes", [](const SamplerHandle& h) { return h.sampler->cache_bytes(); },
            "Bytes held by the decoded clips now (each drawn clip is decoded once, whole).")
        .def_property_readonly(
            "length", [](const SamplerHandle& h) { return h.sampler->options().length; }, "L.")
        .def_property_readonly(
            "batch", [](const SamplerHandle& h) { return h.sampler->options().batch; }, "B.")
        .def_property_readonly(
            "values_per_frame", [](const SamplerHandle& h) { return h.sampler->values_per_frame(); }, "V.")
        .def_property_readonly(
            "clips", [](const SamplerHandle& h) { return h.sampler->clip_ids(); },
            "Names of the clips windows are drawn from (those with at least L frames).")
        .def_property_readonly(
            "short_clips", [](const SamplerHandle& h) { return h.sampler->short_clip_ids(); },
            "Names of the selected clips shorter than L frames: they give no windows (a "
            "ShortClipsWarning counted them), or with pad=True one padded window each.")
        .def_property_readonly(
            "window_count", [](const SamplerHandle& h) { return h.sampler->window_count(); },
            "Distinct windows: sum over clips of F - L + 1.")
        .def_property_readonly(
            "frame_rate", [](const SamplerHandle& h) { return h.sampler->frame_rate(); }, "Hz of the clips.")
        .def_property_readonly(
            "from_packed", [](const SamplerHandle& h) { return h.sampler->from_packed(); },
            "True when decoding from the packed tier.")
        .def_property_readonly(
            "joint_names", [](const SamplerHandle& h) { return h.sampler->joint_names(); },
            "The rig's joints: the order of joint_positions' triples.");
}

}  // namespace mocapdb::python
