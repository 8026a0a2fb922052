// Synthesis models (Database.synthesis_model): poses, batched crowds, whole motions and the
// reliability at control parameters, numpy in and out.
#include "mocapdb/synthesis/synthesis_model.hpp"

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <memory>
#include <mutex>

#include "arrays.hpp"
#include "bindings.hpp"
#include "json_dict.hpp"
#include "mocapdb_json/synthesis_json.hpp"
#include "mocapdb/workflow/load_model.hpp"
#include "model_handle.hpp"

namespace mocapdb::python {
namespace {

VecX parameters_of(const ModelHandle& h, const Array& c) {
    return vector_view(c, h.model->parameters(), "control parameters");
}

/// Q by P (one row per character) from a (Q, P) array.
MatX characters_of(const ModelHandle& h, const Array& c) {
    return transposed_view(c, h.model->parameters(), "control parameters").transpose();
}

}  // namespace

std::shared_ptr<ModelHandle> load_model_handle(const Database& db, const std::string& set, bool naive,
                                               const ProgressCallback& fit_progress) {
    auto handle = std::make_shared<ModelHandle>();
    synthesis::SynthesisOptions options;
    options.fit_progress = fit_progress;
    if (naive) handle->model = workflow::load_naive_motion_model(db, set, options);
    else handle->model = workflow::load_motion_model(db, set, options);
    handle->path = db.path();
    handle->set = set;
    handle->naive = naive;
    return handle;
}

void bind_synthesis(py::module_& m) {
    py::class_<ModelHandle, std::shared_ptr<ModelHandle>>(
        m, "SynthesisModel",
        "A motion set's synthesis model (kriging of its samples at control parameters c). Immutable; "
        "every method may be called from several threads (the batched ones release the GIL)."
        "\n\nExample:\n    >>> model = db.synthesis_model('walks')\n    >>> poses = model.poses([[0.0, 1.2]], t=20.0)   # (1, D)")
        .def(py::pickle([](const ModelHandle& h) { return py::make_tuple(h.path, h.set, h.naive); },  // loaded again
                        [](const py::tuple& t) {
                            if (t.size() != 3) throw InvalidArgument("SynthesisModel: not a pickled model's state");
                            const Database db(t[0].cast<std::filesystem::path>());
                            return load_model_handle(db, t[1].cast<std::string>(), t[2].cast<bool>());
                        }))
        .def_property_readonly(
            "kind", [](const ModelHandle& h) { return std::string(h.model->kind()); },
            "'tucker' (the compressed model) or 'naive' (the uncompressed aligned tensor).")
        .def_property_readonly(
            "predictor",
            [](const ModelHandle& h) { return std::string(synthesis::to_string(h.model->report().predictor)); },
            "What blends the samples: 'kriging', 'rbf' or 'trend' (the one compress chose by cross-validation).")
        .def_property_readonly(
            "reliability_warning",
            [](const ModelHandle& h) -> py::object {
                const auto& w = h.model->kernel_fit().edge_warning;
                if (!w) return py::none();
                json::JsonWriter j;
                json::write_edge_warning(j, *w);
                return to_python(j.tree());
            },
            "Where the set's syntheses are flagged, as compress calibrated it (the reliability_warning of set "
            "show --json: variance_ratio, rho_threshold, beyond_sd, ...); None when the set has no calibration "
            "(then rho < 0.5 flags).")
        .def_property_readonly(
            "local_neighbours", [](const ModelHandle& h) { return h.model->report().local_neighbours; },
            "0 when every synthesis krigs all samples; else k, the nearest samples each request is kriged from "
            "(sets above the exact kriging's size).")
        .def_property_readonly(
            "dofs", [](const ModelHandle& h) { return h.model->dofs(); }, "D, values per pose vector.")
        .def_property_readonly(
            "frames", [](const ModelHandle& h) { return h.model->frames(); },
            "T, aligned frames: t ranges over [0, T - 1].")
        .def_property_readonly(
            "samples", [](const ModelHandle& h) { return h.model->samples(); }, "N, the set's samples.")
        .def_property_readonly(
            "parameter_names", [](const ModelHandle& h) { return h.model->parameter_names(); },
            "The P control parameters' names.")
        .def_property_readonly(
            "parameter_units", [](const ModelHandle& h) { return h.model->parameter_units(); }, "Their units.")
        .def_property_readonly(
            "sample_parameters", [](const ModelHandle& h) { return copy_rows(h.model->sample_parameters()); },
            "(N, P) parameters of the samples, in the set's units.")
        .def_property_readonly(
            "frame_rate", [](const ModelHandle& h) { return h.model->frame_rate(); },
            "Frame rate of synthesized motions (the set's).")
        .def_property_readonly(
            "skeleton", [](const ModelHandle& h) { return std::const_pointer_cast<Skeleton>(h.model->skeleton()); },
            "The set's Skeleton.")
        .def_property_readonly(
            "levels", [](const ModelHandle& h) { return h.model->levels(); }, "Levels of detail (level 0: full).")
        .def(
            "pose",
            [](const ModelHandle& h, const Array& c, double t, Eigen::Index level) {
                const VecX cv = parameters_of(h, c);
                VecX out(h.model->dofs());
                {
                    py::gil_scoped_release release;
                    synthesis::Workspace ws;
                    h.model->pose(cv, t, out, ws, level);
                }
                return copy_vector(out);
            },
            py::arg("c"), py::arg("t"), py::arg("level") = 0,
            "The pose vector (D,) at control parameters c (P,) and fractional aligned frame t in [0, T - 1], in "
            "the canonical frame."
            "\n\nExample:\n    >>> pose = model.pose(model.sample_parameters[0], t=10.5)   # (D,)")
        .def(
            "poses",
            [](ModelHandle& h, const Array& c, double t, Eigen::Index level) {
                const MatX characters = characters_of(h, c);
                Array out({static_cast<py::ssize_t>(characters.rows()), static_cast<py::ssize_t>(h.model->dofs())});
                Eigen::Map<MatX> poses(out.mutable_data(), h.model->dofs(), characters.rows());
                {
                    py::gil_scoped_release release;
                    // One workspace reused by calls that do not overlap; a concurrent call gets its own.
                    std::unique_lock<std::mutex> lock(h.batch_mutex, std::try_to_lock);
                    if (lock.owns_lock()) {
                        h.model->poses(characters, t, poses, h.batch, level);
                    } else {
                        synthesis::BatchWorkspace ws;
                        h.model->poses(characters, t, poses, ws, level);
                    }
                }
                return out;
            },
            py::arg("c"), py::arg("t"), py::arg("level") = 0,
            "Poses (Q, D) of Q characters with control parameters c (Q, P) at aligned frame t, in one batched "
            "call (the GIL is released)."
            "\n\nExample:\n    >>> poses = model.poses(model.sample_parameters, t=10.0)  # (N, D)")
        .def(
            "motion",
            [](const ModelHandle& h, const Array& c, Eigen::Index level) {
                const VecX cv = parameters_of(h, c);
                py::gil_scoped_release release;
                return std::make_shared<Clip>(h.model->motion(cv, level));
            },
            py::arg("c"), py::arg("level") = 0,
            "The synthesized motion at c as a Clip of the set's skeleton and frame rate, with its kriged "
            "timing (starts at the origin facing +Z; ready for write_bvh)."
            "\n\nExample:\n    >>> model.motion(model.sample_parameters[0]).write_bvh('walk.bvh')")
        .def(
            "reliability",
            [](const ModelHandle& h, const Array& c) -> py::object {
                if (c.ndim() == 1) return py::float_(h.model->reliability(parameters_of(h, c)));
                const MatX characters = characters_of(h, c);
                VecX rho;
                {
                    py::gil_scoped_release release;
                    rho = h.model->reliability_batch(characters);
                }
                return copy_vector(rho);
            },
            py::arg("c"),
            "Reliability rho(c) in [0, 1] (1 at a sample, falling where the samples do not support the "
            "result): a float for c of shape (P,), an array (Q,) for c of shape (Q, P)."
            "\n\nExample:\n    >>> rho = model.reliability(model.sample_parameters)   # (N,), 1 at the samples")
        .def(
            "variance_ratio",
            [](const ModelHandle& h, const Array& c) { return h.model->variance_ratio(parameters_of(h, c)); },
            py::arg("c"),
            "The prediction variance at c (P,) over the kernel's total sill, not clamped: rho = clamp(1 - it, 0, "
            "1). The calibrated warning flags above reliability_warning['variance_ratio']."
            "\n\nExample:\n    >>> model.variance_ratio(model.sample_parameters[0])   # ~0 at a sample")
        .def(
            "weights",
            [](const ModelHandle& h, const Array& c) {
                VecX w(h.model->samples());
                synthesis::Workspace ws;
                h.model->weights(parameters_of(h, c), w, ws);
                return copy_vector(w);
            },
            py::arg("c"),
            "Kriging weights (N,) of the samples at c (they sum to 1)."
            "\n\nExample:\n    >>> w = model.weights(model.sample_parameters[0])")
        .def(
            "timing",
            [](const ModelHandle& h, const Array& c) { return copy_vector(h.model->timing(parameters_of(h, c)).warp); },
            py::arg("c"),
            "The synthesized timing (T,): the source frame shown at each aligned frame (starts at 0)."
            "\n\nExample:\n    >>> warp = model.timing(model.sample_parameters[0])")
        .def("__repr__", [](const ModelHandle& h) {
            return "<mocapdb.SynthesisModel " + std::string(h.model->kind()) + ", " +
                   std::to_string(h.model->samples()) + " samples, " + std::to_string(h.model->frames()) + " frames, " +
                   std::to_string(h.model->dofs()) + " dofs>";
        });
}

}  // namespace mocapdb::python
