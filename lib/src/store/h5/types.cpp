// Names of HDF5 datatypes and shapes as the schema and the error messages spell them.
#include <string>

#include "file.hpp"
#include "types.hpp"
#include "errors.hpp"

namespace mocapdb::store::h5 {

std::string dtype_name(hid_t type) {
    const H5T_class_t cls = H5Tget_class(type);
    const std::size_t bits = 8 * H5Tget_size(type);
    switch (cls) {
        case H5T_FLOAT: return "float" + std::to_string(bits);
        case H5T_INTEGER: return (H5Tget_sign(type) == H5T_SGN_NONE ? "uint" : "int") + std::to_string(bits);
        case H5T_STRING: return H5Tis_variable_str(type) > 0 ? "string" : "fixed-string";
        case H5T_COMPOUND: return "other (compound)";
        case H5T_ENUM: return "other (enum)";
        case H5T_ARRAY: return "other (array)";
        case H5T_VLEN: return "other (vlen)";
        case H5T_OPAQUE: return "other (opaque)";
        case H5T_REFERENCE: return "other (reference)";
        case H5T_BITFIELD: return "other (bitfield)";
        case H5T_TIME: return "other (time)";
        default: return "other (unknown class)";
    }
}

std::string shape_text(const Shape& shape) {
    if (shape.empty()) return "scalar";
    std::string out = "(";
    for (std::size_t i = 0; i < shape.size(); ++i) {
        if (i) out += ", ";
        out += std::to_string(shape[i]);
    }
    return out + (shape.size() == 1 ? ",)" : ")");
}

Handle vlen_string_type(H5T_cset_t cset) {
    Handle t(H5Tcopy(H5T_C_S1), H5Tclose);
    if (!t.valid() || H5Tset_size(t.get(), H5T_VARIABLE) < 0 || H5Tset_cset(t.get(), cset) < 0)
        fail_call("", "", "cannot make a string datatype");
    return t;
}

}  // namespace mocapdb::store::h5
