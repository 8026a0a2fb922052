#pragma once
// HDF5 error handling: HDF5's own printing is silenced while our code runs, and every failed call
// becomes a StoreError (or ChecksumError) naming the file and the HDF5 path.
#include <hdf5.h>

#include <string>

namespace mocapdb::store::h5 {

/// HDF5's current error stack as one line, most specific message first, then clears the stack.
std::string take_error_stack();

/// Throws StoreError(file, path, what + HDF5's reason); ChecksumError with "checksum mismatch in
/// dataset PATH" when HDF5 reports a failed checksum.
[[noreturn]] void fail_call(const std::string& file, const std::string& path, const std::string& what);
/// Throws StoreError(file, path, message) without consulting HDF5's error stack.
[[noreturn]] void fail(const std::string& file, const std::string& path, const std::string& message);

/// Returns `result`, or fails (fail_call) when it is negative.
template <class T>
T check(T result, const std::string& file, const std::string& path, const char* what) {
    if (result < 0) fail_call(file, path, what);
    return result;
}

}  // namespace mocapdb::store::h5
