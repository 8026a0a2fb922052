#pragma once
// A set's Tucker model as the group /sets/{set}/model (format version 2, schemas/format-v2.md §8).
#include <string>

#include "h5/file.hpp"
#include "mocapdb/store/database.hpp"

namespace mocapdb::store {

/// Writes /sets/{set}/model (which must not exist). The caller has checked the model against the
/// aligned tensor (compression::check, D, T, N).
void write_model(h5::File& file, const std::string& set, const compression::SetModel& model,
                 const ModelFigures& figures);
/// Reads /sets/{set}/model. StoreError naming the offending object for a model without an aligned
/// tensor, wrong dtypes or shapes (D, T, N must equal the aligned tensor's, 1 <= R <= the mode's
/// dimension), unknown method or status, non-finite values or weights <= 0.
StoredModel read_model(const h5::File& file, const std::string& set);

/// Sum of the storage sizes of the model's datasets (0 when there is no model).
std::uint64_t model_stored_bytes(const h5::File& file, const std::string& set);

}  // namespace mocapdb::store
