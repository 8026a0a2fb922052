#pragma once
// Shared by the synthesis commands (synth, query, reliability, reduce): parsing control parameters
// given by the user and loading a set's synthesis model.
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "mocapdb/store/database.hpp"
#include "mocapdb/synthesis/synthesis_model.hpp"
#include "mocapdb/workflow/synthesis_warnings.hpp"

namespace mocapdb::cli {

/// "v1,v2,..." (positional) or "name=v,..." (named; a categorical parameter takes a level name) into the
/// set's P values (dataset/parameter_request.hpp); InvalidArgument prefixed with `option` otherwise.
VecX parse_parameters(const std::string& text, const MotionSet& set, const std::string& option);

/// "R1xR2xR3" into ranks (InvalidArgument otherwise).
tensor::Ranks parse_ranks(const std::string& text, const std::string& option);

/// The naive model (naive = true) or the stored compressed model, with an optional extra level of
/// detail (lod = "R1xR2xR3", compressed only; it becomes level 1). timing: "shared" (default) or
/// "separate" (synthesis_model.hpp). predictor: "auto" (the one `compress` chose and stored; kriging
/// without a stored choice), "kriging", "rbf" or "trend" (synthesis/predictor_choice.hpp).
std::unique_ptr<synthesis::SynthesisModel> load_synthesis_model(const Database& db, const std::string& set, bool naive,
                                                                const std::string& lod,
                                                                const std::string& timing = "shared",
                                                                const std::string& predictor = "auto");

/// Adds --predictor (auto | kriging | rbf | trend) to a synthesis command.
void add_predictor_option(CLI::App* cmd, std::string& predictor);

/// The warnings `w` (workflow/synthesis_warnings.hpp) of a synthesis, one line each; `set` names the
/// parameters that missed.
std::vector<std::string> warning_lines(const workflow::SynthesisWarnings& w, const MotionSet& set);

/// Index of a parameter by name (InvalidArgument listing the names otherwise).
Eigen::Index parameter_index(const std::vector<std::string>& names, const std::string& name, const std::string& option);

}  // namespace mocapdb::cli
