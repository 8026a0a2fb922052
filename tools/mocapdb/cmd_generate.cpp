// mocapdb generate walk|reach --out DIR: a procedural parametric motion set (BVH files + params.csv).
#include <cstdio>
#include <iostream>

#include "commands.hpp"
#include "json_writer.hpp"
#include "mocapdb_json/clip_json.hpp"
#include "mocapdb/core/error.hpp"
#include "mocapdb/procedural/parametric_set.hpp"

namespace mocapdb::cli {
namespace {

struct GenerateArgs {
    std::string out;
    std::vector<std::string> grid;
    double fps = 60.0;
    int cycles = 3;
    int precision = 9;
    bool force = false;
    bool json = false;
};

void report(const procedural::ParametricSet& set, const std::vector<std::filesystem::path>& paths,
            const GenerateArgs& a) {
    if (a.json) {
        JsonWriter j;
        json::write_generated_set(j, a.out, set, paths);
        std::cout << j.str();
        return;
    }
    std::printf("%-24s %7s", "clip", "frames");
    for (std::size_t p = 0; p < set.parameter_names.size(); ++p) {
        const std::string h = set.parameter_names[p] + " [" + set.parameter_units[p] + "]";
        std::printf(" %14s", h.c_str());
    }
    std::printf("\n");
    for (std::size_t i = 0; i < set.clips.size(); ++i) {
        std::printf("%-24s %7zu", set.clips[i].name.c_str(), set.clips[i].frame_count());
        for (Eigen::Index p = 0; p < set.parameters.cols(); ++p)
            std::printf(" %14.4f", set.parameters(static_cast<Eigen::Index>(i), p));
        std::printf("\n");
    }
    std::printf("wrote %zu BVH files and %s\n", set.clips.size(), paths.back().string().c_str());
    std::printf("next: mocapdb import %s -o DB.h5 && mocapdb set create DB.h5 --name %s --clips '%s_*' --params %s\n",
                a.out.c_str(), set.kind == "reach" ? "reaches" : "walks", set.kind.c_str(),
                paths.back().string().c_str());
}

void add_common(CLI::App& cmd, GenerateArgs& a) {
    cmd.add_option("-o,--out", a.out, "output folder (created)")->required();
    cmd.add_option("--grid", a.grid, "grid axes NAME=LOW:HIGH:COUNT or NAME=VALUE (several)");
    cmd.add_option("--fps", a.fps, "frame rate, Hz")->check(CLI::Range(10.0, 1000.0));
    cmd.add_option("--precision", a.precision, "significant digits written in the BVH files")->check(CLI::Range(1, 17));
    cmd.add_flag("--force", a.force, "overwrite existing files");
    cmd.add_flag(
        "--json", a.json,
        "print JSON: {kind, folder, params_csv, parameters:[{name,unit}], clips:[{name,file,frames,frame_rate,values}]}");
}

}  // namespace

void setup_generate(CLI::App& app) {
    CLI::App* cmd =
        app.add_subcommand("generate", "Generate a procedural parametric motion set (BVH files + params.csv)");
    cmd->require_subcommand(1);
    cmd->footer(
        "The built-in humanoid (170 cm, Y up, facing +Z) walks or reaches; every grid point becomes one BVH\n"
        "file named after its parameters, and params.csv (header 'sample,NAME[UNIT],...') holds the\n"
        "parameters of the axes that vary, ready for: mocapdb import DIR -o DB.h5; mocapdb set create DB.h5\n"
        "--name walks --clips 'walk_*' --params DIR/params.csv (or --extract speed turn: same values).");

    auto w = std::make_shared<GenerateArgs>();
    CLI::App* walk =
        cmd->add_subcommand("walk", "Walks along arcs: speed (m/s) x turn (deg over the clip) [x stride (m)]");
    walk->footer(
        "Examples:\n"
        "  mocapdb generate walk --out gen/walks --grid speed=0.9:1.7:3 turn=-60:60:5\n"
        "  mocapdb generate walk --out gen/one --grid speed=1.3 turn=30 --cycles 4\n"
        "Axes (defaults): speed=0.9:1.7:3 (0.4..1.9 m/s), turn=-60:60:5 (deg, + = left, |turn| <= 180),\n"
        "stride=0 (m; 0 = from speed, else 0.6..2.0). CSV columns: speed[cm/s], turn[rad] (the extractors'\n"
        "definitions, which the generator meets exactly), stride[cm] when it varies.");
    add_common(*walk, *w);
    walk->add_option("--cycles", w->cycles, "whole gait cycles per clip")->check(CLI::Range(1, 20));
    walk->callback([w] {
        procedural::WalkGrid grid;
        procedural::apply_grid_specs(grid, w->grid);
        grid.options.frame_rate = w->fps;
        grid.options.cycles = w->cycles;
        const auto set = procedural::generate_walk_set(grid);
        report(set, procedural::write_parametric_set(w->out, set, w->force, w->precision), *w);
    });

    auto r = std::make_shared<GenerateArgs>();
    CLI::App* reach =
        cmd->add_subcommand("reach", "Right-hand reaches to targets: angle (deg) x height (cm) x distance (cm)");
    reach->footer(
        "Examples:\n"
        "  mocapdb generate reach --out gen/reach --grid angle=-90:90:5 height=60:160:3\n"
        "  mocapdb generate reach --out gen/one --grid angle=45 height=120 distance=60\n"
        "Axes (defaults): angle=-90:90:5 (deg around the body, 0 ahead, + = left, |angle| <= 150),\n"
        "height=60:160:3 (cm above the floor, 30..200), distance=55 (cm from the body's axis, 20..95).\n"
        "Targets out of the arm's reach are refused with the grid point named. CSV columns: the axes that\n"
        "vary, angle[deg], height[cm], distance[cm].");
    add_common(*reach, *r);
    reach->callback([r] {
        procedural::ReachGrid grid;
        procedural::apply_grid_specs(grid, r->grid);
        grid.options.frame_rate = r->fps;
        const auto set = procedural::generate_reach_set(grid);
        report(set, procedural::write_parametric_set(r->out, set, r->force, r->precision), *r);
    });
}

}  // namespace mocapdb::cli
