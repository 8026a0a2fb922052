#pragma once
// What the Python SynthesisModel holds: the immutable model and one batch workspace that calls which
// do not overlap reuse (poses() allocates nothing then).
#include <memory>
#include <mutex>

#include "mocapdb/synthesis/synthesis_model.hpp"

namespace mocapdb::python {

struct ModelHandle {
    std::shared_ptr<const synthesis::SynthesisModel> model;
    std::mutex batch_mutex;
    synthesis::BatchWorkspace batch;
};

}  // namespace mocapdb::python
