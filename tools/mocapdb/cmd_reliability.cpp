// mocapdb reliability: a heat map of the reliability rho over a 2-D slice of a set's control space,
// with the samples marked (the geostatistical paper's Figure 8).
#include <cstdio>
#include <ostream>
#include <sstream>

#include "commands.hpp"
#include "output_files.hpp"
#include "json_writer.hpp"
#include "mocapdb_json/synthesis_json.hpp"
#include "mocapdb/core/error.hpp"
#include "mocapdb/io/text_file.hpp"
#include "mocapdb/workflow/reliability_map.hpp"
#include "pipeline.hpp"
#include "svg_heatmap.hpp"
#include "synthesis_cli.hpp"

namespace mocapdb::cli {
namespace {

struct ReliabilityArgs {
    std::string db;
    std::string set;
    std::string grid;
    std::vector<std::string> fix;
    std::string svg;
    std::string csv;
    bool naive = false;
    bool json = false;
    bool force = false;
};

double number(const std::string& text, const std::string& what) {
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(v))
        throw InvalidArgument(what + ": '" + text + "' is not a finite number");
    return v;
}

workflow::SliceAxis parse_axis(const std::string& spec, const std::vector<std::string>& names) {
    const std::string usage = "--grid: expected AXIS=LO:HI:N (N >= 2), got '" + spec + "'";
    const auto eq = spec.rfind('=');
    if (eq == std::string::npos) throw InvalidArgument(usage);
    workflow::SliceAxis g;
    g.axis = parameter_index(names, spec.substr(0, eq), "--grid");
    std::vector<std::string> parts;
    std::stringstream in(spec.substr(eq + 1));
    std::string item;
    while (std::getline(in, item, ':')) parts.push_back(item);
    if (parts.size() != 3) throw InvalidArgument(usage);
    g.lo = number(parts[0], "--grid LO");
    g.hi = number(parts[1], "--grid HI");
    const double n = number(parts[2], "--grid N");
    if (!(g.hi > g.lo) || n < 2 || n > 2000 || n != std::floor(n))
        throw InvalidArgument(usage + " with LO < HI and 2 <= N <= 2000");
    g.count = static_cast<Eigen::Index>(n);
    return g;
}

void run_reliability(const ReliabilityArgs& a) {
    refuse_existing({a.svg, a.csv}, a.force);
    const Database db(a.db);
    const auto model = load_synthesis_model(db, a.set, a.naive, "");
    const auto& names = model->parameter_names();
    const auto comma = a.grid.find(',');
    if (comma == std::string::npos)
        throw InvalidArgument("--grid: expected two axes AXIS=LO:HI:N,AXIS=LO:HI:N, got '" + a.grid + "'");
    const workflow::SliceAxis gx = parse_axis(a.grid.substr(0, comma), names);
    const workflow::SliceAxis gy = parse_axis(a.grid.substr(comma + 1), names);
    if (gx.axis == gy.axis) throw InvalidArgument("--grid: the two axes must differ");
    // The other axes: fixed by --fix, else at the samples' mean.
    VecX base = workflow::samples_mean(*model);
    for (const std::string& f : a.fix) {
        const auto eq = f.rfind('=');
        if (eq == std::string::npos) throw InvalidArgument("--fix: expected AXIS=V, got '" + f + "'");
        const Eigen::Index k = parameter_index(names, f.substr(0, eq), "--fix");
        if (k == gx.axis || k == gy.axis)
            throw InvalidArgument("--fix: '" + names[static_cast<std::size_t>(k)] + "' is a grid axis");
        base(k) = number(f.substr(eq + 1), "--fix " + names[static_cast<std::size_t>(k)]);
    }
    const workflow::ReliabilityMap m = workflow::reliability_map(*model, gx, gy, base);
    const HeatMapSpec spec = reliability_heat_map(*model, a.set, gx, gy, base, m);
    const MatX& queries = m.queries;
    const VecX& rho = m.rho;
    const std::string svg = render_heat_map(spec);
    write_file_atomically(a.svg, [&](std::ostream& out) { out << svg; });
    if (!a.csv.empty()) {
        write_file_atomically(a.csv, [&](std::ostream& out) {
            out.precision(17);
            for (Eigen::Index k = 0; k < model->parameters(); ++k) out << names[static_cast<std::size_t>(k)] << ",";
            out << "reliability\n";
            for (Eigen::Index q = 0; q < queries.rows(); ++q) {
                for (Eigen::Index k = 0; k < model->parameters(); ++k) out << queries(q, k) << ",";
                out << rho(q) << "\n";
            }
        });
    }
    const double trusted = m.fraction_trusted;
    if (a.json) {
        JsonWriter j;
        json::write_reliability_map(j,
                                    {a.set, model->kind(), names[static_cast<std::size_t>(gx.axis)],
                                     names[static_cast<std::size_t>(gy.axis)], a.svg, a.csv},
                                    m);
        std::fputs(j.str().c_str(), stdout);
        return;
    }
    std::printf(
        "reliability of '%s' over %s x %s (%lld x %lld cells): min %.3f, mean %.3f, max %.3f; "
        "%.0f%% of the slice has rho >= 0.85\n",
        a.set.c_str(), spec.x_label.c_str(), spec.y_label.c_str(), static_cast<long long>(gx.count),
        static_cast<long long>(gy.count), m.rho_min, m.rho_mean, m.rho_max, 100.0 * trusted);
    std::printf("  wrote %s%s%s\n", a.svg.c_str(), a.csv.empty() ? "" : " and ", a.csv.c_str());
}

}  // namespace

void setup_reliability(CLI::App& app) {
    auto a = std::make_shared<ReliabilityArgs>();
    CLI::App* cmd = app.add_subcommand("reliability", "Heat map of the synthesis reliability over a 2-D slice");
    cmd->footer(
        "Example:\n"
        "  mocapdb reliability db.h5 --set walks --grid turn=-1.5:1.5:60,speed=80:180:40 --svg rho.svg\n"
        "rho = 1 - sigma^2(c) / (nugget + sill) (the geostatistical paper, Appendix B): 1 at the samples,\n"
        "towards 0 far from them. Axes not on the grid are fixed by --fix AXIS=V (default: the samples' mean).");
    cmd->add_option("db", a->db, "database file")->required()->check(CLI::ExistingFile);
    cmd->add_option("--set", a->set, "motion set")->required();
    cmd->add_option("--grid", a->grid, "AXIS=LO:HI:N,AXIS=LO:HI:N")->required();
    cmd->add_option("--fix", a->fix, "AXIS=V for an axis off the grid");
    cmd->add_option("--svg", a->svg, "SVG file to write")->required();
    cmd->add_option("--csv", a->csv, "CSV of the grid values");
    cmd->add_flag("--naive", a->naive, "the naive model's kernel (no compressed model needed)");
    cmd->add_flag("--json", a->json, "machine-readable output");
    cmd->add_flag("--force", a->force, "overwrite existing output files");
    cmd->callback([a] { run_reliability(*a); });
}

}  // namespace mocapdb::cli
