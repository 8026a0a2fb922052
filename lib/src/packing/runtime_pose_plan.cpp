#include "runtime_pose_plan.hpp"

#include <algorithm>
#include <cstring>
#include <string>

#include "mocapdb/core/error.hpp"

#include "channel_lanes.hpp"

namespace mocapdb::packing::detail {

std::size_t RuntimePosePlan::memory_bytes() const {
    std::size_t total = sizeof(*this) + basis.capacity() * sizeof(float);
    for (const Skeleton& s : skeletons) {
        total += sizeof(s) + s.inverse_weights.capacity() * sizeof(double) + s.rest_joints.capacity() * sizeof(int);
        for (const auto& lanes : s.lanes) total += lanes.capacity() * sizeof(PoseLanes);
    }
    return total;
}

void make_runtime_pose_plan(const GroupModel& m, bool allow_avx2, RuntimePosePlan& plan) {
    const int da = static_cast<int>(m.active.size()), dp = (da + 15) / 16 * 16;
    if (da > kRuntimeMaxDofs)
        throw InvalidArgument("runtime tier: " + std::to_string(da) + " active dofs in a group, expected at most " +
                              std::to_string(kRuntimeMaxDofs));
    plan.avx2 = allow_avx2 && pose_avx2_available();
    plan.avx512 = allow_avx2 && pose_avx512_available();
    plan.basis.assign(static_cast<std::size_t>(dp) * static_cast<std::size_t>(da), 0.0f);
    for (int c = 0; c < da; ++c)
        for (int r = 0; r < da; ++r)
            plan.basis[static_cast<std::size_t>(c * dp + r)] = static_cast<float>(m.dof_basis(r, c));
    plan.skeletons.clear();
    plan.skeletons.resize(m.skeletons.size());
    for (std::size_t e = 0; e < m.skeletons.size(); ++e) {
        RuntimePosePlan::Skeleton& sk = plan.skeletons[e];
        for (double w : m.skeletons[e].active_weights) sk.inverse_weights.push_back(1.0 / w);
        const auto view = m.skeletons[e].writer.local_view();
        const auto& joints = *view.joints;
        sk.root_projects = view.root_rotates && joints.front().present != 3;
        const std::size_t count[3] = {view.two_channel_joints, view.one_channel_joints,
                                      joints.size() - 1 - view.two_channel_joints - view.one_channel_joints};
        std::size_t first = 1;
        for (int kind = 0; kind < 3; ++kind) {
            for (std::size_t g = 0; 4 * g < count[kind]; ++g) {
                PoseLanes lanes;
                lanes.count = static_cast<int>(std::min<std::size_t>(4, count[kind] - 4 * g));
                TwoChannelLanes two;
                for (int l = 0; l < 4; ++l) {
                    const auto& j = joints[first + 4 * g + static_cast<std::size_t>(l < lanes.count ? l : 0)];
                    lanes.pose_row[l] = j.pose_row;
                    lanes.joint[l] = j.joint;
                    for (int r = 0; r < 3; ++r) {
                        for (int c = 0; c < 3; ++c) lanes.frame[3 * r + c][l] = j.euler_frame(r, c);
                        lanes.axis[r][l] = j.twist_axis[r];
                    }
                    if (kind == 0) set_lane(two, l, j.euler_frame, j.missing);
                }
                for (int l = 0; l < 4; ++l) {
                    lanes.missing[l] = two.missing[l];
                    lanes.dot[l] = two.dot[l];
                    for (int r = 0; r < 3; ++r) {
                        lanes.first[r][l] = two.first[r][l];
                        lanes.second[r][l] = two.second[r][l];
                        lanes.cross[r][l] = two.cross[r][l];
                    }
                }
                sk.lanes[kind].push_back(lanes);
            }
            first += count[kind];
        }
        std::vector<bool> written(view.rest_rotations->size(), false);
        written[view.motion_root] = view.root_rotates;
        for (const auto& kind : sk.lanes)
            for (const PoseLanes& lanes : kind)
                for (int l = 0; l < lanes.count; ++l) written[static_cast<std::size_t>(lanes.joint[l])] = true;
        for (std::size_t j = 0; j < written.size(); ++j)
            if (!written[j]) sk.rest_joints.push_back(static_cast<int>(j));
        PoseRoot& root = sk.root;
        root.joint = static_cast<int>(view.motion_root);
        root.rotates = view.root_rotates;
        root.adds = view.adds;
        std::memcpy(root.above_inverse, view.above_inverse.coeffs().data(), 4 * sizeof(double));
        for (int a = 0; a < 3; ++a) {
            root.translates[a] = view.root_translation[static_cast<std::size_t>(a)] >= 0 ? 1 : 0;
            root.above_position[a] = view.above_position[a];
            root.root_offset[a] = view.root_offset[a];
            root.offset[a] = (*view.offsets)[view.motion_root][a];
        }
    }
    // The kernels point into the plan (set once every vector has its final place).
    for (std::size_t e = 0; e < m.skeletons.size(); ++e) {
        RuntimePosePlan::Skeleton& sk = plan.skeletons[e];
        PoseKernel& k = sk.kernel;
        k.root = &sk.root;
        k.da = da;
        k.dp = dp;
        k.dofs = m.dofs;
        k.basis = plan.basis.data();
        k.inverse_weights = sk.inverse_weights.data();
        k.active = m.active.data();
        k.constant = m.constant.data();
        for (int kind = 0; kind < 3; ++kind) {
            k.lanes[kind] = sk.lanes[kind].data();
            k.groups[kind] = static_cast<int>(sk.lanes[kind].size());
        }
    }
}

void runtime_local_pose(const GroupModel& m, const RuntimePosePlan& plan, const ClipEntry& e, const double* y,
                        double* p, LocalPose& out) {
    const RuntimePosePlan::Skeleton& sk = plan.skeletons[e.skeleton];
    runtime_dofs(plan, e, y, p);
    const ChannelWriter& writer = m.skeletons[e.skeleton].writer;
    const auto v = writer.local_view();  // rest transforms
    const std::size_t n = writer.size();
    out.rotations.resize(n);
    out.translations.resize(n);
    static_assert(sizeof(Quat) == 4 * sizeof(double) && sizeof(Vec3) == 3 * sizeof(double),
                  "Quat: x, y, z, w; Vec3: x, y, z");
    // Rest translations (the motion root's is written below) and the rest rotations the kernels leave.
    std::memcpy(static_cast<void*>(out.translations.data()), v.rest_translations->data(), n * sizeof(Vec3));
    for (const int j : sk.rest_joints)
        out.rotations[static_cast<std::size_t>(j)] = (*v.rest_rotations)[static_cast<std::size_t>(j)];
    double placement[7];
    std::memcpy(placement, e.placement.heading.coeffs().data(), 4 * sizeof(double));
    std::memcpy(placement + 4, e.placement.translation.data(), 3 * sizeof(double));
    auto* rotations = reinterpret_cast<double*>(out.rotations.data());
    auto* translations = reinterpret_cast<double*>(out.translations.data());
    const bool ok = plan.avx512 ? pose_local_avx512(sk.kernel, placement, p, rotations, translations)
                    : plan.avx2 ? pose_local_avx2(sk.kernel, placement, p, rotations, translations)
                                : pose_local_portable(sk.kernel, placement, p, rotations, translations);
    if (!ok || sk.root_projects) {
        m.local_of(e, p, out);
        return;
    }
    for (std::size_t c = 0; c < m.extra_columns.size(); ++c)
        writer.set_position(m.extra_columns[c], p[static_cast<std::size_t>(m.pose_dofs) + c], out);
}

}  // namespace mocapdb::packing::detail
