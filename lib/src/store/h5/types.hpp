#pragma once
// Names of HDF5 datatypes as the schema and the error messages spell them.
#include <hdf5.h>

#include <string>

#include "handle.hpp"

namespace mocapdb::store::h5 {

/// "float64", "float32", "int8".."int64", "uint8".."uint64", "string" (variable-length),
/// "fixed-string", or "other (CLASS)".
std::string dtype_name(hid_t type);

/// A variable-length string datatype in character set `cset`.
Handle vlen_string_type(H5T_cset_t cset = H5T_CSET_UTF8);

}  // namespace mocapdb::store::h5
