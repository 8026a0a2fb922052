#include "store_test_support.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <random>
#include <sstream>
#include <stdexcept>

#include "mocapdb/motion/pose_vector.hpp"
#include "mocapdb/store/sha256.hpp"
#include "shared_data.hpp"

namespace mocapdb::test {

std::string all_violations(const ValidationReport& r) {
    std::string out;
    for (const Violation& v : r.violations) out += v.path + ": " + v.message + "\n";
    return out;
}

bool has_violation(const ValidationReport& r, const std::string& path, const std::string& text) {
    for (const Violation& v : r.violations)
        if (v.path == path && v.message.find(text) != std::string::npos) return true;
    return false;
}

void flip_bytes(const std::filesystem::path& file, std::uint64_t offset, std::size_t count) {
    std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
    if (!f) throw std::runtime_error("flip_bytes: cannot open " + file.string());
    for (std::size_t k = 0; k < count; ++k) {
        f.seekg(static_cast<std::streamoff>(offset + k));
        char c = 0;
        f.read(&c, 1);
        c = static_cast<char>(~c);
        f.seekp(static_cast<std::streamoff>(offset + k));
        f.write(&c, 1);
    }
}

Clip synthetic_clip(std::size_t frames, std::size_t joints, unsigned seed, double frame_rate) {
    std::vector<Joint> js;
    Joint root;
    root.name = "root";
    root.channels = {ChannelType::Xposition, ChannelType::Yposition, ChannelType::Zposition,
                     ChannelType::Zrotation, ChannelType::Xrotation, ChannelType::Yrotation};
    root.rotation_order = EulerOrder::ZXY;
    root.offset = Vec3(0.0, 90.0, 0.0);
    js.push_back(root);
    for (std::size_t j = 1; j <= joints; ++j) {
        Joint joint;
        joint.name = "joint" + std::to_string(j);
        joint.parent = static_cast<int>(j - 1);
        joint.offset = Vec3(0.5 * static_cast<double>(j), 10.0, 0.25);
        joint.channels = {ChannelType::Zrotation, ChannelType::Xrotation, ChannelType::Yrotation};
        joint.rotation_order = EulerOrder::ZXY;
        js.push_back(joint);
    }
    Joint end;
    end.name = "end";
    end.parent = static_cast<int>(joints);
    end.offset = Vec3(0.0, 5.0, 0.0);
    end.end_site = true;
    js.push_back(end);
    Clip clip;
    clip.skeleton = std::make_shared<const Skeleton>(js, SourceUnits{1.0, true});
    clip.frame_rate = frame_rate;
    clip.name = "synthetic";
    const auto c = static_cast<Eigen::Index>(clip.skeleton->channel_count());
    clip.channels = FrameMatrix(static_cast<Eigen::Index>(frames), c);
    std::mt19937 gen(seed);
    std::uniform_real_distribution<double> phase(0.0, 6.0);
    std::vector<double> phases(static_cast<std::size_t>(c));
    for (double& p : phases) p = phase(gen);
    for (Eigen::Index f = 0; f < clip.channels.rows(); ++f)
        for (Eigen::Index k = 0; k < c; ++k) {
            const double t = static_cast<double>(f) / frame_rate;
            clip.channels(f, k) = k < 3 ? 20.0 * std::sin(t + phases[static_cast<std::size_t>(k)]) + (k == 2 ? 50.0 * t : 0.0)
                                        : 0.6 * std::sin(2.0 * t + phases[static_cast<std::size_t>(k)]);
        }
    return clip;
}

ClipSource synthetic_source(const std::string& file_name, const std::string& seed_text) {
    ClipSource s;
    s.file_name = file_name;
    s.sha256 = sha256_hex(seed_text);
    s.format = "bvh";
    return s;
}

AlignedSet synthetic_aligned(std::size_t dofs, std::size_t frames, const MotionSet& set) {
    AlignedSet a;
    a.method = "linear";
    a.reference = 0;
    const auto d = static_cast<Eigen::Index>(dofs), t = static_cast<Eigen::Index>(frames),
               n = static_cast<Eigen::Index>(set.samples.size());
    a.tensor = Tensor3(d, t, n);
    for (Eigen::Index s = 0; s < n; ++s)
        for (Eigen::Index k = 0; k < t; ++k)
            for (Eigen::Index i = 0; i < d; ++i)
                a.tensor(i, k, s) = static_cast<double>(i) + 10.0 * static_cast<double>(k) + 100.0 * static_cast<double>(s);
    a.warps = MatX(t, n);
    for (Eigen::Index s = 0; s < n; ++s) {
        const double last = static_cast<double>(set.samples[static_cast<std::size_t>(s)].frame_count() - 1);
        for (Eigen::Index k = 0; k < t; ++k) a.warps(k, s) = last * static_cast<double>(k) / static_cast<double>(t - 1);
    }
    a.mean = VecX::LinSpaced(d, 0.0, 0.5 * static_cast<double>(d - 1));
    a.scale = VecX::LinSpaced(d, 1.0, static_cast<double>(d));
    for (Eigen::Index s = 0; s < n; ++s) {
        Canonicalization c;
        c.translation = Vec3(static_cast<double>(s), 0.0, -static_cast<double>(s));
        c.yaw = 0.1 * static_cast<double>(s);
        a.canonical.push_back(c);
    }
    return a;
}

std::string file_bytes(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

bool same_bits(const FrameMatrix& a, const FrameMatrix& b) {
    return a.rows() == b.rows() && a.cols() == b.cols() &&
           std::memcmp(a.data(), b.data(), static_cast<std::size_t>(a.size()) * sizeof(double)) == 0;
}

}  // namespace mocapdb::test
