#pragma once
// `mocapdb eval DB.h5 --set NAME`: the leave-one-out accuracy of every predictor on a stored set
// (eval/set_evaluation.hpp), printed as a table, as JSON (--json) and as an SVG plot (--svg).
#include <cstddef>
#include <string>

namespace mocapdb::cli {

struct EvalSetArgs {
    std::string db;
    std::string set;
    bool json = false;
    std::string svg;
    std::size_t max_folds = 40;
    std::size_t inner_folds = 15;
    bool force = false;
};

void run_set_eval(const EvalSetArgs& a);

}  // namespace mocapdb::cli
