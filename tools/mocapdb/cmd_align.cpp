// mocapdb align: time-align a motion set's samples and store the D × T × N pose tensor.
#include <chrono>
#include <cstdio>

#include "commands.hpp"
#include "mocapdb/core/error.hpp"
#include "mocapdb/dataset/alignment.hpp"
#include "mocapdb/dataset/set_builder.hpp"
#include "mocapdb/store/database.hpp"

namespace mocapdb::cli {
namespace {

struct AlignArgs {
    std::string db;
    std::string set;
    long long frames = 100;
    std::string method = "dtw";
    std::string reference;
};

void run_align(const AlignArgs& a) {
    const auto start = std::chrono::steady_clock::now();
    // Read from the published file (errors name it), write in a session only once aligned.
    const Database db(a.db);
    const MotionSet set = db.load_set(a.set);
    std::vector<Clip> samples;
    std::vector<std::string> labels;
    for (const SampleRef& s : set.samples) {
        const Clip clip = db.load_clip(s.clip);
        labels.push_back(sample_label(s, clip.frame_count()));
        samples.push_back(slice(clip, s.begin, s.end));
    }
    AlignOptions options;
    options.method = a.method;
    options.frames = static_cast<Eigen::Index>(a.frames);
    if (!a.reference.empty()) {
        const auto it = std::find(labels.begin(), labels.end(), a.reference);
        if (it == labels.end())
            throw InvalidArgument("set '" + a.set + "' has no sample '" + a.reference + "' (see mocapdb set show)");
        options.reference = static_cast<std::size_t>(it - labels.begin());
    }
    const AlignedSet aligned = align_samples(samples, options);
    const double distance = mean_alignment_distance(samples, aligned);
    DatabaseWriter writer(a.db, DatabaseWriter::Mode::OpenOrCreate);
    writer.put_aligned(a.set, aligned);
    writer.commit();
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("aligned set '%s' (%s, reference %s): tensor %lld dofs x %lld frames x %lld samples; "
                "mean pose distance to the reference %.2f cm; %.2f s\n",
                a.set.c_str(), aligned.method.c_str(), labels[aligned.reference].c_str(),
                static_cast<long long>(aligned.dofs()), static_cast<long long>(aligned.frames()),
                static_cast<long long>(aligned.samples()), distance, seconds);
}

}  // namespace

void setup_align(CLI::App& app) {
    auto a = std::make_shared<AlignArgs>();
    CLI::App* cmd = app.add_subcommand("align", "Time-align a motion set and store its pose tensor");
    cmd->footer(
        "Example:\n"
        "  mocapdb align db.h5 --set walks --frames 100 --method dtw\n"
        "dtw warps every sample onto the reference (default: the sample of median length) with the pose\n"
        "distance of lib/include/mocapdb/align/pose_distance.hpp; linear resamples each sample uniformly.\n"
        "Replaces the set's previous alignment.");
    cmd->add_option("db", a->db, "database file")->required()->check(CLI::ExistingFile);
    cmd->add_option("--set", a->set, "motion set")->required();
    cmd->add_option("--frames", a->frames, "aligned frames T")->check(CLI::Range(2LL, 100000LL));
    cmd->add_option("--method", a->method, "dtw | linear")->check(CLI::IsMember({"dtw", "linear"}));
    cmd->add_option("--reference", a->reference, "reference sample label (CLIP or CLIP:BEGIN-END)");
    cmd->callback([a] { run_align(*a); });
}

}  // namespace mocapdb::cli
