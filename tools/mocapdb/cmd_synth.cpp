// mocapdb synth: synthesize the motion of a set at new control parameters and write it as BVH.
#include <chrono>
#include <cstdio>

#include "commands.hpp"
#include "output_files.hpp"
#include "json_writer.hpp"
#include "mocapdb_json/synthesis_json.hpp"
#include "mocapdb/core/error.hpp"
#include "mocapdb/dataset/motion_set.hpp"
#include "mocapdb/io/bvh.hpp"
#include "mocapdb/io/gltf_writer.hpp"
#include "mocapdb/workflow/synthesis_step.hpp"
#include "pipeline.hpp"
#include "synthesis_cli.hpp"

namespace mocapdb::cli {
namespace {

struct SynthArgs {
    std::string db;
    std::string set;
    std::string param;
    std::string out;
    std::string lod;
    std::string timing = "shared";
    std::string predictor = "auto";
    bool naive = false;
    bool json = false;
    bool force = false;
};

void run_synth(const SynthArgs& a) {
    refuse_existing(a.out, a.force);
    using Clock = std::chrono::steady_clock;
    const auto t0 = Clock::now();
    const Database db(a.db);
    const MotionSet set = db.load_set(a.set);
    const VecX c = parse_parameters(a.param, set, "--param");
    const auto model = load_synthesis_model(db, a.set, a.naive, a.lod, a.timing, a.predictor);
    const double load_s = std::chrono::duration<double>(Clock::now() - t0).count();
    const Eigen::Index level = a.lod.empty() ? 0 : 1;

    const workflow::SynthOutcome o = workflow::synthesize(*model, set, c, level);
    const std::string ext = std::filesystem::path(a.out).extension().string();
    if (ext == ".gltf" || ext == ".glb")
        write_gltf(a.out, o.clip, ext == ".glb" ? GltfContainer::Glb : GltfContainer::Gltf);
    else write_bvh(a.out, o.clip);
    const Clip& clip = o.clip;
    const synthesis::Timing& timing = o.timing;
    const double rho = o.reliability;
    const double synth_s = o.seconds;
    const tensor::Ranks ranks = model->level_ranks(level);
    const workflow::SynthesisWarnings judged = workflow::synthesis_warnings(*model, o, set);
    const std::vector<std::string> warnings = warning_lines(judged, set);
    for (const std::string& w : warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
    if (a.json) {
        json::SynthReport r;
        r.set = a.set;
        r.model = model->kind();
        r.ranks = ranks;
        r.parameter_names = set.parameter_names;
        r.parameter_units = set.parameter_units;
        r.parameter_levels = set.parameter_levels;
        r.warnings = warnings;
        r.judged = judged;
        r.load_s = load_s;
        r.precompute_s = model->report().precompute_seconds;
        r.kernel_stored = model->report().kernel_precomputed;
        r.local_neighbours = static_cast<long long>(model->report().local_neighbours);
        r.predictor = synthesis::to_string(model->report().predictor);
        r.predictor_choice = model->report().predictor_choice;
        r.output = a.out;
        JsonWriter j;
        json::write_synthesis(j, r, o);
        std::fputs(j.str().c_str(), stdout);
        return;
    }
    const Eigen::Index local = model->report().local_neighbours;
    const std::string predictor =
        std::string(synthesis::to_string(model->report().predictor)) +
        (local > 0 ? "; local kriging: each request from its " + std::to_string(local) + " nearest samples" : "");
    std::printf("synthesized '%s' (%s model, ranks %lldx%lldx%lld, %s) -> %s\n", a.set.c_str(), model->kind(),
                static_cast<long long>(ranks[0]), static_cast<long long>(ranks[1]), static_cast<long long>(ranks[2]),
                predictor.c_str(), a.out.c_str());
    std::printf("  %-16s %14s %14s\n", "parameter", "requested", "measured");
    for (std::size_t k = 0; k < set.parameter_names.size(); ++k) {
        const std::string unit = set.parameter_units[k].empty() ? "" : " " + set.parameter_units[k];
        const std::optional<double>& m = o.parameter_measured[k];
        std::printf("  %-16s %14s %14s\n", set.parameter_names[k].c_str(),
                    (parameter_value_text(set, k, c(static_cast<Eigen::Index>(k))) + unit).c_str(),
                    m ? (parameter_value_text(set, k, *m) + unit).c_str() : "-");
    }
    std::printf("  reliability %.3f; %zu frames at %g Hz (%.2f s)%s\n", rho, clip.frame_count(), clip.frame_rate,
                clip.duration(),
                timing.clamped ? (", " + std::to_string(timing.clamped) + " timing increments clamped").c_str() : "");
    if (!o.measurements.empty()) {
        std::printf("  measured:");
        for (std::size_t k = 0; k < o.measurements.size(); ++k)
            std::printf("%s %s = %g%s%s", k ? "," : "", o.measurements[k].name.c_str(), o.measurements[k].value,
                        o.measurements[k].unit.empty() ? "" : " ", o.measurements[k].unit.c_str());
        std::printf("\n");
    }
    std::printf("  time: load + precompute %.3f s, synthesis %.4f s\n", load_s, synth_s);
}

}  // namespace

void setup_synth(CLI::App& app) {
    auto a = std::make_shared<SynthArgs>();
    CLI::App* cmd = app.add_subcommand("synth", "Synthesize a set's motion at new control parameters (BVH)");
    cmd->footer(
        "Example:\n"
        "  mocapdb synth db.h5 --set walks --param 0.3,130 -o walk.bvh\n"
        "  mocapdb synth db.h5 --set gaits --param gait=run,turn=0.3 -o run.bvh\n"
        "--param gives one value per parameter of the set, in the set's order and units (mocapdb set show), or\n"
        "NAME=VALUE pairs in any order; a categorical parameter takes one of its levels. Every extractor that\n"
        "applies (displacement, turn, speed, bearing, and the set's own) is measured back on the result.\n"
        "The compressed model needs `mocapdb compress` first; --naive krigs the uncompressed aligned tensor.\n"
        "--lod R1xR2xR3 synthesizes with the leading ranks only (level of detail). --timing separate krigs\n"
        "the timing with its own kernel (the paper); shared (default) blends it with the poses' weights.\n"
        "--predictor: `compress` chooses kriging, RBF or the trend by cross-validation (mocapdb set show).");
    cmd->add_option("db", a->db, "database file")->required()->check(CLI::ExistingFile);
    cmd->add_option("--set", a->set, "motion set")->required();
    cmd->add_option("--param", a->param, "control parameters v1,v2,... or name=v,... (a category: its level)")
        ->required();
    cmd->add_option("-o,--output", a->out, "file to write: .bvh, or glTF .gltf / .glb")->required();
    cmd->add_option("--lod", a->lod, "level of detail: ranks R1xR2xR3");
    cmd->add_option("--timing", a->timing, "timing kernel: shared | separate")
        ->check(CLI::IsMember({"shared", "separate"}));
    add_predictor_option(cmd, a->predictor);
    cmd->add_flag("--naive", a->naive, "kriging on the uncompressed aligned tensor");
    cmd->add_flag("--json", a->json, "machine-readable output");
    cmd->add_flag("--force", a->force, "overwrite an existing output file");
    cmd->callback([a] { run_synth(*a); });
}

}  // namespace mocapdb::cli
