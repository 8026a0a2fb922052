#pragma once
// A name the caller asked for (clip id, motion set, skeleton id) is not in the database: a StoreError
// (what() reads "FILE: HDF5_PATH: no such ...") that callers can tell from damage, e.g. to map it to
// a lookup error (Python's KeyError).
#include "mocapdb/store/store_error.hpp"

namespace mocapdb {

class NotFoundError : public StoreError {
public:
    using StoreError::StoreError;
};

}  // namespace mocapdb
