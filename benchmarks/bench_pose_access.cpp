// Pose access on a packed group (issue 14, acceptance 4: one decoded pose <= 2 µs on one thread for
// a 31-joint skeleton): the packed collection codec's decode paths, timed on one thread.
//
//   bench_pose_access [--folder cmu-asfamc|cmu-walkrun-pfnn|all] [--errors 1,0.5,0.1] [--poses 20000]
//                     [--repeats 3] [--crowd 100] [--ticks 480] [--cache DIR] [--clock wall|cpu]
//
// Per folder (its largest group) and E, µs per pose, best of --repeats (median beside it):
//   cold_us      GroupDecoder::decode_pose at random (clip, frame): range-decodes the pose's window
//   index_us     PoseIndex::pose at the same random (clip, frame): the group range-decoded once, in
//                memory sparse (its build seconds and memory, MB, printed beside it)
//   window_us    decode_window of every window once, per frame decoded (streaming)
//   play_us      PoseSampler, every frame of every clip in order (sequential playback)
//   crowd_us     PoseSampler (capacity 128), --crowd clips at random start frames, each advanced one
//                frame per tick for --ticks ticks, all sampled every tick (looping at clip ends)
//   crowd4_us    the same advancing 4 frames per tick (120 Hz data shown at 30 Hz)
//   hit rate     share of sampler requests whose window was already decoded
// each for channel rows (decode_pose, PoseSampler::pose) and for local poses (decode_local_pose,
// PoseSampler::local_pose: per joint a local rotation quaternion and translation); and, on 10000
// poses from the crowd's clips, whether the sampler equals the decoder bit for bit (rows and local
// poses) and the largest deviation of a local rotation from the row's (quaternion, up to sign).
// --cache DIR keeps the packed bytes per (folder, E) between runs (packing ASF takes ~30 s); bytes of
// an older packing version are packed again. --clock cpu times with the thread's CPU clock instead of
// wall time (a loaded machine then inflates figures less; the default is wall).
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "bench_timing.hpp"
#include "shared_folder.hpp"
#include "mocapdb/core/error.hpp"
#include "mocapdb/io/clip_file.hpp"
#include "mocapdb/packing/group_decoder.hpp"
#include "mocapdb/packing/packed_group.hpp"
#include "mocapdb/packing/pose_index.hpp"
#include "mocapdb/packing/pose_sampler.hpp"

namespace fs = std::filesystem;
using namespace mocapdb;
using namespace mocapdb::bench;

namespace {

// The largest group of the folder packed at E (from the cache when it holds readable bytes).
std::vector<std::uint8_t> packed_bytes(const std::string& folder, double E, const std::string& cache) {
    fs::path file;
    if (!cache.empty()) {
        fs::create_directories(cache);
        std::ostringstream name;
        name << folder << "_E" << E << ".mdbp";
        file = fs::path(cache) / name.str();
        std::ifstream in(file, std::ios::binary);
        if (in) {
            std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
            try {
                packing::GroupDecoder check(bytes);
                return bytes;
            } catch (const Error&) {
                // an older packing version: pack again
            }
        }
    }
    const std::vector<Clip> clips = read_shared_folder(folder);
    std::vector<const Clip*> ptrs;
    for (const Clip& c : clips) ptrs.push_back(&c);
    auto groups = packing::group_clips(ptrs);
    std::sort(groups.begin(), groups.end(), [](const auto& a, const auto& b) { return a.size() > b.size(); });
    std::vector<const Clip*> group;
    for (std::size_t i : groups.front()) group.push_back(ptrs[i]);
    packing::PackOptions options;
    options.format = packing::PackFormat::Archive;  // the archive format's decode paths and index
    options.max_error_cm = E;
    packing::PackedGroup packed = packing::pack_group(group, options);
    if (!file.empty()) {
        std::ofstream out(file, std::ios::binary);
        out.write(reinterpret_cast<const char*>(packed.bytes.data()), static_cast<std::streamsize>(packed.bytes.size()));
    }
    return std::move(packed.bytes);
}

struct Timing {
    std::vector<double> us;
    void add(double seconds, std::size_t poses) { us.push_back(seconds / static_cast<double>(poses) * 1e6); }
};

}  // namespace

