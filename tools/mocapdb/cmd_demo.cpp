// mocapdb demo [--data DIR] [--out DIR]: the main job end to end on one database. Without --data a
// procedural parametric set (reaches by default, or walks) is generated as BVH files; with --data the
// clips of a folder are used. Then: import, set, DTW alignment, compression to a max joint error, the
// rate-distortion table, synthesis at new parameters (inside and outside the sampled region) with the
// measured parameters and reliability of each result, the reliability map and the report files.
#include <chrono>
#include <cstdio>
#include <iostream>
#include <set>
#include <sstream>

#include "clip_options.hpp"
#include "commands.hpp"
#include "json_writer.hpp"
#include "mocapdb_json/demo_json.hpp"
#include "mocapdb/core/stopwatch.hpp"
#include "mocapdb/core/error.hpp"
#include "mocapdb/io/bvh.hpp"
#include "mocapdb/io/text_file.hpp"
#include "mocapdb/procedural/parametric_set.hpp"
#include "mocapdb/store/database.hpp"
#include "mocapdb/workflow/aligned_set_data.hpp"
#include "mocapdb/workflow/demo_queries.hpp"
#include "mocapdb/workflow/reliability_map.hpp"
#include "mocapdb/workflow/set_rate_report.hpp"
#include "mocapdb/workflow/synthesis_step.hpp"
#include "mocapdb/workflow/synthesis_warnings.hpp"
#include "pipeline.hpp"
#include "svg_heatmap.hpp"
#include "synthesis_cli.hpp"

