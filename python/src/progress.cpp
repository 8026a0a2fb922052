#include "progress.hpp"

#include <string>
#include <utility>

namespace mocapdb::python {

PythonProgress::PythonProgress(py::object callable) : callable_(std::move(callable)) {
    if (!callable_.is_none() && !PyCallable_Check(callable_.ptr()))
        throw py::type_error("progress: expected None or a callable progress(done, total, item)");
}

ProgressCallback PythonProgress::callback() {
    if (callable_.is_none()) return {};
    return [this](const Progress& p) {
        py::gil_scoped_acquire gil;
        if (error_) return;
        try {
            callable_(p.done, p.total, std::string(p.item));
        } catch (...) {
            error_ = std::current_exception();
        }
    };
}

void PythonProgress::rethrow() {
    if (error_) std::rethrow_exception(std::exchange(error_, nullptr));
}

}  // namespace mocapdb::python
