// mocapdb query: one synthesized pose at control parameters and an aligned frame.
#include <cstdio>

#include "commands.hpp"
#include "json_writer.hpp"
#include "mocapdb_json/synthesis_json.hpp"
#include "mocapdb/core/error.hpp"
#include "mocapdb/compression/joint_error.hpp"
#include "mocapdb/motion/pose_vector.hpp"
#include "synthesis_cli.hpp"

namespace mocapdb::cli {
namespace {

struct QueryArgs {
    std::string db;
    std::string set;
    std::string param;
    double frame = 0.0;
    std::string lod;
    std::string predictor = "auto";
    bool naive = false;
    bool joints = false;
    bool json = false;
};

void run_query(const QueryArgs& a) {
    const Database db(a.db);
    const MotionSet set = db.load_set(a.set);
    const VecX c = parse_parameters(a.param, set, "--param");
    const auto model = load_synthesis_model(db, a.set, a.naive, a.lod, "shared", a.predictor);
    if (!(a.frame >= 0.0 && a.frame <= static_cast<double>(model->frames() - 1)))
        throw InvalidArgument("--frame: the aligned frame must lie in [0, " + std::to_string(model->frames() - 1) +
                              "], got " + std::to_string(a.frame));
    const Eigen::Index level = a.lod.empty() ? 0 : 1;
    const VecX pose = model->pose(c, a.frame, level);
    const double rho = model->reliability(c);
    const Skeleton& sk = *model->skeleton();
    const workflow::SynthesisWarnings judged = workflow::synthesis_warnings(*model, set, c);
    const std::vector<std::string> warnings = warning_lines(judged, set);
    for (const std::string& w : warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());

    json::PoseQuery q;
    q.set = a.set;
    q.model = model->kind();
    q.predictor = synthesis::to_string(model->report().predictor);
    q.frame = a.frame;
    q.reliability = rho;
    q.warnings = warnings;
    q.judged = judged;
    q.skeleton = model->skeleton();
    q.pose = pose;
    q.joints = a.joints;
    if (a.joints) q.joint_positions = compression::pose_joint_positions(sk, pose);
    else q.channels = from_pose_vectors(sk, pose, Canonicalization{});
    if (a.json) {
        JsonWriter j;
        json::write_pose_query(j, q);
        std::fputs(j.str().c_str(), stdout);
        return;
    }
    std::printf("pose of '%s' at frame %g (%s model, %s), reliability %.3f:\n", a.set.c_str(), a.frame, model->kind(),
                q.predictor.c_str(), rho);
    if (a.joints) {
        const MatX& p = q.joint_positions;
        for (std::size_t k = 0; k < sk.size(); ++k) {
            const auto r = static_cast<Eigen::Index>(3 * k);
            std::printf("  %-16s %10.3f %10.3f %10.3f cm\n", sk.joint(k).name.c_str(), p(r, 0), p(r + 1, 0),
                        p(r + 2, 0));
        }
    } else {
        const FrameMatrix& ch = q.channels;
        for (std::size_t k = 0; k < sk.size(); ++k) {
            const Joint& joint = sk.joint(k);
            if (joint.channels.empty()) continue;
            std::printf("  %-16s", joint.name.c_str());
            for (std::size_t m = 0; m < joint.channels.size(); ++m)
                std::printf(" %s=%.6g", to_string(joint.channels[m]).c_str(),
                            ch(0, static_cast<Eigen::Index>(sk.first_channel(k) + m)));
            std::printf("\n");
        }
    }
}

}  // namespace

void setup_query(CLI::App& app) {
    auto a = std::make_shared<QueryArgs>();
    CLI::App* cmd = app.add_subcommand("query", "One synthesized pose at control parameters and an aligned frame");
    cmd->footer(
        "Example:\n"
        "  mocapdb query db.h5 --set walks --param 0.3,130 --frame 42.5 --joints --json\n"
        "  mocapdb query db.h5 --set gaits --param gait=run,turn=0.3 --frame 10\n"
        "--frame is a (fractional) frame of the aligned timeline [0, T-1]. Channels are in cm and radians;\n"
        "--joints gives joint positions in cm (canonical frame: the motion starts at the origin facing +Z).");
    cmd->add_option("db", a->db, "database file")->required()->check(CLI::ExistingFile);
    cmd->add_option("--set", a->set, "motion set")->required();
    cmd->add_option("--param", a->param, "control parameters v1,v2,... or name=v,... (a category: its level)")
        ->required();
    cmd->add_option("--frame", a->frame, "aligned frame t")->required();
    cmd->add_option("--lod", a->lod, "level of detail: ranks R1xR2xR3");
    add_predictor_option(cmd, a->predictor);
    cmd->add_flag("--naive", a->naive, "kriging on the uncompressed aligned tensor");
    cmd->add_flag("--joints", a->joints, "joint positions (cm) instead of channels");
    cmd->add_flag("--json", a->json, "machine-readable output");
    cmd->callback([a] { run_query(*a); });
}

}  // namespace mocapdb::cli
