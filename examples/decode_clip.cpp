// Decodes one clip from the lossless tier and from the packed tier, and measures how far the packed
// clip's joints are from the source's (forward kinematics, every joint and end site, cm).
//   example_decode_clip DB.h5 CLIP
#include <algorithm>
#include <cstdio>
#include <exception>

#include "mocapdb/motion/forward_kinematics.hpp"
#include "mocapdb/store/database.hpp"

int main(int argc, char** argv) {
    if (argc != 3) {
        std::fprintf(stderr, "usage: %s DB.h5 CLIP\n", argv[0]);
        return 2;
    }
    try {
        const mocapdb::Database db(argv[1]);
        const mocapdb::Clip source = db.load_clip(argv[2]);
        std::printf("clip %s: %zu frames x %zu channels at %g Hz\n", argv[2], source.frame_count(),
                    static_cast<std::size_t>(source.channels.cols()), source.frame_rate);
        mocapdb::GlobalPose pose;
        mocapdb::forward_kinematics(*source.skeleton, source.frame(0), pose);
        double low = pose.positions.front().y(), high = low;
        for (const auto& p : pose.positions) {
            low = std::min(low, p.y());
            high = std::max(high, p.y());
        }
        std::printf("frame 0: %zu joint positions, figure %.1f cm tall\n", pose.positions.size(), high - low);

        const auto tier = db.packed();
        if (!tier || !tier->find(argv[2])) {
            std::printf("no packed tier for this clip (run: mocapdb pack %s --max-error-cm 1)\n", argv[1]);
            return 0;
        }
        const mocapdb::Clip packed = db.load_clip_packed(argv[2]);
        mocapdb::GlobalPose a, b;
        double worst = 0.0;
        for (std::size_t f = 0; f < source.frame_count(); ++f) {
            mocapdb::forward_kinematics(*source.skeleton, source.frame(f), a);
            mocapdb::forward_kinematics(*packed.skeleton, packed.frame(f), b);
            for (std::size_t j = 0; j < a.positions.size(); ++j) worst = std::max(worst, (a.positions[j] - b.positions[j]).norm());
        }
        std::printf("packed tier: max joint error %.4f cm over %zu frames (bound %.3f cm)\n", worst, source.frame_count(),
                    tier->max_error_cm);
        return worst <= tier->max_error_cm + 1e-4 ? 0 : 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "example_decode_clip: %s\n", e.what());
        return 1;
    }
}
