#pragma once
// What the Python SynthesisModel holds: the immutable model and one batch workspace that calls which
// do not overlap reuse (poses() allocates nothing then).
#include <filesystem>
#include <memory>
#include <mutex>
#include <string>

#include "mocapdb/store/database.hpp"
#include "mocapdb/synthesis/synthesis_model.hpp"

namespace mocapdb::python {

struct ModelHandle {
    std::shared_ptr<const synthesis::SynthesisModel> model;
    // Where it was loaded from: a pickled model is loaded again from there (read-only).
    std::filesystem::path path;
    std::string set;
    bool naive = false;
    std::mutex batch_mutex;
    synthesis::BatchWorkspace batch;
};

/// The set's model from the database at `path` (naive: kriging of the aligned tensor).
std::shared_ptr<ModelHandle> load_model_handle(const Database& db, const std::string& set, bool naive,
                                               const ProgressCallback& fit_progress = {});

}  // namespace mocapdb::python
