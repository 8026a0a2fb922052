#pragma once
// Errors of the motion database file: every message names the file and the HDF5 path of the object
// concerned, and what was expected against what was found.
#include <string>

#include "mocapdb/core/error.hpp"

namespace mocapdb {

/// A database file that cannot be opened, read or written as the format requires (foreign file,
/// unsupported version, truncated file, wrong shape or dtype, failed HDF5 call).
/// what() reads "FILE: HDF5_PATH: MESSAGE" (the path part is omitted when no object is concerned).
class StoreError : public Error {
public:
    StoreError(std::string file, std::string object_path, const std::string& message);

    const std::string& file() const noexcept { return file_; }
    /// HDF5 path of the offending object ("/clips/16_15/channels"), or "" for the file as a whole.
    const std::string& object_path() const noexcept { return object_path_; }
    /// The message without the file and path.
    const std::string& message() const noexcept { return message_; }

private:
    std::string file_;
    std::string object_path_;
    std::string message_;
};

/// Stored bytes do not match their checksum (fletcher32): the file is corrupted at object_path().
class ChecksumError : public StoreError {
public:
    using StoreError::StoreError;
};

}  // namespace mocapdb
