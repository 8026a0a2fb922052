// mocapdb compress: decompose a set's aligned tensor into a Tucker model and store it in the file.
#include <cstdio>

#include "commands.hpp"
#include "json_writer.hpp"
#include "mocapdb_json/step_json.hpp"
#include "pipeline.hpp"

namespace mocapdb::cli {
namespace {

struct CompressArgs {
    std::string db;
    CompressRequest request;
    bool json = false;
};

void run_compress(const CompressArgs& a) {
    const CompressOutcome o = compress_set(a.db, a.request);
    if (a.json) {
        JsonWriter j;
        json::write_compression(j, a.request.set, o);
        std::fputs(j.str().c_str(), stdout);
        return;
    }
    std::fputs(describe_compression(a.request.set, o).c_str(), stdout);
}

}  // namespace

void setup_compress(CLI::App& app) {
    auto a = std::make_shared<CompressArgs>();
    CLI::App* cmd = app.add_subcommand("compress", "Decompose a set's aligned tensor (Tucker) and store the model");
    cmd->footer(
        "Examples:\n"
        "  mocapdb compress db.h5 --set walks --max-error-cm 1\n"
        "  mocapdb compress db.h5 --set walks --ranks 22,6,24 --method hooi --json\n"
        "Without a target the ranks are the smallest meeting a max joint error of 1 cm. Errors are measured\n"
        "against the aligned tensor after forward kinematics (every joint, frame and sample). The tensor is\n"
        "centred and weighted per dof by the length of the chain it moves (lib/include/mocapdb/compression/\n"
        "dof_weights.hpp); --rmse is in those weighted units. Replaces the set's previous model.");
    cmd->add_option("db", a->db, "database file")->required()->check(CLI::ExistingFile);
    cmd->add_option("--set", a->request.set, "motion set (aligned)")->required();
    auto* ranks = cmd->add_option_function<std::vector<long long>>(
                         "--ranks",
                         [a](const std::vector<long long>& r) {
                             a->request.ranks = tensor::Ranks{r[0], r[1], r[2]};
                         },
                         "explicit ranks R1,R2,R3 (dof, time, sample)")
                      ->delimiter(',')
                      ->expected(3);
    auto* max_error = cmd->add_option("--max-error-cm", a->request.max_error_cm, "target max joint-position error (cm)")
                          ->check(CLI::PositiveNumber);
    auto* rmse = cmd->add_option("--rmse", a->request.rmse, "target RMSE of the weighted, centred tensor")
                     ->check(CLI::NonNegativeNumber);
    auto* ratio = cmd->add_option("--ratio", a->request.ratio, "target compression ratio of the Tucker parameters")
                      ->check(CLI::PositiveNumber);
    ranks->excludes(max_error, rmse, ratio);
    max_error->excludes(rmse, ratio);
    rmse->excludes(ratio);
    cmd->add_option("--method", a->request.method, "hosvd | sthosvd | hooi")
        ->transform(CLI::CheckedTransformer(tucker_methods()));
    cmd->add_option("--max-iterations", a->request.max_iterations, "HOOI sweeps at most")->check(CLI::Range(0, 10000));
    cmd->add_flag("--json", a->json, "print one JSON object");
    cmd->callback([a] { run_compress(*a); });
}

}  // namespace mocapdb::cli