int main(int argc, char** argv) {
    std::string folder = "all", cache, clock = "wall";
    std::vector<double> errors{1.0, 0.5, 0.1};
    int poses = 20000, repeats = 3, crowd = 100, ticks = 480;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto next = [&]() -> std::string { return i + 1 < argc ? argv[++i] : ""; };
        if (a == "--folder") folder = next();
        else if (a == "--errors") errors = parse_doubles(next());
        else if (a == "--poses") poses = std::stoi(next());
        else if (a == "--repeats") repeats = std::max(1, std::stoi(next()));
        else if (a == "--crowd") crowd = std::max(1, std::stoi(next()));
        else if (a == "--ticks") ticks = std::max(1, std::stoi(next()));
        else if (a == "--cache") cache = next();
        else if (a == "--clock") clock = next();
        else {
            std::fprintf(stderr, "unknown argument %s\n", a.c_str());
            return 2;
        }
    }
    if (clock != "wall" && clock != "cpu") {
        std::fprintf(stderr, "--clock wall|cpu\n");
        return 2;
    }
    const bool cpu = clock == "cpu";
    auto now = [cpu] { return cpu ? thread_cpu_seconds() : wall_seconds(); };
    const std::vector<std::string> folders =
        folder == "all" ? std::vector<std::string>{"cmu-walkrun-pfnn", "cmu-asfamc"} : std::vector<std::string>{folder};
    for (const auto& name : folders)
        for (double E : errors) {
            const packing::GroupDecoder decoder(packed_bytes(name, E, cache));
            const double build_start = now();
            const packing::PoseIndex index(decoder);
            const double build_s = now() - build_start;
            const std::size_t clips = decoder.clip_count();
            const std::size_t channels = decoder.skeleton(0)->channel_count();
            std::size_t frames = 0, windows = 0;
            for (std::size_t k = 0; k < clips; ++k) {
                frames += decoder.frame_count(k);
                windows += decoder.window_count(k);
            }
            std::vector<double> row(channels), other(channels);
            packing::LocalPose local, local2;
            // [0]: channel rows, [1]: local poses
            Timing cold[2], indexed[2], window, play[2], crowd1[2], crowd4[2];
            double hit1 = 0, hit4 = 0;
            bool identical = true;
            double rotation_error = 0.0;
            auto consume = [&](const packing::LocalPose& p) { g_sink = g_sink + p.rotations[1].w() + p.translations[0].x(); };
            for (int r = 0; r < repeats; ++r) {
                // Random access, the same (clip, frame) sequence for each source: [0] rows, [1] local poses.
                auto random_access = [&](Timing* out, auto&& rows_of, auto&& local_of) {
                    for (int kind = 0; kind < 2; ++kind) {
                        std::mt19937 rng(7);
                        const double t = now();
                        for (int p = 0; p < poses; ++p) {
                            const std::size_t k = rng() % clips;
                            const std::size_t f = rng() % decoder.frame_count(k);
                            if (kind == 0) {
                                rows_of(k, f);
                                g_sink = g_sink + row[0];
                            } else {
                                local_of(k, f);
                                consume(local);
                            }
                        }
                        out[kind].add(now() - t, static_cast<std::size_t>(poses));
                    }
                };
                random_access(
                    cold, [&](std::size_t k, std::size_t f) { decoder.decode_pose(k, f, row.data()); },
                    [&](std::size_t k, std::size_t f) { decoder.decode_local_pose(k, f, local); });
                random_access(
                    indexed, [&](std::size_t k, std::size_t f) { index.pose(k, f, row.data()); },
                    [&](std::size_t k, std::size_t f) { index.local_pose(k, f, local); });
                {  // streaming, window by window
                    const double t = now();
                    for (std::size_t k = 0; k < clips; ++k)
                        for (std::size_t w = 0; w < decoder.window_count(k); ++w) g_sink = g_sink + decoder.decode_window(k, w)(0, 0);
                    window.add(now() - t, frames);
                }
                for (int kind = 0; kind < 2; ++kind) {  // sequential playback
                    packing::PoseSampler sampler(decoder, 4);
                    const double t = now();
                    for (std::size_t k = 0; k < clips; ++k)
                        for (std::size_t f = 0; f < decoder.frame_count(k); ++f) {
                            if (kind == 0) {
                                g_sink = g_sink + sampler.pose(k, f)[0];
                            } else {
                                sampler.local_pose(k, f, local);
                                consume(local);
                            }
                        }
                    play[kind].add(now() - t, frames);
                }
                for (int step : {1, 4})  // a crowd
                    for (int kind = 0; kind < 2; ++kind) {
                        std::mt19937 rng(11);
                        std::vector<std::size_t> clip(static_cast<std::size_t>(crowd)), frame(clip.size());
                        for (std::size_t a = 0; a < clip.size(); ++a) {
                            clip[a] = rng() % clips;
                            frame[a] = rng() % decoder.frame_count(clip[a]);
                        }
                        packing::PoseSampler sampler(decoder, 128);
                        const double t = now();
                        for (int tick = 0; tick < ticks; ++tick)
                            for (std::size_t a = 0; a < clip.size(); ++a) {
                                if (kind == 0) {
                                    g_sink = g_sink + sampler.pose(clip[a], frame[a])[0];
                                } else {
                                    sampler.local_pose(clip[a], frame[a], local);
                                    consume(local);
                                }
                                frame[a] = (frame[a] + static_cast<std::size_t>(step)) % decoder.frame_count(clip[a]);
                            }
                        (step == 1 ? crowd1 : crowd4)[kind].add(now() - t, clip.size() * static_cast<std::size_t>(ticks));
                        (step == 1 ? hit1 : hit4) =
                            static_cast<double>(sampler.hits()) / static_cast<double>(sampler.hits() + sampler.misses());
                        if (r == 0 && step == 1 && kind == 0) {  // bit-identity with decode_pose (untimed)
                            sampler.clear();
                            const Skeleton& skeleton = *decoder.skeleton(0);
                            std::mt19937 again(11);
                            for (int p = 0; p < 2000; ++p) {
                                const std::size_t k = again() % clips;
                                const std::size_t f = again() % decoder.frame_count(k);
                                for (std::size_t s = 0; s < 5 && f + s < decoder.frame_count(k); ++s) {
                                    decoder.decode_pose(k, f + s, row.data());
                                    sampler.pose(k, f + s, other.data());
                                    identical = identical && std::memcmp(row.data(), other.data(), channels * sizeof(double)) == 0;
                                    index.pose(k, f + s, other.data());
                                    identical = identical && std::memcmp(row.data(), other.data(), channels * sizeof(double)) == 0;
                                    // Local poses: sampler == decoder bit for bit, rotations == the row's.
                                    sampler.local_pose(k, f + s, local);
                                    decoder.decode_local_pose(k, f + s, local2);
                                    identical = identical &&
                                                std::memcmp(local.rotations.data(), local2.rotations.data(), local.rotations.size() * sizeof(Quat)) == 0;
                                    index.local_pose(k, f + s, local);
                                    identical = identical &&
                                                std::memcmp(local.rotations.data(), local2.rotations.data(), local.rotations.size() * sizeof(Quat)) == 0 &&
                                                std::memcmp(local.translations.data(), local2.translations.data(), local.translations.size() * sizeof(Vec3)) == 0;
                                    for (std::size_t j = 0; j < skeleton.size(); ++j) {
                                        const Quat q = decoder.skeleton(k)->local_rotation(j, row.data());
                                        const Quat& l = local.rotations[j];
                                        rotation_error = std::max(rotation_error, std::min((q.coeffs() - l.coeffs()).norm(),
                                                                                           (q.coeffs() + l.coeffs()).norm()));
                                    }
                                }
                            }
                        }
                    }
            }
            std::printf(
                "clock=%s folder=%s E=%g clips=%zu frames=%zu windows=%zu channels=%zu joints=%zu | channel rows: cold_us=%.2f "
                "(median %.2f) window_us=%.2f (median %.2f) play_us=%.2f (median %.2f) crowd_us=%.2f (median %.2f) "
                "crowd4_us=%.2f (median %.2f) | local poses: cold_us=%.2f (median %.2f) play_us=%.2f (median %.2f) "
                "crowd_us=%.2f (median %.2f) crowd4_us=%.2f (median %.2f) | hit %.3f / %.3f | index: build_s=%.3f memory_mb=%.2f coefficients=%zu columns_8_16_32=%zu/%zu/%zu "
                "rows index_us=%.2f (median %.2f) local index_us=%.2f (median %.2f) | "
                "sampler_and_index_equal_decoder=%d local_rotation_max_dev=%.1e\n",
                clock.c_str(), name.c_str(), E, clips, frames, windows, channels, decoder.skeleton(0)->size(), best(cold[0].us),
                median(cold[0].us), best(window.us), median(window.us), best(play[0].us), median(play[0].us),
                best(crowd1[0].us), median(crowd1[0].us), best(crowd4[0].us), median(crowd4[0].us), best(cold[1].us),
                median(cold[1].us), best(play[1].us), median(play[1].us), best(crowd1[1].us), median(crowd1[1].us),
                best(crowd4[1].us), median(crowd4[1].us), hit1, hit4, build_s, static_cast<double>(index.memory_bytes()) / 1e6,
                index.coefficient_count(), index.column_widths()[0], index.column_widths()[1], index.column_widths()[2], best(indexed[0].us), median(indexed[0].us), best(indexed[1].us),
                median(indexed[1].us), identical ? 1 : 0, rotation_error);
            std::fflush(stdout);
        }
    return 0;
}
