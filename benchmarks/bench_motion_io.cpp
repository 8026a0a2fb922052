// Motion data layer throughput on the shared CMU clips: BVH parse (MB/s), AMC parse (MB/s) and
// forward kinematics (frames/s). Prints one "name value unit" line per figure.
// Usage: bench_motion_io [SHARED_DIR]   (default: ../shared beside the repository)
#include "bench_timing.hpp"
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "mocapdb/io/asf_amc.hpp"
#include "mocapdb/io/bvh.hpp"
#include "mocapdb/io/text_file.hpp"
#include "mocapdb/motion/forward_kinematics.hpp"

using namespace mocapdb;
namespace fs = std::filesystem;

using namespace mocapdb::bench;

namespace {

std::vector<fs::path> files_with(const fs::path& dir, const std::string& ext) {
    std::vector<fs::path> out;
    for (const auto& e : fs::directory_iterator(dir))
        if (e.path().extension() == ext) out.push_back(e.path());
    std::sort(out.begin(), out.end());
    return out;
}



}  // namespace

int main(int argc, char** argv) {
    const fs::path shared = argc > 1 ? fs::path(argv[1]) : fs::path(MOCAPDB_SHARED_DIR);
    const fs::path bvh_dir = shared / "datasets" / "cmu-walkrun-pfnn";
    const fs::path amc_dir = shared / "datasets" / "cmu-asfamc";
    if (!fs::exists(bvh_dir) || !fs::exists(amc_dir)) {
        std::fprintf(stderr, "bench_motion_io: shared datasets not found under %s\n", shared.string().c_str());
        return 1;
    }

    // BVH: text already in memory, so this measures parsing, not the disk.
    std::vector<std::pair<std::string, std::string>> bvh_texts;
    double bvh_bytes = 0;
    for (const auto& p : files_with(bvh_dir, ".bvh")) {
        bvh_texts.emplace_back(p.string(), read_text_file(p));
        bvh_bytes += static_cast<double>(bvh_texts.back().second.size());
    }
    std::vector<Clip> clips;
    BvhReadOptions options;
    options.frame_rate = 60.0;
    const double bvh_s = best_of(5, [&] {
        clips.clear();
        for (const auto& [name, text] : bvh_texts) clips.push_back(parse_bvh(text, name, options));
    });

    // AMC likewise (skeletons parsed once per subject, outside the timing).
    std::vector<std::pair<std::string, std::string>> amc_texts;
    std::vector<std::shared_ptr<const Skeleton>> amc_skeletons;
    double amc_bytes = 0;
    for (const auto& p : files_with(amc_dir, ".amc")) {
        const auto asf = find_asf_for_amc(p);
        if (!asf) continue;
        amc_texts.emplace_back(p.string(), read_text_file(p));
        amc_skeletons.push_back(read_asf(*asf));
        amc_bytes += static_cast<double>(amc_texts.back().second.size());
    }
    std::vector<Clip> amc_clips;
    const double amc_s = best_of(3, [&] {
        amc_clips.clear();
        for (std::size_t i = 0; i < amc_texts.size(); ++i)
            amc_clips.push_back(parse_amc(amc_texts[i].second, amc_texts[i].first, amc_skeletons[i]));
    });

    // FK: every frame of every clip, allocation-free loop.
    auto fk_rate = [](const std::vector<Clip>& set, int repeats, std::size_t& joints_out) {
        std::size_t frames = 0;
        joints_out = set.front().skeleton->size();
        for (const Clip& c : set) frames += c.frame_count();
        GlobalPose pose;
        double sink = 0;
        const double s = best_of(repeats, [&] {
            for (const Clip& c : set)
                for (std::size_t f = 0; f < c.frame_count(); ++f) {
                    forward_kinematics(*c.skeleton, c.frame(f), pose);
                    sink += pose.positions.back().x();
                }
        });
        if (sink == 12345.678) std::printf("#\n");  // keep the work observable
        return static_cast<double>(frames) / s;
    };
    std::size_t bvh_joints = 0, amc_joints = 0;
    const double fk_bvh = fk_rate(clips, 5, bvh_joints);
    const double fk_amc = fk_rate(amc_clips, 3, amc_joints);

    std::size_t bvh_frames = 0, amc_frames = 0;
    for (const Clip& c : clips) bvh_frames += c.frame_count();
    for (const Clip& c : amc_clips) amc_frames += c.frame_count();
    std::printf("bvh_files %zu\nbvh_bytes %.0f\nbvh_frames %zu\n", bvh_texts.size(), bvh_bytes, bvh_frames);
    std::printf("bvh_parse_throughput %.1f MB/s\n", bvh_bytes / 1e6 / bvh_s);
    std::printf("amc_files %zu\namc_bytes %.0f\namc_frames %zu\n", amc_texts.size(), amc_bytes, amc_frames);
    std::printf("amc_parse_throughput %.1f MB/s\n", amc_bytes / 1e6 / amc_s);
    std::printf("fk_throughput_bvh %.0f frames/s (%zu joints)\n", fk_bvh, bvh_joints);
    std::printf("fk_throughput_amc %.0f frames/s (%zu joints)\n", fk_amc, amc_joints);
    return 0;
}
