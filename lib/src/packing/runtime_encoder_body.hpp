#pragma once
// The runtime encoder's entry for the packing module (internal): encode_runtime without the bytes of a
// format-3 group, for pack_group's runtime format, which builds the model itself.
#include <vector>

#include "mocapdb/packing/runtime_encoder.hpp"
#include "group_model.hpp"

namespace mocapdb::packing::detail {

/// The body of model m (as read back from its header: the decoder's view) for its clips, in m's order;
/// options checked by the caller. Errors as encode_runtime's.
RuntimeBody encode_runtime_body(const GroupModel& m, const std::vector<const Clip*>& clips, const RuntimeOptions& o);

}  // namespace mocapdb::packing::detail