namespace mocapdb::cli {
namespace {

namespace fs = std::filesystem;

struct DemoArgs {
    std::string data;
    std::string out = "demo-out";
    std::string motion = "reach";
    std::vector<std::string> clips;
    std::vector<std::string> extract;
    double fps = 0.0;
    long long frames = 60;
    double max_error_cm = 1.0;
    std::vector<std::string> at;
    bool quick = false;
    bool force = false;
};

void progress(const std::string& line) {
    std::fflush(stdout);
    std::cerr << "demo: " << line << std::flush;
}

std::string values_text(const VecX& v, const std::vector<std::string>& units) {
    std::ostringstream s;
    s.setf(std::ios::fixed);
    s.precision(2);
    for (Eigen::Index k = 0; k < v.size(); ++k) {
        s << (k ? ", " : "") << v(k);
        const std::string& u = units[static_cast<std::size_t>(k)];
        if (!u.empty()) s << " " << u;
    }
    return s.str();
}

const char* kReadme =
    "mocapdb demo: what each file is\n"
    "\n"
    "demo.h5              the motion database (HDF5, schemas/format-v4.md): the imported clips, the motion\n"
    "                     set with its control parameters, the DTW-aligned pose tensor and the compressed\n"
    "                     Tucker model the synthesis uses (mocapdb info demo.h5; README.md shows h5py).\n"
    "samples/             (procedural runs) the generated clips as BVH files and params.csv, the control\n"
    "                     parameters of each clip: the input of the import.\n"
    "synth_*.bvh          motions synthesized at new control parameters (report.json lists them with the\n"
    "                     requested and measured parameters and their reliability). Open them in Blender:\n"
    "                     File > Import > Motion Capture (.bvh).\n"
    "rate_distortion.svg  compression ratio against max joint-position error for every method of the table\n"
    "                     (as mocapdb report --svg).\n"
    "reliability.svg      reliability rho of synthesis over a 2-D slice of the control space with the\n"
    "                     samples marked (as mocapdb reliability): 1 at the samples, towards 0 far from them.\n"
    "report.json          every number the demo printed: import, set, alignment, compression, the\n"
    "                     rate-distortion rows, each synthesis, the reliability map, timings.\n"
    "README.txt           this file.\n";

/// Refuses an output folder holding a demo's outputs unless --force; creates it; removes stale syntheses.
void prepare_output(const fs::path& out, bool force) {
    std::error_code ec;
    const auto refuse = [&](const std::string& name) {
        throw InvalidArgument(out.string() + " already holds the outputs of a demo (" + name +
                              "); pass --force to replace them, or choose another --out");
    };
    for (const char* name : {"demo.h5", "report.json", "samples"})
        if (fs::exists(out / name, ec) && !force) refuse(name);
    fs::create_directories(out, ec);
    if (ec) throw IoError(out.string() + ": cannot create the output folder: " + ec.message());
    for (const auto& entry : fs::directory_iterator(out)) {  // stale syntheses of an earlier run
        const std::string name = entry.path().filename().string();
        if (name.rfind("synth_", 0) != 0 || entry.path().extension() != ".bvh") continue;
        if (!force) refuse(name);
        fs::remove(entry.path());
    }
}

/// What the import and the set are made from.
struct DemoInputs {
    std::vector<fs::path> inputs;
    SetRequest set_request;
    procedural::ReachGrid reach_grid;  ///< of the procedural reaches
};

/// 1. The clips: generated (BVH + params.csv) or the given folder.
DemoInputs choose_inputs(const DemoArgs& a, bool procedural, const fs::path& out, json::DemoReport& r) {
    DemoInputs in;
    in.set_request.replace = true;
    if (procedural) {
        const auto t = SteadyClock::now();
        procedural::ParametricSet generated;
        if (a.motion == "reach") {
            r.set_name = "reaches";
            procedural::apply_grid_specs(in.reach_grid, {"angle=-90:90:7", "height=70:150:3"});
            progress("generating reaches of the built-in humanoid (analytic IK; target angle x height)\n");
            generated = procedural::generate_reach_set(in.reach_grid);
        } else {
            r.set_name = "walks";
            procedural::WalkGrid grid;
            grid.options.cycles = 2;
            procedural::apply_grid_specs(grid, {"speed=0.8:1.8:3", "turn=-90:90:5"});
            progress("generating walks of the built-in humanoid (planted feet, leg IK; speed x turn)\n");
            generated = procedural::generate_walk_set(grid);
        }
        const auto paths = procedural::write_parametric_set(out / "samples", generated, a.force);
        r.generate_s = seconds_since(t);
        in.inputs.push_back(out / "samples");
        in.set_request.clips = {generated.kind + "_*"};
        in.set_request.params_csv = paths.back();
        progress("wrote " + std::to_string(generated.clips.size()) + " BVH files and " + paths.back().string() + "\n");
    } else {
        r.set_name = "motions";
        in.inputs.push_back(a.data);
        in.set_request.clips = a.clips.empty() ? std::vector<std::string>{"*"} : a.clips;
        in.set_request.extract = a.extract.empty() ? std::vector<std::string>{"turn", "speed"} : a.extract;
    }
    in.set_request.name = r.set_name;
    return in;
}

/// 2. Import, 3. the set, 4. alignment, 5. compression.
void build_model(const DemoArgs& a, const DemoInputs& in, json::DemoReport& r) {
    const fs::path db = r.database;
    workflow::ImportOptions import_options;
    if (a.fps > 0.0) import_options.frame_rate = a.fps;
    r.imported = import_clips(db, in.inputs, import_options, true, std::cerr);
    progress(describe_import(db, r.imported));
    r.set = create_set(r.database, in.set_request);
    progress(describe_set(r.set));
    const MotionSet& set = r.set.set;
    if (set.samples.size() < 3)
        throw InvalidArgument("the demo needs at least 3 samples, the set has " + std::to_string(set.samples.size()));
    AlignRequest align_request;
    align_request.set = r.set_name;
    align_request.frames = a.frames;
    progress("aligning (DTW) ...\n");
    r.aligned = align_set(r.database, align_request);
    progress(describe_alignment(r.set_name, r.aligned));
    CompressRequest compress_request;
    compress_request.set = r.set_name;
    compress_request.max_error_cm = a.max_error_cm;
    progress("compressing ...\n");
    r.compressed = compress_set(r.database, compress_request);
    progress(describe_compression(r.set_name, r.compressed));
}

/// 6. The rate-distortion table (printed, and rate_distortion.svg).
void rate_distortion(const DemoArgs& a, const fs::path& out, json::DemoReport& r) {
    progress("rate-distortion table (Tucker, PCA, zfp, deflate) ...\n");
    const auto rd_start = SteadyClock::now();
    compression::RateOptions rate_options;
    std::set<double> targets = a.quick ? std::set<double>{2.0, 1.0} : std::set<double>{5.0, 2.0, 1.0, 0.5, 0.2, 0.1};
    targets.insert(a.max_error_cm);
    rate_options.hooi = !a.quick;
    rate_options.max_cm.assign(targets.rbegin(), targets.rend());
    const workflow::AlignedSetData context = workflow::load_aligned_set(Database(r.database), r.set_name);
    r.rate = workflow::rate_report(context, rate_options);
    r.rate_s = seconds_since(rd_start);
    const std::string rd_svg = rate_svg(r.set_name, r.rate);
    write_file_atomically(out / "rate_distortion.svg", [&](std::ostream& o) { o << rd_svg; });
    std::printf("== compression (model stored in %s: ranks %s, max joint error %.3f cm, ratio %.2f:1)\n",
                r.database.c_str(), ranks_text(r.compressed.model.tucker.ranks).c_str(), r.compressed.stats.max_cm,
                r.compressed.ratio());
    std::fputs(rate_table_text(r.set_name, r.rate).c_str(), stdout);
}

/// 7. Synthesis at new parameters: between the samples (or --at) and outside them; synth_*.bvh.
void synthesize_new(const DemoArgs& a, const DemoInputs& in, bool procedural, const fs::path& out,
                    const synthesis::SynthesisModel& model, json::DemoReport& r) {
    const MotionSet& set = r.set.set;
    const MatX& samples = model.sample_parameters();
    const auto& names = set.parameter_names;
    const auto& units = set.parameter_units;
    std::vector<VecX> targets_in;
    if (!a.at.empty()) {
        for (const std::string& text : a.at) targets_in.push_back(parse_parameters(text, set, "--at"));
    } else if (procedural && a.motion == "reach") {
        targets_in = workflow::reach_cell_centres(in.reach_grid);
        if (a.quick) targets_in.resize(std::min<std::size_t>(targets_in.size(), 3));
    } else {
        targets_in = workflow::between_samples(samples, a.quick ? 3 : 5);
    }
    std::vector<std::pair<VecX, std::string>> requests;
    for (const VecX& c : targets_in) requests.push_back({c, a.at.empty() ? "between samples" : "requested"});
    if (a.at.empty()) {
        // Outside: from the samples' mean along one parameter axis, one sampled range of that parameter
        // beyond the samples; of the 2P such points, the one the model trusts least.
        requests.push_back({workflow::least_trusted_outside(model), "outside the samples"});
    }
    const workflow::DemoMeasurement measurement = workflow::choose_measurement(set, *model.skeleton());
    json::DemoSyntheses& syn = r.synthesis;
    syn.model = model.kind();
    syn.precompute_s = model.report().precompute_seconds;
    syn.variogram = model.report().model;
    syn.measured_with = "nothing (the set's parameters were neither extracted nor reach targets)";
    if (measurement.kind == workflow::DemoMeasure::Extractors)
        syn.measured_with = "the extractors (" + measurement.extractor_names + ") on the whole synthesized clip";
    else if (measurement.kind == workflow::DemoMeasure::ReachTarget)
        syn.measured_with =
            "the right hand's end site at the hold (its slowest frame among those at least 80% of its "
            "largest distance from the start): bearing around the origin's vertical axis [deg], "
            "height [cm], horizontal distance [cm]";

    std::printf("\n== synthesis at new parameters (%s model, ranks %s; %zu samples; parameters: %s)\n", model.kind(),
                ranks_text(model.level_ranks(0)).c_str(), set.samples.size(), describe_parameters(set).c_str());
    const kriging::VariogramModel& vg = syn.variogram;
    std::printf(
        "   kriging: variogram p = %g, nugget %.4g, sill %.4g, range %.4g (normalized parameters: each axis "
        "to zero mean, unit deviation); rho = 1 - variance / (nugget + sill)\n",
        vg.paper_p(), vg.nugget, vg.sill, vg.range);
    std::printf("   measured: %s\n", syn.measured_with.c_str());
    for (std::size_t q = 0; q < requests.size(); ++q) {
        json::DemoSynthesis s;
        s.where = requests[q].second;
        s.inside = workflow::inside_box(samples, requests[q].first);
        s.outcome = workflow::synthesize(model, set, requests[q].first);
        s.measured = workflow::measure_synthesis(measurement, s.outcome.clip, names);
        char name[64];
        std::snprintf(name, sizeof name, "synth_%02zu%s.bvh", q + 1, s.inside ? "" : "_outside");
        s.file = name;
        write_bvh(out / s.file, s.outcome.clip);
        std::printf("%-20s requested %s\n", name, values_text(s.outcome.requested, units).c_str());
        std::printf("%-20s measured  %s\n", "",
                    s.measured.size() == s.outcome.requested.size() ? values_text(s.measured, units).c_str() : "-");
        std::printf("%-20s rho %.4f, %zu frames (%.2f s), synthesized in %.4f s; %s\n", "", s.outcome.reliability,
                    s.outcome.clip.frame_count(), s.outcome.clip.duration(), s.outcome.seconds, s.where.c_str());
        // The warnings synth prints: the set's calibrated thresholds and the parameters measured back.
        for (const std::string& w : warning_lines(workflow::synthesis_warnings(model, s.outcome, set), set))
            std::printf("%-20s warning: %s\n", "", w.c_str());
        syn.motions.push_back(std::move(s));
    }
}

/// 8. The reliability map over the first two parameters (padded beyond the samples), reliability.svg.
void map_reliability(const fs::path& out, const synthesis::SynthesisModel& model, json::DemoReport& r) {
    if (model.parameters() < 2) return;
    const MatX& samples = model.sample_parameters();
    std::vector<VecX> points;  // the samples and every synthesized point, with a margin
    for (const json::DemoSynthesis& s : r.synthesis.motions) points.push_back(s.outcome.requested);
    const workflow::SliceAxis gx = workflow::padded_axis(samples, points, 0, 41);
    const workflow::SliceAxis gy = workflow::padded_axis(samples, points, 1, 41);
    const VecX base = workflow::samples_mean(model);
    json::DemoMap m;
    m.map = workflow::reliability_map(model, gx, gy, base);
    const HeatMapSpec spec = reliability_heat_map(model, r.set_name, gx, gy, base, m.map);
    const std::string svg = render_heat_map(spec);
    write_file_atomically(out / "reliability.svg", [&](std::ostream& o) { o << svg; });
    m.x = r.set.set.parameter_names[0];
    m.y = r.set.set.parameter_names[1];
    m.x_lo = spec.x_lo;
    m.x_hi = spec.x_hi;
    m.y_lo = spec.y_lo;
    m.y_hi = spec.y_hi;
    r.map = std::move(m);
}

void run_demo(const DemoArgs& a) {
    const auto start = SteadyClock::now();
    const fs::path out = a.out;
    const bool procedural = a.data.empty();
    if (!procedural && a.motion != "reach")
        throw InvalidArgument("--motion chooses the procedural set; it does not apply with --data");
    if (procedural && (!a.clips.empty() || !a.extract.empty() || a.fps > 0.0))
        throw InvalidArgument("--clips, --extract and --fps apply with --data only");
    prepare_output(out, a.force);

    json::DemoReport r;
    r.mode = procedural ? "procedural-" + a.motion : std::string("data");
    r.out = out.string();
    r.database = (out / "demo.h5").string();
    const DemoInputs in = choose_inputs(a, procedural, out, r);
    build_model(a, in, r);
    rate_distortion(a, out, r);
    const auto model_start = SteadyClock::now();
    const auto model = load_synthesis_model(Database(r.database), r.set_name, false, "");
    r.synthesis.load_s = seconds_since(model_start);
    synthesize_new(a, in, procedural, out, *model, r);
    map_reliability(out, *model, r);

    // 9. report.json and README.txt.
    r.total_s = seconds_since(start);
    JsonWriter j;
    json::write_demo_report(j, r);
    const std::string report = j.str();
    write_file_atomically(out / "report.json", [&](std::ostream& o) { o << report; });
    write_file_atomically(out / "README.txt", [&](std::ostream& o) { o << kReadme; });

    std::printf("\n== outputs in %s (%.1f s in all)\n", out.string().c_str(), r.total_s);
    std::printf("  demo.h5  report.json  README.txt  rate_distortion.svg%s  %zu synth_*.bvh%s\n",
                r.map ? "  reliability.svg" : "", r.synthesis.motions.size(), procedural ? "  samples/" : "");
    if (!r.map) std::printf("  (no reliability.svg: the set has a single parameter)\n");
}

}  // namespace

void setup_demo(CLI::App& app) {
    auto a = std::make_shared<DemoArgs>();
    CLI::App* cmd =
        app.add_subcommand("demo", "The main job end to end: import, set, align, compress, report, synthesize");
    cmd->footer(
        "Examples:\n"
        "  mocapdb demo --out demo-out\n"
        "  mocapdb demo --motion walk --out demo-walk\n"
        "  mocapdb demo --data ../shared/datasets/cmu-asfamc --clips '16_1?' '16_2?' --out demo-cmu\n"
        "Without --data the built-in humanoid's reaches (target angle x height, analytic IK, Fitts-law timing)\n"
        "or walks (speed x turn) are generated into OUT/samples as BVH files with params.csv; with --data the\n"
        "folder's BVH and ASF/AMC clips are used and their parameters measured (--extract, default turn\n"
        "speed). Then everything goes through OUT/demo.h5: import, set, DTW alignment, Tucker compression to\n"
        "--max-error-cm, the rate-distortion table (as mocapdb report), synthesis between the samples and\n"
        "outside them (requested and measured parameters, reliability rho), OUT/synth_*.bvh,\n"
        "OUT/rate_distortion.svg, OUT/reliability.svg, OUT/report.json, OUT/README.txt.");
    cmd->add_option("--data", a->data, "folder of BVH / ASF+AMC clips (default: a procedural set)")
        ->check(CLI::ExistingDirectory);
    cmd->add_option("-o,--out", a->out, "output folder (created)");
    cmd->add_option("--motion", a->motion, "procedural set: reach | walk")->check(CLI::IsMember({"reach", "walk"}));
    cmd->add_flag("--quick", a->quick, "fewer syntheses and a shorter table (for tests)");
    cmd->add_option("--clips", a->clips, "with --data: clip ids or shell patterns (quoted)");
    cmd->add_option("--extract", a->extract, "with --data: parameters measured from the motion (default: turn speed)");
    cmd->add_option("--fps", a->fps, "with --data: frame rate in Hz for every file")->check(frame_rate_check());
    cmd->add_option("--frames", a->frames, "aligned frames T")->check(CLI::Range(8LL, 2000LL));
    cmd->add_option("--max-error-cm", a->max_error_cm, "max joint error of the stored model (cm)")
        ->check(CLI::PositiveNumber);
    cmd->add_option("--at", a->at, "synthesize at these parameters v1,v2,... (several; default: chosen)");
    cmd->add_flag("--force", a->force, "replace the outputs of a previous demo in the folder");
    cmd->callback([a] { run_demo(*a); });
}

}  // namespace mocapdb::cli
