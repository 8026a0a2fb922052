// mocapdb compress: decompose a set's aligned tensor into a Tucker model and store it in the file.
#include <chrono>
#include <cstdio>
#include <sstream>

#include "commands.hpp"
#include "json_writer.hpp"
#include "mocapdb/compression/byte_accounting.hpp"
#include "mocapdb/compression/dof_weights.hpp"
#include "mocapdb/compression/rank_search.hpp"
#include "mocapdb/compression/rate_distortion.hpp"
#include "mocapdb/core/error.hpp"
#include "set_context.hpp"

namespace mocapdb::cli {
namespace {

struct CompressArgs {
    std::string db;
    std::string set;
    std::vector<long long> ranks;
    double max_error_cm = 0.0;
    double rmse = -1.0;
    double ratio = 0.0;
    std::string method = "hosvd";
    int max_iterations = 50;
    bool json = false;
};

tensor::TuckerMethod method_of(const std::string& name) {
    if (name == "sthosvd") return tensor::TuckerMethod::StHosvd;
    if (name == "hooi") return tensor::TuckerMethod::Hooi;
    return tensor::TuckerMethod::Hosvd;
}

std::string ranks_text(const tensor::Ranks& r) {
    return std::to_string(r[0]) + "x" + std::to_string(r[1]) + "x" + std::to_string(r[2]);
}

void run_compress(const CompressArgs& a) {
    using Clock = std::chrono::steady_clock;
    const auto start = Clock::now();
    const SetContext c = load_set_context(Database(a.db), a.set);
    const Tensor3& poses = c.aligned.tensor;
    const VecX weight = compression::position_error_weights(*c.skeleton);
    const eval::JointErrorMeter meter(c.skeleton, poses);
    const compression::PreparedSet prepared = compression::prepare_set(poses, weight);

    std::string criterion;
    compression::RankSearchResult chosen;
    if (!a.ranks.empty()) {
        const tensor::Dims3 dims = tensor::dims_of(poses);
        tensor::Ranks r{};
        for (int n = 0; n < 3; ++n) {
            if (a.ranks[static_cast<std::size_t>(n)] < 1 || a.ranks[static_cast<std::size_t>(n)] > dims[static_cast<std::size_t>(n)])
                throw InvalidArgument("--ranks: rank " + std::to_string(n + 1) + " must be in [1, " +
                                      std::to_string(dims[static_cast<std::size_t>(n)]) + "] for a tensor of " +
                                      ranks_text(dims) + " (dofs x frames x samples)");
            r[static_cast<std::size_t>(n)] = a.ranks[static_cast<std::size_t>(n)];
        }
        chosen.model = compression::hosvd_model(prepared, r);
        chosen.target_met = true;
        criterion = "ranks " + ranks_text(r);
    } else if (a.rmse >= 0.0) {
        chosen = compression::search_ranks_for_rmse(prepared, meter, a.rmse);
        criterion = "rmse <= " + std::to_string(a.rmse);
    } else if (a.ratio > 0.0) {
        chosen = compression::ranks_for_ratio(prepared, meter, a.ratio);
        criterion = "ratio >= " + std::to_string(a.ratio);
    } else {
        const double target = a.max_error_cm > 0.0 ? a.max_error_cm : 1.0;
        chosen = compression::search_ranks_for_max_error(prepared, meter, target);
        std::ostringstream s;
        s << "max joint error <= " << target << " cm";
        criterion = s.str();
    }
    const double search_seconds = std::chrono::duration<double>(Clock::now() - start).count();

    // The chosen ranks, decomposed with the requested method.
    const auto fit_start = Clock::now();
    tensor::HooiOptions hooi;
    hooi.max_iterations = a.max_iterations;
    compression::SetModel model =
        compression::fit_set_model(poses, weight, chosen.model.tucker.ranks, method_of(a.method), hooi);
    const double fit_seconds = std::chrono::duration<double>(Clock::now() - fit_start).count();
    const eval::JointErrorStats stats = meter.measure(model.reconstruct());
    const double us_per_pose = compression::time_pose_evaluation(model.tucker);

    ModelFigures figures{stats.dof_rmse, stats.rmse_cm, stats.mean_cm, stats.max_cm, stats.p99_cm};
    DatabaseWriter writer(a.db, DatabaseWriter::Mode::OpenOrCreate);
    writer.put_model(a.set, model, figures);
    writer.commit();
    std::uint64_t stored = 0;
    for (const SetRecord& r : Database(a.db).sets())
        if (r.name == a.set) stored = r.model_stored_bytes;

    const std::uint64_t raw = compression::aligned_float32_bytes(poses);
    const std::uint64_t bytes = compression::tucker_float32_bytes(model) +
                                compression::side_info_bytes(poses.dimension(1), poses.dimension(2),
                                                             c.set.parameters.cols());
    const double total_seconds = std::chrono::duration<double>(Clock::now() - start).count();
    const tensor::TuckerModel& t = model.tucker;
    if (a.json) {
        JsonWriter j;
        j.begin_object();
        j.key("set").value(a.set);
        j.key("criterion").value(criterion);
        j.key("target_met").value(chosen.target_met);
        j.key("method").value(tensor::to_string(t.method));
        j.key("status").value(tensor::to_string(t.status));
        j.key("iterations").value(t.iterations);
        j.key("dims").begin_array();
        for (Eigen::Index d : tensor::dims_of(poses)) j.value(static_cast<long long>(d));
        j.end_array();
        j.key("ranks").begin_array();
        for (Eigen::Index r : t.ranks) j.value(static_cast<long long>(r));
        j.end_array();
        j.key("raw_bytes").value(static_cast<long long>(raw));
        j.key("bytes").value(static_cast<long long>(bytes));
        j.key("ratio").value(static_cast<double>(raw) / static_cast<double>(bytes));
        j.key("file_bytes").value(static_cast<long long>(stored));
        j.key("relative_error").value(1.0 - t.fit);
        j.key("relative_error_bound").value(t.error_bound / t.data_norm);
        j.key("dof_rmse").value(stats.dof_rmse);
        j.key("rmse_cm").value(stats.rmse_cm);
        j.key("mean_cm").value(stats.mean_cm);
        j.key("max_cm").value(stats.max_cm);
        j.key("p99_cm").value(stats.p99_cm);
        j.key("worst").begin_object();
        j.key("sample").value(static_cast<long long>(stats.worst.sample));
        j.key("frame").value(static_cast<long long>(stats.worst.frame));
        j.key("joint").value(stats.worst.joint);
        j.end_object();
        j.key("search_s").value(search_seconds);
        j.key("precompute_s").value(fit_seconds);
        j.key("us_per_pose").value(us_per_pose);
        j.key("total_s").value(total_seconds);
        j.end_object();
        std::fputs(j.str().c_str(), stdout);
        return;
    }
    std::printf("compressed set '%s' (%s): %s -> ranks %s, %s%s\n", a.set.c_str(), criterion.c_str(),
                ranks_text(tensor::dims_of(poses)).c_str(), ranks_text(t.ranks).c_str(), tensor::to_string(t.method),
                chosen.target_met ? "" : " (target NOT met: closest ranks)");
    std::printf("  bytes %llu (float32 model + timing/parameters) vs raw aligned float32 %llu: ratio %.2f:1; "
                "model in file %llu bytes\n",
                static_cast<unsigned long long>(bytes), static_cast<unsigned long long>(raw),
                static_cast<double>(raw) / static_cast<double>(bytes), static_cast<unsigned long long>(stored));
    std::printf("  relative error %.3g (HOSVD bound %.3g); joint error: rmse %.3f cm, mean %.3f cm, p99 %.3f cm, "
                "max %.3f cm (sample %lld, frame %lld, %s)\n",
                1.0 - t.fit, t.error_bound / t.data_norm, stats.rmse_cm, stats.mean_cm, stats.p99_cm, stats.max_cm,
                static_cast<long long>(stats.worst.sample), static_cast<long long>(stats.worst.frame),
                stats.worst.joint.c_str());
    std::printf("  rank search %.2f s, decomposition %.3f s, %.3f us per pose; %.2f s in all\n", search_seconds,
                fit_seconds, us_per_pose, total_seconds);
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
    cmd->add_option("--set", a->set, "motion set (aligned)")->required();
    auto* ranks = cmd->add_option("--ranks", a->ranks, "explicit ranks R1,R2,R3 (dof, time, sample)")
                      ->delimiter(',')
                      ->expected(3);
    auto* max_error = cmd->add_option("--max-error-cm", a->max_error_cm, "target max joint-position error (cm)")
                          ->check(CLI::PositiveNumber);
    auto* rmse = cmd->add_option("--rmse", a->rmse, "target RMSE of the weighted, centred tensor")
                     ->check(CLI::NonNegativeNumber);
    auto* ratio = cmd->add_option("--ratio", a->ratio, "target compression ratio of the Tucker parameters")
                      ->check(CLI::PositiveNumber);
    ranks->excludes(max_error, rmse, ratio);
    max_error->excludes(rmse, ratio);
    rmse->excludes(ratio);
    cmd->add_option("--method", a->method, "hosvd | sthosvd | hooi")->check(CLI::IsMember({"hosvd", "sthosvd", "hooi"}));
    cmd->add_option("--max-iterations", a->max_iterations, "HOOI sweeps at most")->check(CLI::Range(0, 10000));
    cmd->add_flag("--json", a->json, "print one JSON object");
    cmd->callback([a] { run_compress(*a); });
}

}  // namespace mocapdb::cli
