// mocapdb's errors as Python exceptions: one class per library error class, with the library's
// one-line message. InvalidArgument and ParseError are also ValueErrors, IoError an OSError, so that
// code catching the built-in classes keeps working.
#include <string>

#include "bindings.hpp"
#include "mocapdb/core/error.hpp"
#include "mocapdb/core/remedy.hpp"
#include "mocapdb/store/store_error.hpp"

namespace mocapdb::python {
namespace {

// The classes live as long as the module (it holds a reference to each).
PyObject* error_class = nullptr;
PyObject* invalid_argument_class = nullptr;
PyObject* parse_error_class = nullptr;
PyObject* io_error_class = nullptr;
PyObject* store_error_class = nullptr;
PyObject* checksum_error_class = nullptr;

PyObject* add_class(py::module_& m, const char* name, const char* doc, py::tuple bases) {
    const std::string qualified = std::string("mocapdb.") + name;
    PyObject* cls = PyErr_NewExceptionWithDoc(qualified.c_str(), doc, bases.ptr(), nullptr);
    if (cls == nullptr) throw py::error_already_set();
    m.add_object(name, py::handle(cls));  // the module takes its own reference; ours stays for the translator
    return cls;
}

// The library says what is wrong; Python adds the keyword or call that fixes it.
std::string with_hint(const Error& e) {
    std::string text = e.what();
    const auto* r = dynamic_cast<const Remediable*>(&e);
    if (r == nullptr) return text;
    switch (r->remedy()) {
        case Remedy::Overwrite: return text + "; pass replace=True to replace it";
        case Remedy::ReplaceFile: return text + "; force=True replaces the file with a new one";
        case Remedy::NameSkeletonFile: return text + "; pass asf=PATH";
        case Remedy::PackFirst: return text + "; run mocapdb.pack(db, max_error_cm=E) first";
        case Remedy::CompressFirst: return text + "; run mocapdb.compress(db, set) first";
        case Remedy::AlignFirst: return text + "; run mocapdb.align(db, set) first";
        case Remedy::GiveParameters: return text + "; create the set with extract= or params_csv=";
        case Remedy::ParametersOrExtract: return text + " (extract= or params_csv=)";
        case Remedy::Ranks: return text + " (ranks=)";
        case Remedy::Segmentation: return text + " (segment=)";
        case Remedy::Feet: return text + " (feet=[LEFT, RIGHT])";
    }
    return text;
}

void raise_parse_error(const ParseError& e) {
    py::object error = py::reinterpret_borrow<py::object>(parse_error_class)(e.what());
    error.attr("file") = e.file();
    error.attr("line") = e.line();
    error.attr("column") = e.column();
    PyErr_SetObject(parse_error_class, error.ptr());
}

}  // namespace

void bind_errors(py::module_& m) {
    error_class = add_class(m, "Error", "Base of every error mocapdb raises; str(e) is a complete one-line message.",
                            py::make_tuple(py::handle(PyExc_Exception)));
    py::handle error(error_class);
    invalid_argument_class = add_class(m, "InvalidArgument", "A documented precondition was broken (bad option, shape, name).",
                                       py::make_tuple(error, py::handle(PyExc_ValueError)));
    parse_error_class = add_class(m, "ParseError",
                                  "Malformed input text; str(e) reads FILE:LINE:COLUMN: MESSAGE, and e.file, e.line, "
                                  "e.column hold the location.",
                                  py::make_tuple(error, py::handle(PyExc_ValueError)));
    io_error_class = add_class(m, "IoError", "A file could not be opened, read or written.",
                               py::make_tuple(error, py::handle(PyExc_OSError)));
    store_error_class = add_class(m, "StoreError",
                                  "A database file is not what it should be; the message names the file and HDF5 path.",
                                  py::make_tuple(error));
    checksum_error_class = add_class(m, "ChecksumError", "A stored dataset's bytes fail their checksum (damage).",
                                     py::make_tuple(py::handle(store_error_class)));

    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const ChecksumError& e) {
            PyErr_SetString(checksum_error_class, with_hint(e).c_str());
        } catch (const StoreError& e) {
            PyErr_SetString(store_error_class, with_hint(e).c_str());
        } catch (const ParseError& e) {
            raise_parse_error(e);
        } catch (const IoError& e) {
            PyErr_SetString(io_error_class, with_hint(e).c_str());
        } catch (const InvalidArgument& e) {
            PyErr_SetString(invalid_argument_class, with_hint(e).c_str());
        } catch (const Error& e) {
            PyErr_SetString(error_class, with_hint(e).c_str());
        }
    });
}

}  // namespace mocapdb::python
