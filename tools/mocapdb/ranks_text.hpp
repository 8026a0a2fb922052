#pragma once
// Tucker ranks as the CLI prints them: "R1xR2xR3" ("-" when there are none), one format for the
// compress, report, demo and eval outputs.
#include <string>
#include <vector>

#include "mocapdb/tensor/unfold.hpp"

namespace mocapdb::cli {

inline std::string ranks_text(const std::vector<long long>& r) {
    std::string s;
    for (std::size_t i = 0; i < r.size(); ++i) s += (i ? "x" : "") + std::to_string(r[i]);
    return s.empty() ? "-" : s;
}

inline std::string ranks_text(const tensor::Ranks& r) { return ranks_text(std::vector<long long>(r.begin(), r.end())); }

}  // namespace mocapdb::cli
