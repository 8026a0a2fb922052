// mocapdb align: time-align a motion set's samples and store the D × T × N pose tensor.
#include <cstdio>

#include "commands.hpp"
#include "pipeline.hpp"

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
    AlignRequest r;
    r.set = a.set;
    r.frames = a.frames;
    r.method = a.method;
    r.reference = a.reference;
    std::fputs(describe_alignment(a.set, align_set(a.db, r)).c_str(), stdout);
}

}  // namespace

void setup_align(CLI::App& app) {
    auto a = std::make_shared<AlignArgs>();
    CLI::App* cmd = app.add_subcommand("align", "Time-align a motion set and store its pose tensor");
    cmd->footer(
        "Example:\n"
        "  mocapdb align db.h5 --set walks --frames 100 --method dtw\n"
        "dtw warps every sample onto the reference (default: the sample of median length) with the pose\n"
        "distance of lib/include/mocapdb/dataset/pose_distance.hpp; linear resamples each sample uniformly.\n"
        "Replaces the set's previous alignment.");
    cmd->add_option("db", a->db, "database file")->required()->check(CLI::ExistingFile);
    cmd->add_option("--set", a->set, "motion set")->required();
    cmd->add_option("--frames", a->frames, "aligned frames T")->check(CLI::Range(2LL, 100000LL));
    cmd->add_option("--method", a->method, "dtw | linear")->check(CLI::IsMember({"dtw", "linear"}));
    cmd->add_option("--reference", a->reference, "reference sample label (CLIP or CLIP:BEGIN-END)");
    cmd->callback([a] { run_align(*a); });
}

}  // namespace mocapdb::cli
