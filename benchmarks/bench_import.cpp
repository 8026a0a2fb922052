// Import throughput and peak memory on the shared CMU folders, as `mocapdb import` does it: the AMC
// folder into a new database, then the PFNN BVH folder (60 Hz) appended in a second session; then a
// re-import of everything (all skipped as duplicates), a full read of every clip, and validate.
// Prints one "name value unit" line per figure.
// Usage: bench_import [SHARED_DIR]   (default: ../shared beside the repository)
#include "bench_timing.hpp"
#include <sys/resource.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>

#include "mocapdb/store/database.hpp"
#include "mocapdb/workflow/import_files.hpp"
#include "mocapdb/store/validate.hpp"

using namespace mocapdb;
namespace fs = std::filesystem;

using namespace mocapdb::bench;

namespace {


double peak_rss_mb() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return static_cast<double>(usage.ru_maxrss) / 1024.0;  // Linux: kilobytes
}

double cpu_seconds() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    auto sec = [](const timeval& t) { return static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_usec); };
    return sec(usage.ru_utime) + sec(usage.ru_stime);
}

struct Phase {
    workflow::ImportSummary summary;
    double seconds = 0.0;      // wall clock
    double cpu = 0.0;          // user + system time of this process
};

Phase import_folder(const fs::path& db, const fs::path& folder, std::optional<double> fps, DatabaseWriter::Mode mode) {
    const auto start = Clock::now();
    const double cpu = cpu_seconds();
    DatabaseWriter writer(db, mode);
    workflow::ImportOptions options;
    options.frame_rate = fps;
    Phase p;
    p.summary = workflow::import_files(writer, workflow::collect_clip_files({folder}), options);
    writer.commit();
    p.seconds = seconds_since(start);
    p.cpu = cpu_seconds() - cpu;
    return p;
}

void report(const char* name, const Phase& p) {
    const double mb = static_cast<double>(p.summary.bytes_read) / 1e6;
    std::printf("%s_clips %zu clips\n", name, p.summary.added);
    std::printf("%s_source %.1f MB\n", name, mb);
    std::printf("%s_time %.2f s\n", name, p.seconds);
    std::printf("%s_cpu_time %.2f s\n", name, p.cpu);
    std::printf("%s_throughput_cpu %.1f MB/s\n", name, mb / p.cpu);
    std::printf("%s_throughput %.1f MB/s\n", name, mb / p.seconds);
    std::printf("%s_rate %.1f clips/s\n", name, static_cast<double>(p.summary.files) / p.seconds);
    std::printf("%s_frames_rate %.0f frames/s\n", name, static_cast<double>(p.summary.frames) / p.seconds);
}

}  // namespace

int main(int argc, char** argv) {
    const fs::path shared = argc > 1 ? fs::path(argv[1]) : fs::path(MOCAPDB_SHARED_DIR);
    const fs::path amc_dir = shared / "datasets" / "cmu-asfamc";
    const fs::path bvh_dir = shared / "datasets" / "cmu-walkrun-pfnn";
    if (!fs::exists(amc_dir) || !fs::exists(bvh_dir)) {
        std::fprintf(stderr, "bench_import: shared datasets not found under %s\n", shared.string().c_str());
        return 1;
    }
    const fs::path dir = fs::temp_directory_path() / ("mocapdb-bench-import-" + std::to_string(::getpid()));
    fs::create_directories(dir);
    const fs::path db = dir / "cmu.h5";
    try {
        const double rss_start = peak_rss_mb();
        const Phase amc = import_folder(db, amc_dir, std::nullopt, DatabaseWriter::Mode::Create);
        const Phase bvh = import_folder(db, bvh_dir, 60.0, DatabaseWriter::Mode::OpenOrCreate);
        const double rss_import = peak_rss_mb();
        report("import_amc", amc);
        report("import_bvh_append", bvh);
        Phase both;
        both.seconds = amc.seconds + bvh.seconds;
        both.cpu = amc.cpu + bvh.cpu;
        both.summary.added = amc.summary.added + bvh.summary.added;
        both.summary.files = amc.summary.files + bvh.summary.files;
        both.summary.frames = amc.summary.frames + bvh.summary.frames;
        both.summary.bytes_read = amc.summary.bytes_read + bvh.summary.bytes_read;
        report("import_total", both);

        const Database view(db);
        std::uint64_t raw = 0, stored = 0;
        for (const ClipRecord& r : view.clips()) {
            raw += r.frames * r.channels * sizeof(double);
            stored += r.stored_bytes;
        }
        std::printf("database_file %.1f MB\n", static_cast<double>(view.file_size()) / 1e6);
        std::printf("channels_float64 %.1f MB\n", static_cast<double>(raw) / 1e6);
        std::printf("channels_stored %.1f MB\n", static_cast<double>(stored) / 1e6);
        std::printf("channels_compression %.2f x\n", static_cast<double>(raw) / static_cast<double>(stored));
        std::printf("peak_rss_before_import %.1f MB\n", rss_start);
        std::printf("peak_rss_import %.1f MB\n", rss_import);

        auto start = Clock::now();
        const Phase again_amc = import_folder(db, amc_dir, std::nullopt, DatabaseWriter::Mode::OpenOrCreate);
        const Phase again_bvh = import_folder(db, bvh_dir, 60.0, DatabaseWriter::Mode::OpenOrCreate);
        std::printf("reimport_skipped %zu clips\n", again_amc.summary.skipped + again_bvh.summary.skipped);
        std::printf("reimport_time %.2f s\n", seconds_since(start));

        start = Clock::now();
        std::size_t frames = 0;
        for (const ClipRecord& r : view.clips()) frames += view.load_clip(r.id).frame_count();
        const double load = seconds_since(start);
        std::printf("load_all_clips_time %.2f s\n", load);
        std::printf("load_all_clips_throughput %.1f MB/s\n", static_cast<double>(raw) / 1e6 / load);
        std::printf("load_all_clips_frames %zu frames\n", frames);

        start = Clock::now();
        const ValidationReport report = validate_database(db);
        std::printf("validate_time %.2f s\n", seconds_since(start));
        std::printf("validate_ok %d\n", report.ok() ? 1 : 0);
        std::printf("peak_rss_end %.1f MB\n", peak_rss_mb());
    } catch (const std::exception& e) {
        std::fprintf(stderr, "bench_import: %s\n", e.what());
        fs::remove_all(dir);
        return 1;
    }
    fs::remove_all(dir);
    return 0;
}
