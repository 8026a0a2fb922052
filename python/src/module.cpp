// The compiled part of the `mocapdb` Python package (python/mocapdb/__init__.py re-exports it).
#include "bindings.hpp"
#include "mocapdb/core/version.hpp"

PYBIND11_MODULE(_core, m) {
    m.doc() =
        "mocapdb's C++ library: motion capture databases, clips, forward kinematics, synthesis, training windows.";
    m.attr("__version__") = mocapdb::version_string;
    mocapdb::python::bind_errors(m);
    mocapdb::python::bind_clips(m);
    mocapdb::python::bind_synthesis(m);
    mocapdb::python::bind_database(m);
    mocapdb::python::bind_sampler(m);
    mocapdb::python::bind_workflow(m);
}
