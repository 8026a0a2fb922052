#include "mocapdb/io/gltf_writer.hpp"

#include <cstring>
#include <set>
#include <sstream>

#include <tiny_gltf.h>

#include "mocapdb/core/error.hpp"
#include "mocapdb/io/text_file.hpp"

namespace mocapdb {
namespace {

constexpr double kMetresPerCm = 0.01;

/// Appends float32 values to the one buffer as a new buffer view; returns its accessor.
class BufferBuilder {
public:
    explicit BufferBuilder(tinygltf::Model& m) : m_(m) { m_.buffers.emplace_back(); }

    int add(const std::vector<float>& values, int type, int components, bool min_max, int target = 0) {
        return add_bytes(values.data(), values.size() * sizeof(float), values.size() / components,
                         TINYGLTF_COMPONENT_TYPE_FLOAT, type, target,
                         min_max ? bounds(values, components) : std::pair<std::vector<double>, std::vector<double>>{});
    }
    int add_indices(const std::vector<std::uint16_t>& values) {
        return add_bytes(values.data(), values.size() * sizeof(std::uint16_t), values.size(),
                         TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_SCALAR,
                         TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER, {});
    }

private:
    static std::pair<std::vector<double>, std::vector<double>> bounds(const std::vector<float>& v, int components) {
        std::vector<double> lo(components, 1e300), hi(components, -1e300);
        for (std::size_t i = 0; i < v.size(); ++i) {
            const std::size_t c = i % static_cast<std::size_t>(components);
            lo[c] = std::min(lo[c], static_cast<double>(v[i]));
            hi[c] = std::max(hi[c], static_cast<double>(v[i]));
        }
        return {lo, hi};
    }
    int add_bytes(const void* data, std::size_t bytes, std::size_t count, int component, int type, int target,
                  std::pair<std::vector<double>, std::vector<double>> min_max) {
        auto& buffer = m_.buffers[0].data;
        while (buffer.size() % 4) buffer.push_back(0);
        tinygltf::BufferView view;
        view.buffer = 0;
        view.byteOffset = buffer.size();
        view.byteLength = bytes;
        view.target = target;
        buffer.resize(buffer.size() + bytes);
        std::memcpy(buffer.data() + view.byteOffset, data, bytes);
        m_.bufferViews.push_back(view);
        tinygltf::Accessor a;
        a.bufferView = static_cast<int>(m_.bufferViews.size() - 1);
        a.componentType = component;
        a.count = count;
        a.type = type;
        a.minValues = std::move(min_max.first);
        a.maxValues = std::move(min_max.second);
        m_.accessors.push_back(a);
        return static_cast<int>(m_.accessors.size() - 1);
    }
    tinygltf::Model& m_;
};

/// An octahedron from the origin to `tail` (the parent joint's frame, metres), 6 vertices, 8 faces.
void bone_shape(const Vec3& tail, std::vector<float>& positions, std::vector<std::uint16_t>& indices) {
    const double length = tail.norm();
    const Vec3 axis = tail / length;
    const Vec3 helper = std::abs(axis.y()) < 0.9 ? Vec3::UnitY() : Vec3::UnitX();
    const Vec3 u = axis.cross(helper).normalized() * (0.08 * length), v = axis.cross(u).normalized() * (0.08 * length);
    const Vec3 ring = 0.2 * tail;
    const Vec3 points[6] = {Vec3::Zero(), ring + u, ring + v, ring - u, ring - v, tail};
    for (const Vec3& p : points)
        for (int k = 0; k < 3; ++k) positions.push_back(static_cast<float>(p(k)));
    const std::uint16_t faces[24] = {0, 2, 1, 0, 3, 2, 0, 4, 3, 0, 1, 4, 5, 1, 2, 5, 2, 3, 5, 3, 4, 5, 4, 1};
    indices.assign(faces, faces + 24);
}

bool translates(const Joint& j) {
    for (ChannelType c : j.channels)
        if (!is_rotation(c)) return true;
    return false;
}

bool rotates(const Joint& j) {
    for (ChannelType c : j.channels)
        if (is_rotation(c)) return true;
    return false;  // no rotation channel: the local rotation is the identity (an ASF axis C · I · C⁻¹ too)
}

tinygltf::Model gltf_model(const Clip& clip) {
    const Skeleton& sk = *clip.skeleton;
    const std::size_t frames = clip.frame_count();
    if (frames == 0) throw InvalidArgument("glTF export: the clip '" + clip.name + "' has no frames");
    tinygltf::Model m;
    m.asset.version = "2.0";
    m.asset.generator = "mocapdb";
    BufferBuilder buffers(m);
    std::set<std::string> names;
    for (const Joint& j : sk.joints())
        if (!names.insert(gltf_node_name(j.name)).second)
            throw InvalidArgument("glTF export: two joints would both be named '" + gltf_node_name(j.name) + "'");

    // Joints: nodes 0..J-1 in skeleton order (parents first), rest translation = offset.
    for (std::size_t k = 0; k < sk.size(); ++k) {
        const Joint& j = sk.joint(k);
        tinygltf::Node n;
        n.name = gltf_node_name(j.name);
        const Vec3 t = sk.local_translation(k, clip.frame(0)) * kMetresPerCm;
        n.translation = {t.x(), t.y(), t.z()};
        if (rotates(j)) {
            const Quat q = sk.local_rotation(k, clip.frame(0));
            n.rotation = {q.x(), q.y(), q.z(), q.w()};
        }
        m.nodes.push_back(n);
        if (j.parent >= 0) m.nodes[static_cast<std::size_t>(j.parent)].children.push_back(static_cast<int>(k));
    }

    // Bone shapes: under each parent, towards each child's rest offset.
    tinygltf::Material material;
    material.name = "bone";
    material.pbrMetallicRoughness.baseColorFactor = {0.55, 0.6, 0.7, 1.0};
    m.materials.push_back(material);
    for (std::size_t k = 1; k < sk.size(); ++k) {
        const Joint& j = sk.joint(k);
        const Vec3 tail = j.offset * kMetresPerCm;
        if (tail.norm() < 1e-6) continue;
        std::vector<float> positions;
        std::vector<std::uint16_t> indices;
        bone_shape(tail, positions, indices);
        tinygltf::Primitive p;
        p.attributes["POSITION"] = buffers.add(positions, TINYGLTF_TYPE_VEC3, 3, true, TINYGLTF_TARGET_ARRAY_BUFFER);
        p.indices = buffers.add_indices(indices);
        p.material = 0;
        p.mode = TINYGLTF_MODE_TRIANGLES;
        tinygltf::Mesh mesh;
        mesh.primitives.push_back(p);
        m.meshes.push_back(mesh);
        tinygltf::Node shape;
        shape.name = kGltfBonePrefix + j.name;
        shape.mesh = static_cast<int>(m.meshes.size() - 1);
        m.nodes.push_back(shape);
        m.nodes[static_cast<std::size_t>(j.parent)].children.push_back(static_cast<int>(m.nodes.size() - 1));
    }

    // The animation: one time input, a sampler and channel per animated joint and path.
    std::vector<float> times(frames);
    for (std::size_t f = 0; f < frames; ++f) times[f] = static_cast<float>(static_cast<double>(f) / clip.frame_rate);
    const int input = buffers.add(times, TINYGLTF_TYPE_SCALAR, 1, true);
    tinygltf::Animation animation;
    animation.name = clip.name.empty() ? "motion" : clip.name;
    const auto channel = [&](std::size_t node, const char* path, const std::vector<float>& values, int type, int n) {
        tinygltf::AnimationSampler s;
        s.input = input;
        s.output = buffers.add(values, type, n, false);
        s.interpolation = "LINEAR";
        animation.samplers.push_back(s);
        tinygltf::AnimationChannel c;
        c.sampler = static_cast<int>(animation.samplers.size() - 1);
        c.target_node = static_cast<int>(node);
        c.target_path = path;
        animation.channels.push_back(c);
    };
    for (std::size_t k = 0; k < sk.size(); ++k) {
        const Joint& j = sk.joint(k);
        if (j.end_site) continue;
        if (rotates(j)) {
            std::vector<float> q(frames * 4);
            Quat previous = Quat::Identity();
            for (std::size_t f = 0; f < frames; ++f) {
                Quat r = sk.local_rotation(k, clip.frame(f));
                if (f > 0 && r.dot(previous) < 0.0) r.coeffs() = -r.coeffs();  // no flip: linear interpolation
                previous = r;
                const float v[4] = {static_cast<float>(r.x()), static_cast<float>(r.y()), static_cast<float>(r.z()),
                                    static_cast<float>(r.w())};
                std::memcpy(&q[4 * f], v, sizeof v);
            }
            channel(k, "rotation", q, TINYGLTF_TYPE_VEC4, 4);
        }
        if (translates(j)) {
            std::vector<float> t(frames * 3);
            for (std::size_t f = 0; f < frames; ++f) {
                const Vec3 p = sk.local_translation(k, clip.frame(f)) * kMetresPerCm;
                for (int c = 0; c < 3; ++c) t[3 * f + static_cast<std::size_t>(c)] = static_cast<float>(p(c));
            }
            channel(k, "translation", t, TINYGLTF_TYPE_VEC3, 3);
        }
    }
    if (!animation.channels.empty()) m.animations.push_back(animation);
    tinygltf::Scene scene;
    scene.name = clip.name;
    scene.nodes = {0};
    m.scenes.push_back(scene);
    m.defaultScene = 0;
    return m;
}

}  // namespace

std::string gltf_node_name(const std::string& joint) { return joint == "root" ? "root_joint" : joint; }

void write_gltf(std::ostream& out, const Clip& clip, GltfContainer container) {
    const tinygltf::Model model = gltf_model(clip);
    tinygltf::TinyGLTF writer;
    if (!writer.WriteGltfSceneToStream(&model, out, container == GltfContainer::Gltf, container == GltfContainer::Glb))
        throw IoError("the glTF writer failed for clip '" + clip.name + "'");
}

void write_gltf(const std::filesystem::path& path, const Clip& clip, GltfContainer container) {
    gltf_model(clip);  // the clip's errors before any file is touched
    write_file_atomically(path, [&](std::ostream& out) { write_gltf(out, clip, container); });
}

}  // namespace mocapdb
