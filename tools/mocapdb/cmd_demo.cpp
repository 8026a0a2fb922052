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
#include "mocapdb_json/step_json.hpp"
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

// One synthesis of the demo: where it was asked, what came back.
struct DemoSynthesis {
    std::string label;   // "between samples" / "outside the samples" / "requested"
    bool inside = true;  // within the samples' bounding box
    workflow::SynthOutcome outcome;
    VecX measured;  // by the set's extractors, or the reach target measurement
    fs::path file;
};

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

void write_values(JsonWriter& j, const std::string& key, const VecX& v) {
    j.key(key).begin_array();
    for (Eigen::Index k = 0; k < v.size(); ++k) j.value(v(k));
    j.end_array();
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

void run_demo(const DemoArgs& a) {
    const auto start = SteadyClock::now();
    const fs::path out = a.out;
    const fs::path db = out / "demo.h5";
    const bool procedural = a.data.empty();
    if (!procedural && a.motion != "reach")
        throw InvalidArgument("--motion chooses the procedural set; it does not apply with --data");
    if (procedural && (!a.clips.empty() || !a.extract.empty() || a.fps > 0.0))
        throw InvalidArgument("--clips, --extract and --fps apply with --data only");
    std::error_code ec;
    const auto refuse = [&](const std::string& name) {
        throw InvalidArgument(out.string() + " already holds the outputs of a demo (" + name +
                              "); pass --force to replace them, or choose another --out");
    };
    for (const char* name : {"demo.h5", "report.json", "samples"})
        if (fs::exists(out / name, ec) && !a.force) refuse(name);
    fs::create_directories(out, ec);
    if (ec) throw IoError(out.string() + ": cannot create the output folder: " + ec.message());
    for (const auto& entry : fs::directory_iterator(out)) {  // stale syntheses of an earlier run
        const std::string name = entry.path().filename().string();
        if (name.rfind("synth_", 0) != 0 || entry.path().extension() != ".bvh") continue;
        if (!a.force) refuse(name);
        fs::remove(entry.path());
    }

    // 1. The clips: generated (BVH + params.csv) or the given folder.
    JsonWriter j;
    j.begin_object();
    j.key("mode").value(procedural ? "procedural-" + a.motion : std::string("data"));
    j.key("out").value(out.string());
    std::vector<fs::path> inputs;
    SetRequest set_request;
    set_request.replace = true;
    procedural::ReachGrid reach_grid;
    std::string set_name;
    double generate_s = 0.0;
    if (procedural) {
        const auto t = SteadyClock::now();
        procedural::ParametricSet generated;
        if (a.motion == "reach") {
            set_name = "reaches";
            procedural::apply_grid_specs(reach_grid, {"angle=-90:90:7", "height=70:150:3"});
            progress("generating reaches of the built-in humanoid (analytic IK; target angle x height)\n");
            generated = procedural::generate_reach_set(reach_grid);
        } else {
            set_name = "walks";
            procedural::WalkGrid grid;
            grid.options.cycles = 2;
            procedural::apply_grid_specs(grid, {"speed=0.8:1.8:3", "turn=-90:90:5"});
            progress("generating walks of the built-in humanoid (planted feet, leg IK; speed x turn)\n");
            generated = procedural::generate_walk_set(grid);
        }
        const auto paths = procedural::write_parametric_set(out / "samples", generated, a.force);
        generate_s = seconds_since(t);
        inputs.push_back(out / "samples");
        set_request.clips = {generated.kind + "_*"};
        set_request.params_csv = paths.back();
        progress("wrote " + std::to_string(generated.clips.size()) + " BVH files and " + paths.back().string() + "\n");
    } else {
        set_name = "motions";
        inputs.push_back(a.data);
        set_request.clips = a.clips.empty() ? std::vector<std::string>{"*"} : a.clips;
        set_request.extract = a.extract.empty() ? std::vector<std::string>{"turn", "speed"} : a.extract;
    }
    set_request.name = set_name;

    // 2. Import.
    workflow::ImportOptions import_options;
    if (a.fps > 0.0) import_options.frame_rate = a.fps;
    const ImportOutcome imported = import_clips(db, inputs, import_options, true, std::cerr);
    progress(describe_import(db, imported));

    // 3. The set, 4. alignment, 5. compression.
    const SetOutcome built = create_set(db.string(), set_request);
    progress(describe_set(built));
    const MotionSet& set = built.set;
    if (set.samples.size() < 3)
        throw InvalidArgument("the demo needs at least 3 samples, the set has " + std::to_string(set.samples.size()));
    AlignRequest align_request;
    align_request.set = set_name;
    align_request.frames = a.frames;
    progress("aligning (DTW) ...\n");
    const AlignOutcome aligned = align_set(db.string(), align_request);
    progress(describe_alignment(set_name, aligned));
    CompressRequest compress_request;
    compress_request.set = set_name;
    compress_request.max_error_cm = a.max_error_cm;
    progress("compressing ...\n");
    const CompressOutcome compressed = compress_set(db.string(), compress_request);
    progress(describe_compression(set_name, compressed));

    // 6. The rate-distortion table.
    progress("rate-distortion table (Tucker, PCA, zfp, deflate) ...\n");
    const auto rd_start = SteadyClock::now();
    compression::RateOptions rate_options;
    std::set<double> targets = a.quick ? std::set<double>{2.0, 1.0} : std::set<double>{5.0, 2.0, 1.0, 0.5, 0.2, 0.1};
    targets.insert(a.max_error_cm);
    rate_options.hooi = !a.quick;
    rate_options.max_cm.assign(targets.rbegin(), targets.rend());
    const workflow::AlignedSetData context = workflow::load_aligned_set(Database(db), set_name);
    const RateOutcome rate = workflow::rate_report(context, rate_options);
    const double rd_s = seconds_since(rd_start);
    const std::string rd_svg = rate_svg(set_name, rate);
    write_file_atomically(out / "rate_distortion.svg", [&](std::ostream& o) { o << rd_svg; });
    std::printf("== compression (model stored in %s: ranks %s, max joint error %.3f cm, ratio %.2f:1)\n",
                db.string().c_str(), ranks_text(compressed.model.tucker.ranks).c_str(), compressed.stats.max_cm,
                compressed.ratio());
    std::fputs(rate_table_text(set_name, rate).c_str(), stdout);

    // 7. Synthesis at new parameters.
    const auto model_start = SteadyClock::now();
    const auto model = load_synthesis_model(Database(db), set_name, false, "");
    const double model_s = seconds_since(model_start);
    const MatX& samples = model->sample_parameters();
    const auto& names = set.parameter_names;
    const auto& units = set.parameter_units;
    std::vector<VecX> targets_in;
    if (!a.at.empty()) {
        for (const std::string& text : a.at) targets_in.push_back(parse_parameters(text, names, units, "--at"));
    } else if (procedural && a.motion == "reach") {
        targets_in = workflow::reach_cell_centres(reach_grid);
        if (a.quick) targets_in.resize(std::min<std::size_t>(targets_in.size(), 3));
    } else {
        targets_in = workflow::between_samples(samples, a.quick ? 3 : 5);
    }
    std::vector<std::pair<VecX, std::string>> requests;
    for (const VecX& c : targets_in) requests.push_back({c, a.at.empty() ? "between samples" : "requested"});
    if (a.at.empty()) {
        // Outside: from the samples' mean along one parameter axis, one sampled range of that parameter
        // beyond the samples; of the 2P such points, the one the model trusts least.
        requests.push_back({workflow::least_trusted_outside(*model), "outside the samples"});
    }
    const workflow::DemoMeasurement measurement = workflow::choose_measurement(set, *model->skeleton());
    std::string measured_what = "nothing (the set's parameters were neither extracted nor reach targets)";
    if (measurement.kind == workflow::DemoMeasure::Extractors)
        measured_what = "the extractors (" + measurement.extractor_names + ") on the whole synthesized clip";
    else if (measurement.kind == workflow::DemoMeasure::ReachTarget)
        measured_what =
            "the right hand's end site at the hold (its slowest frame among those at least 80% of its "
            "largest distance from the start): bearing around the origin's vertical axis [deg], "
            "height [cm], horizontal distance [cm]";

    std::printf("\n== synthesis at new parameters (%s model, ranks %s; %zu samples; parameters: %s)\n", model->kind(),
                ranks_text(model->level_ranks(0)).c_str(), set.samples.size(),
                describe_parameters(names, units).c_str());
    const kriging::VariogramModel& vg = model->report().model;
    std::printf(
        "   kriging: variogram p = %g, nugget %.4g, sill %.4g, range %.4g (normalized parameters: each axis "
        "to zero mean, unit deviation); rho = 1 - variance / (nugget + sill)\n",
        vg.paper_p(), vg.nugget, vg.sill, vg.range);
    std::printf("   measured: %s\n", measured_what.c_str());
    std::vector<DemoSynthesis> results;
    for (std::size_t q = 0; q < requests.size(); ++q) {
        DemoSynthesis s;
        s.label = requests[q].second;
        s.inside = workflow::inside_box(samples, requests[q].first);
        s.outcome = workflow::synthesize(*model, set, requests[q].first);
        s.measured = workflow::measure_synthesis(measurement, s.outcome.clip, names);
        char name[64];
        std::snprintf(name, sizeof name, "synth_%02zu%s.bvh", q + 1, s.inside ? "" : "_outside");
        s.file = out / name;
        write_bvh(s.file, s.outcome.clip);
        std::printf("%-20s requested %s\n", (std::string(name)).c_str(),
                    values_text(s.outcome.requested, units).c_str());
        std::printf("%-20s measured  %s\n", "",
                    s.measured.size() == s.outcome.requested.size() ? values_text(s.measured, units).c_str() : "-");
        std::printf("%-20s rho %.4f, %zu frames (%.2f s), synthesized in %.4f s; %s%s\n", "", s.outcome.reliability,
                    s.outcome.clip.frame_count(), s.outcome.clip.duration(), s.outcome.seconds, s.label.c_str(),
                    workflow::is_low_reliability(s.outcome.reliability)
                        ? "\n                     warning: reliability below 0.5: far from the samples, extrapolated"
                        : "");
        results.push_back(std::move(s));
    }

    // 8. The reliability map over the first two parameters (padded beyond the samples).
    bool have_map = false;
    workflow::ReliabilityMap map;
    HeatMapSpec map_spec;
    if (model->parameters() >= 2) {
        std::vector<VecX> points;  // the samples and every synthesized point, with a margin
        for (const auto& r : requests) points.push_back(r.first);
        const workflow::SliceAxis gx = workflow::padded_axis(samples, points, 0, 41);
        const workflow::SliceAxis gy = workflow::padded_axis(samples, points, 1, 41);
        const VecX base = workflow::samples_mean(*model);
        map = workflow::reliability_map(*model, gx, gy, base);
        map_spec = reliability_heat_map(*model, set_name, gx, gy, base, map);
        const std::string svg = render_heat_map(map_spec);
        write_file_atomically(out / "reliability.svg", [&](std::ostream& o) { o << svg; });
        have_map = true;
    }

    // 9. report.json and README.txt.
    const double total_s = seconds_since(start);
    j.key("database").value(db.string());
    j.key("import").begin_object();
    j.key("files").value(imported.summary.files).key("clips").value(imported.summary.added);
    j.key("frames").value(imported.summary.frames).key("seconds_of_motion").value(imported.summary.seconds);
    j.key("bytes_read").value(static_cast<long long>(imported.summary.bytes_read));
    j.key("seconds").value(imported.seconds).end_object();
    j.key("set").begin_object();
    j.key("name").value(set_name).key("parameter_source").value(set.parameter_source);
    j.key("samples").value(set.samples.size());
    j.key("parameters").begin_array();
    for (std::size_t p = 0; p < names.size(); ++p)
        j.begin_object().key("name").value(names[p]).key("unit").value(units[p]).end_object();
    j.end_array();
    j.key("values").begin_array();
    for (Eigen::Index n = 0; n < set.parameters.rows(); ++n) {
        j.begin_array();
        for (Eigen::Index k = 0; k < set.parameters.cols(); ++k) j.value(set.parameters(n, k));
        j.end_array();
    }
    j.end_array().end_object();
    j.key("align").begin_object();
    j.key("method").value(aligned.aligned.method).key("frames").value(static_cast<long long>(aligned.aligned.frames()));
    j.key("dofs").value(static_cast<long long>(aligned.aligned.dofs()));
    j.key("reference").value(aligned.labels[aligned.aligned.reference]);
    j.key("mean_distance_cm").value(aligned.distance).key("seconds").value(aligned.seconds).end_object();
    j.key("compress");
    json::write_compression(j, set_name, compressed);
    j.key("rate_distortion").begin_object();
    j.key("raw_bytes").value(static_cast<long long>(rate.report.raw_bytes));
    j.key("side_bytes").value(static_cast<long long>(rate.report.side_bytes));
    j.key("seconds_of_motion").value(rate.seconds);
    write_rate_rows_json(j, rate);
    j.key("seconds").value(rd_s).end_object();
    j.key("synthesis").begin_object();
    j.key("model").value(model->kind()).key("precompute_s").value(model->report().precompute_seconds);
    j.key("load_s").value(model_s).key("measured_with").value(measured_what);
    j.key("variogram").begin_object().key("p").value(vg.paper_p()).key("nugget").value(vg.nugget);
    j.key("sill").value(vg.sill).key("range").value(vg.range).end_object();
    j.key("motions").begin_array();
    for (const DemoSynthesis& s : results) {
        j.begin_object();
        j.key("file").value(s.file.filename().string()).key("where").value(s.label).key("inside").value(s.inside);
        write_values(j, "requested", s.outcome.requested);
        if (s.measured.size() == s.outcome.requested.size()) write_values(j, "measured", s.measured);
        j.key("reliability").value(s.outcome.reliability);
        j.key("frames").value(s.outcome.clip.frame_count()).key("frame_rate").value(s.outcome.clip.frame_rate);
        j.key("duration_s").value(s.outcome.clip.duration());
        j.key("clamped_increments").value(static_cast<long long>(s.outcome.timing.clamped));
        j.key("seconds").value(s.outcome.seconds);
        j.end_object();
    }
    j.end_array().end_object();
    if (have_map) {
        j.key("reliability_map").begin_object();
        j.key("file").value("reliability.svg");
        j.key("x").value(names[0]).key("y").value(names[1]);
        j.key("x_range").begin_array().value(map_spec.x_lo).value(map_spec.x_hi).end_array();
        j.key("y_range").begin_array().value(map_spec.y_lo).value(map_spec.y_hi).end_array();
        j.key("cells").value(static_cast<long long>(map.rho.size()));
        j.key("min").value(map.rho_min).key("mean").value(map.rho_mean).key("max").value(map.rho_max);
        j.key("fraction_ge_0_85").value(map.fraction_trusted).end_object();
    }
    j.key("timings_s").begin_object();
    j.key("generate").value(generate_s).key("import").value(imported.seconds).key("align").value(aligned.seconds);
    j.key("compress").value(compressed.total_s).key("rate_distortion").value(rd_s).key("model").value(model_s);
    j.key("total").value(total_s).end_object();
    j.end_object();
    const std::string report = j.str();
    write_file_atomically(out / "report.json", [&](std::ostream& o) { o << report; });
    write_file_atomically(out / "README.txt", [&](std::ostream& o) { o << kReadme; });

    std::printf("\n== outputs in %s (%.1f s in all)\n", out.string().c_str(), total_s);
    std::printf("  demo.h5  report.json  README.txt  rate_distortion.svg%s  %zu synth_*.bvh%s\n",
                have_map ? "  reliability.svg" : "", results.size(), procedural ? "  samples/" : "");
    if (!have_map) std::printf("  (no reliability.svg: the set has a single parameter)\n");
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
