#pragma once
// The Python module's parts (one concept per file), registered by module.cpp in this order: errors
// first (the others' functions throw them), then the types the later parts return.
//
// Conventions of the whole module:
//   - arrays are numpy float64, C order, frames first: channels (F, C), pose vectors (F, D), joint
//     positions (F, J, 3); the library's column-major D x F matrices have that very memory layout;
//   - every library error becomes the mocapdb exception of its class with the library's one-line
//     message (errors.cpp);
//   - long computations release the GIL; objects that are not thread-safe in C++ (Database,
//     WindowSampler) are guarded by the GIL (their methods keep it).
#include <pybind11/pybind11.h>

namespace mocapdb::python {

namespace py = pybind11;

void bind_errors(py::module_& m);
void bind_clips(py::module_& m);
void bind_synthesis(py::module_& m);
void bind_database(py::module_& m);
void bind_sampler(py::module_& m);
void bind_workflow(py::module_& m);

}  // namespace mocapdb::python
