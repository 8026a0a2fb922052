#pragma once
// The runtime encoder's entry for the packing module (internal): encode_runtime without the bytes of a
// format-3 group, for pack_group's runtime format, which builds the model itself.
#include <functional>
#include <vector>

#include "mocapdb/packing/runtime_encoder.hpp"
#include "group_model.hpp"

namespace mocapdb::packing::detail {

/// The body of model m (as read back from its header: the decoder's view) for its clips, in m's order;
/// options checked by the caller. Errors as encode_runtime's.
/// clip_done(i, passes): clip i done in one of `passes` encodes (two when W is chosen), from the workers.
RuntimeBody encode_runtime_body(const GroupModel& m, const std::vector<const Clip*>& clips, const RuntimeOptions& o,
                                const std::function<void(std::size_t, int)>& clip_done = {});

}  // namespace mocapdb::packing::detail
