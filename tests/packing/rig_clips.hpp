#pragma once
// Generated rigs the packing tests share (header-only): the procedural humanoid's walks and a
// 100-joint rig with hinges, static joints and end sites.
#include <cmath>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "mocapdb/motion/clip.hpp"
#include "mocapdb/procedural/walk.hpp"

namespace mocapdb::test {

/// Six procedural walks at 60 Hz (speeds 0.9 and 1.5 m/s, turns -60, 0 and 90 degrees), two cycles.
inline std::vector<Clip> procedural_walks() {
    std::vector<Clip> out;
    int i = 0;
    for (double speed : {0.9, 1.5})
        for (double turn : {-60.0, 0.0, 90.0}) {
            procedural::WalkOptions o;
            o.frame_rate = 60.0;
            o.cycles = 2;
            Clip c = procedural::generate_walk({speed, turn, 0.0}, o).clip;
            c.name = "walk" + std::to_string(i++);
            out.push_back(std::move(c));
        }
    return out;
}

// A 100-joint rig (root + spine + 9 branches of 10 joints, the last of each with an end site; some
// joints static, a few with 1 or 2 rotation channels) moving smoothly at `rate` for `seconds`.
inline Clip hundred_joint_clip(double rate, double seconds, unsigned seed) {
    std::vector<Joint> js;
    Joint root;
    root.name = "root";
    root.channels = {ChannelType::Xposition, ChannelType::Yposition, ChannelType::Zposition,
                     ChannelType::Zrotation, ChannelType::Xrotation, ChannelType::Yrotation};
    root.offset = Vec3(0.0, 95.0, 0.0);
    js.push_back(root);
    for (int b = 0; b < 9; ++b) {
        int parent = 0;
        for (int k = 0; k < 11; ++k) {
            Joint j;
            j.name = "b" + std::to_string(b) + "_" + std::to_string(k);
            j.parent = parent;
            j.offset = Vec3(0.8 * (b - 4), k == 0 ? 3.0 : 4.0, 0.3 * k);
            if (k == 10) {
                j.end_site = true;
            } else if (k % 4 == 3) {
                j.channels = {ChannelType::Xrotation};  // hinge
            } else if (k % 4 != 2) {
                j.channels = {ChannelType::Zrotation, ChannelType::Xrotation, ChannelType::Yrotation};
            }  // k % 4 == 2: static joint (no channels)
            parent = static_cast<int>(js.size());
            js.push_back(j);
        }
    }
    Clip clip;
    clip.skeleton = std::make_shared<const Skeleton>(js, SourceUnits{1.0, true});
    clip.frame_rate = rate;
    clip.name = "rig100";
    const auto channels = static_cast<Eigen::Index>(clip.skeleton->channel_count());
    clip.channels = FrameMatrix(static_cast<Eigen::Index>(std::lround(rate * seconds)), channels);
    std::mt19937 gen(seed);
    std::uniform_real_distribution<double> phase(0.0, 6.0), speed(0.5, 3.0);
    for (Eigen::Index k = 0; k < channels; ++k) {
        const double p = phase(gen), w = speed(gen);
        for (Eigen::Index f = 0; f < clip.channels.rows(); ++f) {
            const double t = static_cast<double>(f) / rate;
            clip.channels(f, k) = k < 3 ? 15.0 * std::sin(w * t + p) + (k == 2 ? 80.0 * t : 0.0) : 0.5 * std::sin(w * t + p);
        }
    }
    return clip;
}

}  // namespace mocapdb::test
