#pragma once
// Shared by the `mocapdb gp` subcommands (cmd_gp.cpp) and its experiments (cmd_gp_experiments.cpp):
// the parsed options and the steps both use. Everything prints to stdout / stderr (CLI only).
#include <cstddef>
#include <string>
#include <vector>

#include "json_writer.hpp"
#include "progress_bar.hpp"
#include "mocapdb/gp/experiment.hpp"
#include "mocapdb/gp/model_steps.hpp"
#include "mocapdb/gp/motion_data.hpp"
#include "mocapdb/workflow/gp_children.hpp"

namespace mocapdb::cli::gp_cli {

struct GpArgs {
    // children
    std::string db;
    std::string set;
    std::vector<std::string> clips;
    double fps = 0.0;
    // data
    std::size_t frames = 90;
    double duration = 0.0;
    std::vector<std::string> joints;
    std::vector<std::string> exclude;
    bool keep_noisy = false;
    // model
    int layers = 2;
    std::vector<std::size_t> groups;
    std::string subject;
    std::size_t q = 1;
    std::size_t rank = 1;
    std::string kernel = "matern32";
    int restarts = 1;
    int max_iterations = 300;
    unsigned long long seed = 1;
    bool mo_baseline = false;
    bool json = false;
    // interpolate / sample / experiment
    std::string child;
    std::size_t observed = 40;
    std::size_t n = 10;
    std::string out;
    bool force = false;
    bool artificial = false;
    std::size_t runs = 5;
    std::vector<std::size_t> tests;
    std::vector<std::size_t> observed_list{40, 30, 20, 10};
    std::vector<std::string> eval_clips;
    std::size_t samples = 25;
};

workflow::GpChildren load_children(const GpArgs& a);
gp::MotionDataOptions data_options(const GpArgs& a);
gp::ModelSpec model_spec(const GpArgs& a, bool hierarchical);
gp::FitOptions fit_options(const GpArgs& a, ProgressBar* bar);
std::size_t child_index(const std::vector<std::string>& names, const std::string& which);
/// Three layers: each child's group, from --groups or from the subject in its CMU name (groups numbered
/// in order of first appearance). Nothing for two layers or the MOA baseline.
void assign_groups(const GpArgs& a, const std::vector<std::string>& names, gp::HgpData& data);
const char* model_label(const GpArgs& a);
void print_fit_summary(const char* label, const gp::FitResult& f);
void print_data_summary(const gp::MotionData& md);

void run_experiment_artificial(const GpArgs& a);
void run_experiment_replicates(const GpArgs& a);

}  // namespace mocapdb::cli::gp_cli
