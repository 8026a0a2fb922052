// The runtime tier in the library (packing::encode_runtime, packing::RuntimeDecoder): per shared folder
// and E its bytes, its max error over every frame and the time of one cold random whole local pose,
// beside format 3's GroupDecoder::decode_local_pose on the same sequence.
//
//   bench_runtime_format [--folders cmu-walkrun-pfnn,cmu-asfamc] [--errors 1,0.5,0.1] [--windows 8,16]
//                        [--poses 20000] [--reps 5] [--seed 7] [--limit N] [--bases learned|auto] [--format3 0|1]
//
// Groups as bench_runtime_prototype makes them (group_clips; pack_group with learned time and dof bases,
// or `mocapdb pack`'s Auto with --bases auto), then encode_runtime per group at each --windows entry
// (8, 16, or 0: chosen per group). Bytes: the runtime bodies plus the packed groups' header_bytes
// (topology, skeletons, bases, contexts: the prototype's stand-in for the shared header). Max: FK of
// every joint and end site of every decoded frame (decode_clip) against the source, cm. Timing: N
// (clip, frame) drawn uniformly over the folder's frames (mt19937_64 --seed, bench_acl_runtime's
// sequence), one thread, thread CPU, best of --reps; the same poses for every decoder in each repeat.
// `sequential`: every frame of every clip by decode_local_poses (window by window). Resident: the
// decoders' resident_bytes().
#include <algorithm>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "bench_timing.hpp"
#include "shared_folder.hpp"
#include "mocapdb/motion/forward_kinematics.hpp"
#include "mocapdb/packing/group_decoder.hpp"
#include "mocapdb/packing/packed_group.hpp"
#include "mocapdb/packing/runtime_decoder.hpp"
#include "mocapdb/packing/runtime_encoder.hpp"

using namespace mocapdb;
using namespace mocapdb::packing;

namespace {

double max_error(const Clip& source, const Clip& decoded) {
    const MatX a = joint_positions(source), b = joint_positions(decoded);
    double worst = 0.0;
    for (Eigen::Index f = 0; f < a.cols(); ++f)
        for (Eigen::Index j = 0; j < a.rows(); j += 3) worst = std::max(worst, (a.block<3, 1>(j, f) - b.block<3, 1>(j, f)).norm());
    return worst;
}

}  // namespace

