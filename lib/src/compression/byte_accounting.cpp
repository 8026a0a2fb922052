#include "mocapdb/compression/byte_accounting.hpp"

namespace mocapdb::compression {

std::uint64_t aligned_float32_bytes(const Tensor3& poses) {
    return kFloat32 * static_cast<std::uint64_t>(poses.size());
}

std::uint64_t side_info_bytes(Eigen::Index frames, Eigen::Index samples, Eigen::Index parameters) {
    return kFloat32 * static_cast<std::uint64_t>(frames * samples + samples * parameters + 3 * samples);
}

std::uint64_t tucker_float32_bytes(const SetModel& model) {
    return kFloat32 * static_cast<std::uint64_t>(model.tucker.parameter_count() + 2 * model.dofs());
}

}  // namespace mocapdb::compression
