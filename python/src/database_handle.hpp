#pragma once
// What the Python Database holds: a shared read view that close() lets go of. Objects made from it
// that read the file later (a WindowSampler) share the view, so closing the Database never leaves
// them reading a closed file.
#include <filesystem>
#include <memory>
#include <string>

#include "mocapdb/core/error.hpp"
#include "mocapdb/store/database.hpp"

namespace mocapdb::python {

struct DatabaseHandle {
    std::filesystem::path path;
    std::shared_ptr<const Database> db;

    const Database& get() const {
        if (!db) throw InvalidArgument(path.string() + ": the database was closed");
        return *db;
    }
};

}  // namespace mocapdb::python