int main(int argc, char** argv) {
    std::vector<std::string> folders{"cmu-walkrun-pfnn", "cmu-asfamc"};
    std::vector<double> errors{1.0, 0.5, 0.1};
    std::vector<int> windows{8, 16};
    std::size_t poses = 20000, limit = 0;
    int reps = 5;
    std::uint64_t seed = 7;
    bool auto_bases = false, format3 = true;
    for (int a = 1; a + 1 < argc; a += 2) {
        const std::string k = argv[a], v = argv[a + 1];
        if (k == "--folders") folders = bench::split_list(v);
        else if (k == "--errors") {
            errors.clear();
            for (const auto& s : bench::split_list(v)) errors.push_back(std::stod(s));
        } else if (k == "--windows") {
            windows.clear();
            for (const auto& s : bench::split_list(v)) windows.push_back(std::stoi(s));
        } else if (k == "--poses") poses = std::stoul(v);
        else if (k == "--reps") reps = std::max(1, std::stoi(v));
        else if (k == "--seed") seed = std::stoull(v);
        else if (k == "--limit") limit = std::stoul(v);
        else if (k == "--bases") auto_bases = v == "auto";
        else if (k == "--format3") format3 = v == "1";
        else {
            std::fprintf(stderr, "bench_runtime_format: unknown argument %s\n", k.c_str());
            return 2;
        }
    }
    std::printf("folder,E,W,runtime_bytes,body_bytes,header_bytes,max_cm,encoder_max_cm,cold_us,format3_us,format3_bytes,"
                "sequential_us,resident_bytes,encode_s,avx2,encode_cpu_s\n");
    for (const std::string& folder : folders) {
        const std::vector<Clip> clips = bench::read_shared_folder(folder, limit);
        std::vector<const Clip*> all;
        for (const Clip& c : clips) all.push_back(&c);
        const auto groups = group_clips(all);
        // (group, member) of each clip, and the random poses (bench_acl_runtime's draw).
        std::vector<std::pair<std::size_t, std::size_t>> where(clips.size());
        for (std::size_t g = 0; g < groups.size(); ++g)
            for (std::size_t m = 0; m < groups[g].size(); ++m) where[groups[g][m]] = {g, m};
        std::vector<std::uint64_t> ends;
        std::uint64_t sum = 0;
        for (const Clip& c : clips) ends.push_back(sum += c.frame_count());
        std::mt19937_64 rng(seed);
        std::vector<std::pair<std::size_t, std::size_t>> sequence;
        for (std::size_t p = 0; p < poses; ++p) {
            const std::uint64_t u = rng() % sum;
            const auto k = static_cast<std::size_t>(std::upper_bound(ends.begin(), ends.end(), u) - ends.begin());
            sequence.push_back({k, static_cast<std::size_t>(u - (k == 0 ? 0 : ends[k - 1]))});
        }
        for (double E : errors) {
            PackOptions po;
            po.format = PackFormat::Archive;  // the format-3 group encode_runtime reads
            po.max_error_cm = E;
            if (!auto_bases) {
                po.time_basis = TimeBasis::Learned;
                po.dof_basis = DofBasis::Learned;
            }
            std::vector<std::vector<std::uint8_t>> packed(groups.size());
            std::vector<std::vector<const Clip*>> members(groups.size());
            std::size_t header_bytes = 0, format3_bytes = 0;
            for (std::size_t g = 0; g < groups.size(); ++g) {
                for (std::size_t i : groups[g]) members[g].push_back(all[i]);
                PackedGroup pg = pack_group(members[g], po);
                header_bytes += pg.stats.header_bytes;
                format3_bytes += pg.stats.bytes;
                packed[g] = std::move(pg.bytes);
            }
            std::vector<GroupDecoder> format3_decoders;
            if (format3)
                for (const auto& b : packed) format3_decoders.emplace_back(b);
            for (int W : windows) {
                std::vector<RuntimeBody> bodies;
                std::vector<RuntimeDecoder> decoders;
                double encode_s = 0.0, encoder_max = 0.0, encode_cpu = 0.0;
                std::size_t body_bytes = 0, resident = 0;
                std::string used;
                for (std::size_t g = 0; g < groups.size(); ++g) {
                    RuntimeOptions ro;
                    ro.max_error_cm = E;
                    ro.window = W;
                    const double e0 = bench::thread_cpu_seconds();
                    bodies.push_back(encode_runtime(packed[g], members[g], ro));
                    encode_cpu += bench::thread_cpu_seconds() - e0;
                    encode_s += bodies.back().stats.encode_seconds;
                    encoder_max = std::max(encoder_max, bodies.back().stats.max_error_cm);
                    body_bytes += bodies.back().bytes.size();
                    used += (used.empty() ? "" : "/") + std::to_string(bodies.back().stats.window);
                }
                for (std::size_t g = 0; g < groups.size(); ++g) {
                    decoders.emplace_back(packed[g].data(), packed[g].size(), bodies[g].bytes.data(), bodies[g].bytes.size());
                    resident += decoders.back().resident_bytes();
                }
                // Every frame of every clip against its source.
                double worst = 0.0;
                for (std::size_t k = 0; k < clips.size(); ++k)
                    worst = std::max(worst, max_error(clips[k], decoders[where[k].first].decode_clip(where[k].second)));
                // Cold random local poses, and format 3's on the same sequence (in turn, each repeat).
                LocalPose out;
                double sink = 0.0, cold = 1e300, f3 = 1e300, sequential = 1e300;
                for (int r = 0; r < reps; ++r) {
                    double c0 = bench::thread_cpu_seconds();
                    for (const auto& [k, f] : sequence) {
                        decoders[where[k].first].decode_local_pose(where[k].second, f, out);
                        sink += out.rotations[1].w();
                    }
                    cold = std::min(cold, (bench::thread_cpu_seconds() - c0) / static_cast<double>(sequence.size()) * 1e6);
                    if (format3 && W == windows.front()) {
                        c0 = bench::thread_cpu_seconds();
                        for (const auto& [k, f] : sequence) {
                            format3_decoders[where[k].first].decode_local_pose(where[k].second, f, out);
                            sink += out.rotations[1].w();
                        }
                        f3 = std::min(f3, (bench::thread_cpu_seconds() - c0) / static_cast<double>(sequence.size()) * 1e6);
                    }
                }
                std::vector<LocalPose> window_poses;
                for (int r = 0; r < std::min(reps, 3); ++r) {
                    const double c0 = bench::thread_cpu_seconds();
                    for (std::size_t k = 0; k < clips.size(); ++k) {
                        decoders[where[k].first].decode_local_poses(where[k].second, 0, clips[k].frame_count(), window_poses);
                        sink += window_poses.back().rotations[1].w();
                    }
                    sequential = std::min(sequential, (bench::thread_cpu_seconds() - c0) / static_cast<double>(sum) * 1e6);
                }
                std::printf("%s,%g,%s,%zu,%zu,%zu,%.7f,%.7f,%.3f,%.2f,%zu,%.3f,%zu,%.1f,%d,%.3f\n", folder.c_str(), E, used.c_str(),
                            body_bytes + header_bytes, body_bytes, header_bytes, worst, encoder_max, cold,
                            format3 && W == windows.front() ? f3 : 0.0, format3_bytes, sequential, resident, encode_s,
                            decoders.front().uses_avx2() ? 1 : 0, encode_cpu);
                std::fflush(stdout);
                if (sink == 12345.678) std::printf("#\n");
            }
        }
    }
    return 0;
}
