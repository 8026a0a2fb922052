// mocapdb's errors as Python exceptions: one class per library error class, with the library's
// one-line message. InvalidArgument and ParseError are also ValueErrors, IoError an OSError, so that
// code catching the built-in classes keeps working.
#include <string>

#include "bindings.hpp"
#include "mocapdb/core/error.hpp"
#include "mocapdb/store/not_found_error.hpp"
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
PyObject* not_found_error_class = nullptr;

PyObject* add_class(py::module_& m, const char* name, const char* doc, py::tuple bases, py::dict members = py::dict()) {
    const std::string qualified = std::string("mocapdb.") + name;
    PyObject* cls = PyErr_NewExceptionWithDoc(qualified.c_str(), doc, bases.ptr(), members.ptr());
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
    error_class = add_class(
        m, "Error",
        "Base of every error mocapdb raises; str(e) is a complete one-line message."
        "\n\nExample:\n    >>> try:\n    ...     mocapdb.open('missing.h5')\n    ... except mocapdb.Error as e:\n    ...     print(e)",
        py::make_tuple(py::handle(PyExc_Exception)));
    py::handle error(error_class);
    invalid_argument_class = add_class(
        m, "InvalidArgument",
        "A documented precondition was broken (bad option, shape, name)."
        "\n\nExample:\n    >>> try:\n    ...     db.sampler(length=0)\n    ... except ValueError as e:   # mocapdb.InvalidArgument\n    ...     print(e)",
        py::make_tuple(error, py::handle(PyExc_ValueError)));
    parse_error_class = add_class(
        m, "ParseError",
        "Malformed input text; str(e) reads FILE:LINE:COLUMN: MESSAGE, and e.file, e.line, "
        "e.column hold the location."
        "\n\nExample:\n    >>> try:\n    ...     mocapdb.read_clip('broken.bvh')\n    ... except mocapdb.ParseError as e:\n    ...     print(e.file, e.line)",
        py::make_tuple(error, py::handle(PyExc_ValueError)));
    io_error_class = add_class(
        m, "IoError",
        "A file could not be opened, read or written."
        "\n\nExample:\n    >>> try:\n    ...     mocapdb.open('missing.h5')\n    ... except OSError as e:   # mocapdb.IoError\n    ...     print(e)",
        py::make_tuple(error, py::handle(PyExc_OSError)));
    store_error_class = add_class(
        m, "StoreError",
        "A database file is not what it should be; the message names the file and HDF5 path."
        "\n\nExample:\n    >>> try:\n    ...     mocapdb.open('not_a_database.h5')\n    ... except mocapdb.StoreError as e:\n    ...     print(e)",
        py::make_tuple(error));
    checksum_error_class = add_class(
        m, "ChecksumError",
        "A stored dataset's bytes fail their checksum (damage)."
        "\n\nExample:\n    >>> try:\n    ...     db.clip('16_11')\n    ... except mocapdb.ChecksumError as e:   # the file is damaged\n    ...     print(e)",
        py::make_tuple(py::handle(store_error_class)));
    not_found_error_class =
        add_class(m, "NotFoundError",
                  "A clip, motion set or skeleton name the database does not hold; also a KeyError.\n\n"
                  "Example:\n    >>> try:\n    ...     db.clip('no such clip')\n"
                  "    ... except KeyError as e:\n    ...     print(e)",
                  py::make_tuple(py::handle(store_error_class), py::handle(PyExc_KeyError)),
                  // str(e) is the message, not KeyError's quoted repr of it
                  py::dict(py::arg("__str__") = py::handle(PyExc_Exception).attr("__str__")));
    add_class(m, "ShortClipsWarning",
              "Some selected clips are shorter than a sampler's window and give no windows (the message counts "
              "them).\n\nExample:\n    >>> import warnings\n"
              "    >>> warnings.simplefilter('error', mocapdb.ShortClipsWarning)  # make it an error",
              py::make_tuple(py::handle(PyExc_UserWarning)));

    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const NotFoundError& e) {
            PyErr_SetString(not_found_error_class, e.what());
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
