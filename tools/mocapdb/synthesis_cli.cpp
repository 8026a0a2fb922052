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
        // The average is compress's choice of members (auto uses it), not one to name here.
        if (!options.predictor || *options.predictor == synthesis::Predictor::Average)
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

std::vector<std::string> warning_lines(const workflow::SynthesisWarnings& w, const MotionSet& set) {
    std::vector<std::string> out;
    char buf[400];
    if (w.low_reliability && w.calibrated) {
        const bool by_variance = w.variance_ratio > w.threshold.variance_ratio;
        const bool by_votes = w.threshold.votes > 0 && w.nearby_misses >= w.threshold.votes;
        if (by_variance)
            std::snprintf(buf, sizeof buf,
                          "prediction variance %.3f of the sill (reliability %.3f) above %.3f, where this set's "
                          "syntheses miss their parameters (calibrated by compress): the motion may not meet them",
                          w.variance_ratio, w.rho, w.threshold.variance_ratio);
        else if (by_votes)
            std::snprintf(buf, sizeof buf,
                          "%zu of the %zu requests nearest to this one that compress synthesized to calibrate the "
                          "warning missed their parameters: the motion may not meet them",
                          w.nearby_misses, w.threshold.neighbours);
        else
            std::snprintf(buf, sizeof buf,
                          "the request lies %.2f SD beyond the samples (more than %.2f, where this set's syntheses "
                          "miss their parameters; calibrated by compress): the motion may not meet them",
                          w.beyond_sd, w.threshold.beyond_sd);
        out.emplace_back(buf);
    } else if (w.low_reliability) {
        std::snprintf(buf, sizeof buf,
                      "reliability %.3f < %.1f: the parameters are far from the samples; the motion is "
                      "extrapolated and may not meet them (see mocapdb reliability)",
                      w.rho, workflow::kLowReliability);
        out.emplace_back(buf);
    }
    for (const workflow::ParameterMiss& m : w.misses) {
        const std::string& unit = set.parameter_units[m.parameter];
        const std::string u = unit.empty() ? "" : " " + unit;
        const std::string requested = parameter_value_text(set, m.parameter, m.requested) + u;
        if (m.measured)
            std::snprintf(buf, sizeof buf, "%s measured %s on the result, %s requested: off by more than %s%s",
                          set.parameter_names[m.parameter].c_str(),
                          (parameter_value_text(set, m.parameter, *m.measured) + u).c_str(), requested.c_str(),
                          parameter_value_text(set, m.parameter, m.tolerance).c_str(), u.c_str());
        else
            std::snprintf(buf, sizeof buf, "%s could not be measured on the result (%s requested)",
                          set.parameter_names[m.parameter].c_str(), requested.c_str());
        out.emplace_back(buf);
    }
    if (!w.kernel_fit.empty()) out.push_back(w.kernel_fit);
    if (w.regularized)
        out.emplace_back("singular kriging system: the covariance matrix was regularized (eigenvalues clamped)");
    else if (w.jittered) out.emplace_back("near-singular kriging system: a jitter was added to its diagonal");
    return out;
}

}  // namespace mocapdb::cli
