// mocapdb reduce: greedy sample reduction by leave-one-out reliability (the geostatistical paper
// Section 5.2), as a report, optionally writing the reduced set (stored and aligned like the original).
#include <chrono>
#include <cstdio>

#include "commands.hpp"
#include "json_writer.hpp"
#include "mocapdb_json/synthesis_json.hpp"
#include "mocapdb/core/error.hpp"
#include "mocapdb/store/database.hpp"
#include "mocapdb/workflow/set_reduction.hpp"

namespace mocapdb::cli {
namespace {

struct ReduceArgs {
    std::string db;
    std::string set;
    double tau = 0.85;
    long long min_samples = 0;
    bool apply = false;
    std::string name;
    bool force = false;
    bool naive = false;
    bool json = false;
};

void run_reduce(const ReduceArgs& a) {
    const auto start = std::chrono::steady_clock::now();
    workflow::ReductionRequest request;
    request.set = a.set;
    request.tau = a.tau;
    request.min_samples = static_cast<Eigen::Index>(a.min_samples);
    request.naive = a.naive;
    const workflow::ReductionOutcome outcome = workflow::reduce_set(a.db, request);
    const MotionSet& set = outcome.set;
    const kriging::ReductionResult& r = outcome.result;
    const std::vector<std::string>& labels = outcome.labels;
    const std::string target = a.name.empty() ? a.set + "-reduced" : a.name;
    std::string applied;
    if (a.apply) {
        if (r.kept.size() < 2) throw InvalidArgument("--apply: the reduced set would have fewer than 2 samples");
        if (Database(a.db).has_set(target) && !a.force)
            throw InvalidArgument("--apply: set '" + target + "' exists (use --force to replace it, or --name)");
        applied = workflow::store_reduced_set(a.db, outcome, target, a.force) ? "stored and aligned" : "stored";
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (a.json) {
        json::ReductionReport report{a.set, a.tau, std::nullopt, seconds};
        if (a.apply) report.written_set = target;
        JsonWriter j;
        json::write_reduction(j, report, outcome);
        std::fputs(j.str().c_str(), stdout);
        return;
    }
    std::printf("reduction of '%s' at tau %.3f (%s kernel %s): %zu of %zu samples kept%s\n", a.set.c_str(), a.tau,
                outcome.model_kind.c_str(), outcome.kernel.to_string().c_str(), r.kept.size(), set.samples.size(),
                r.stopped_on_threshold ? "" : " (stopped on the minimum sample count)");
    for (std::size_t k = 0; k < r.removed.size(); ++k)
        std::printf("  removed %-20s leave-one-out reliability %.3f\n",
                    labels[static_cast<std::size_t>(r.removed[k])].c_str(), r.removed_reliability[k]);
    if (!r.max_reliability.empty() && r.stopped_on_threshold)
        std::printf("  next candidate's reliability %.3f < tau\n", r.max_reliability.back());
    if (a.apply) std::printf("  reduced set '%s' %s in %s\n", target.c_str(), applied.c_str(), a.db.c_str());
    else std::printf("  (report only: --apply writes the reduced set as '%s')\n", target.c_str());
    std::printf("  %.2f s\n", seconds);
}

}  // namespace

void setup_reduce(CLI::App& app) {
    auto a = std::make_shared<ReduceArgs>();
    CLI::App* cmd = app.add_subcommand("reduce", "Greedy sample reduction by leave-one-out reliability");
    cmd->footer(
        "Example:\n"
        "  mocapdb reduce db.h5 --set walks --tau 0.85 --apply --name walks-small\n"
        "Repeatedly removes the sample best predicted by the others (highest leave-one-out reliability)\n"
        "until that reliability falls below tau. The variogram is the set's synthesis kernel (the stored\n"
        "compressed model's, or with --naive the uncompressed tensor's). --apply stores the kept samples\n"
        "as a new set (default name SET-reduced) and aligns it with the original's method and frames;\n"
        "run mocapdb compress on it before synthesizing.");
    cmd->add_option("db", a->db, "database file")->required()->check(CLI::ExistingFile);
    cmd->add_option("--set", a->set, "motion set")->required();
    cmd->add_option("--tau", a->tau, "reliability threshold in [0, 1]")->check(CLI::Range(0.0, 1.0));
    cmd->add_option("--min-samples", a->min_samples, "never keep fewer samples (0 = trend size + 1)")
        ->check(CLI::NonNegativeNumber);
    cmd->add_flag("--apply", a->apply, "store the reduced set");
    cmd->add_option("--name", a->name, "name of the reduced set (default SET-reduced)");
    cmd->add_flag("--force", a->force, "replace an existing set of that name");
    cmd->add_flag("--naive", a->naive, "use the naive model's kernel (no compressed model needed)");
    cmd->add_flag("--json", a->json, "machine-readable output");
    cmd->callback([a] { run_reduce(*a); });
}

}  // namespace mocapdb::cli
