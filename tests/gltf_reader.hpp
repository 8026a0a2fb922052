#pragma once
// Reading a glTF file back with a second, independent reader (Debian's assimp) for the export's round
// trip tests: world positions of every named node at every animation key, and the largest distance to
// our FK of the clip that was written.
#include <catch2/catch.hpp>

#include <assimp/Importer.hpp>
#include <assimp/scene.h>

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "mocapdb/io/gltf_writer.hpp"
#include "mocapdb/motion/forward_kinematics.hpp"

namespace mocapdb::test {


/// World positions (cm) of every named node of a glTF file at each of `frames` animation keys,
/// computed from assimp's scene: node transforms with the animation's keys applied (key f = frame f).
inline std::map<std::string, std::vector<Vec3>> gltf_world_positions(const std::filesystem::path& path,
                                                              std::size_t frames) {
    Assimp::Importer importer;
    const aiScene* scene = importer.ReadFile(path.string(), 0);
    REQUIRE(scene != nullptr);
    REQUIRE(scene->mNumAnimations == 1);
    const aiAnimation* animation = scene->mAnimations[0];
    std::map<std::string, const aiNodeAnim*> channels;
    for (unsigned c = 0; c < animation->mNumChannels; ++c)
        channels[animation->mChannels[c]->mNodeName.C_Str()] = animation->mChannels[c];
    std::map<std::string, std::vector<Vec3>> out;
    for (std::size_t f = 0; f < frames; ++f) {
        std::vector<std::pair<const aiNode*, aiMatrix4x4>> stack{{scene->mRootNode, aiMatrix4x4()}};
        while (!stack.empty()) {
            const auto [node, parent] = stack.back();
            stack.pop_back();
            aiMatrix4x4 local = node->mTransformation;
            const auto it = channels.find(node->mName.C_Str());
            if (it != channels.end()) {
                aiVector3D scaling, position;
                aiQuaternion rotation;
                local.Decompose(scaling, rotation, position);
                const aiNodeAnim* a = it->second;
                if (a->mNumPositionKeys > 1) {
                    REQUIRE(a->mNumPositionKeys == frames);
                    position = a->mPositionKeys[f].mValue;
                }
                if (a->mNumRotationKeys > 1) {
                    REQUIRE(a->mNumRotationKeys == frames);
                    rotation = a->mRotationKeys[f].mValue;
                }
                local = aiMatrix4x4(scaling, rotation, position);
            }
            const aiMatrix4x4 world = parent * local;
            out[node->mName.C_Str()].push_back(Vec3(world.a4, world.b4, world.c4) * 100.0);
            for (unsigned c = 0; c < node->mNumChildren; ++c) stack.push_back({node->mChildren[c], world});
        }
    }
    return out;
}


struct GltfDifference {
    double max_cm = 0.0;
    std::string where;  ///< joint and frame of the largest distance
};

/// The largest distance (cm) between the file's joint positions and the FK of `clip`, over every joint and
/// end site (by name) and every frame.
inline GltfDifference gltf_difference(const std::filesystem::path& path, const Clip& clip) {
    const auto read = gltf_world_positions(path, clip.frame_count());
    const Skeleton& sk = *clip.skeleton;
    GlobalPose pose;
    GltfDifference out;
    for (std::size_t f = 0; f < clip.frame_count(); ++f) {
        forward_kinematics(sk, clip.frame(f), pose);
        for (std::size_t j = 0; j < sk.size(); ++j) {
            const auto it = read.find(gltf_node_name(sk.joint(j).name));
            REQUIRE(it != read.end());
            const double d = (it->second[f] - pose.positions[j]).norm();
            if (d > out.max_cm) {
                out.max_cm = d;
                out.where = sk.joint(j).name + " at frame " + std::to_string(f);
            }
        }
    }
    return out;
}

}  // namespace mocapdb::test
