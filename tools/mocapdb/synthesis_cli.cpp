#include "synthesis_cli.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "mocapdb/core/error.hpp"
#include "mocapdb/dataset/motion_set.hpp"
#include "mocapdb/synthesis/motion_model.hpp"
#include "mocapdb/synthesis/naive_motion_model.hpp"
#include "mocapdb/workflow/load_model.hpp"
#include "mocapdb/workflow/synthesis_warnings.hpp"
#include "progress_bar.hpp"

namespace mocapdb::cli {

VecX parse_parameters(const std::string& text, const MotionSet& set, const std::string& option) {
    std::vector<std::string> items;
    std::stringstream in(text);
    std::string item;
    while (std::getline(in, item, ',')) items.push_back(item);
    if (!text.empty() && text.back() == ',') items.emplace_back();  // "1," : an empty last value
    try {
        return parameter_request(set, items);
    } catch (const InvalidArgument& e) {
        throw InvalidArgument(option + ": " + e.what());
    }
}

tensor::Ranks parse_ranks(const std::string& text, const std::string& option) {
    tensor::Ranks r{};
    std::stringstream in(text);
    std::string item;
    int n = 0;
    while (std::getline(in, item, 'x')) {
        char* end = nullptr;
        const long v = std::strtol(item.c_str(), &end, 10);
        if (n >= 3 || item.empty() || end != item.c_str() + item.size() || v < 1)
            throw InvalidArgument(option + ": expected ranks R1xR2xR3 (positive integers), got '" + text + "'");
        r[static_cast<std::size_t>(n++)] = v;
    }
    if (n != 3) throw InvalidArgument(option + ": expected ranks R1xR2xR3 (positive integers), got '" + text + "'");
    return r;
}

std::unique_ptr<synthesis::SynthesisModel> load_synthesis_model(const Database& db, const std::string& set, bool naive,
                                                                const std::string& lod, const std::string& timing,
                                                                const std::string& predictor) {
    synthesis::SynthesisOptions options;
    // A model whose stored kernel does not match (or that has none) fits it at load: show its progress.
    ProgressBar bar("synth: kernel fit");
    options.fit_progress = bar.callback();
    if (timing == "separate") options.timing_kernel = synthesis::SynthesisOptions::TimingKernel::Separate;
    else if (timing != "shared") throw InvalidArgument("--timing: expected shared or separate, got '" + timing + "'");
    if (predictor != "auto") {
        options.predictor = synthesis::parse_predictor(predictor);
        if (!options.predictor)
            throw InvalidArgument("--predictor: expected auto, kriging, rbf or trend, got '" + predictor + "'");
    }
    if (naive) {
        if (!lod.empty()) throw InvalidArgument("--lod applies to the compressed model only (not with --naive)");
        return workflow::load_naive_motion_model(db, set, options);
    }
    if (!lod.empty()) options.levels.push_back(parse_ranks(lod, "--lod"));
    return workflow::load_motion_model(db, set, options);
}

void add_predictor_option(CLI::App* cmd, std::string& predictor) {
    cmd->add_option("--predictor", predictor,
                    "what blends the samples: auto (the one compress chose by cross-validation) | kriging | rbf | "
                    "trend")
        ->check(CLI::IsMember({"auto", "kriging", "rbf", "trend"}));
}

Eigen::Index parameter_index(const std::vector<std::string>& names, const std::string& name,
                             const std::string& option) {
    for (std::size_t k = 0; k < names.size(); ++k)
        if (names[k] == name) return static_cast<Eigen::Index>(k);
    std::string list;
    for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
    throw InvalidArgument(option + ": the set has no parameter '" + name + "' (parameters: " + list + ")");
}

}  // namespace mocapdb::cli

namespace mocapdb::cli {

std::vector<std::string> synthesis_warnings(const synthesis::SynthesisModel& model, double rho) {
    const workflow::SynthesisWarnings w = workflow::synthesis_warnings(model, rho);
    std::vector<std::string> out;
    if (w.low_reliability) {
        char buf[200];
        std::snprintf(buf, sizeof buf,
                      "reliability %.3f < %.1f: the parameters are far from the samples; the motion is extrapolated "
                      "and may not meet them (see mocapdb reliability)",
                      rho, workflow::kLowReliability);
        out.emplace_back(buf);
    }
    if (!w.kernel_fit.empty()) out.push_back(w.kernel_fit);
    if (w.regularized)
        out.emplace_back("singular kriging system: the covariance matrix was regularized (eigenvalues clamped)");
    else if (w.jittered) out.emplace_back("near-singular kriging system: a jitter was added to its diagonal");
    return out;
}

}  // namespace mocapdb::cli
