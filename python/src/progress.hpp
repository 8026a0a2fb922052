#pragma once
// A Python callable progress(done, total, item) as the library's ProgressCallback: called under the GIL
// (also from a call that released it), so a tqdm bar can be driven from it. The library's callbacks must
// not throw: the callable's first exception is kept, later reports are skipped, and rethrow() raises it
// once the library call has returned.
#include <exception>

#include "bindings.hpp"
#include "mocapdb/core/progress.hpp"

namespace mocapdb::python {

class PythonProgress {
public:
    /// callable: None (no reports) or a callable of (done: int, total: int, item: str); TypeError otherwise.
    explicit PythonProgress(py::object callable);
    /// Empty when the callable is None. Valid while this object lives.
    ProgressCallback callback();
    /// Raises the callable's first exception, if it raised one (call with the GIL held).
    void rethrow();

private:
    py::object callable_;
    std::exception_ptr error_;
};

}  // namespace mocapdb::python
