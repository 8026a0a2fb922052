#pragma once
// The pieces of `mocapdb eval`'s writers (eval_report.hpp), one file per output kind: text helpers
// (eval_report_text.cpp), CSV and SVG (eval_report_figures.cpp), results.json (eval_report_json.cpp),
// verdict texts (eval_report_verdicts.cpp) and REPORT.md (eval_report.cpp, eval_report_later_sections.cpp).
// Formatting only.
#include <filesystem>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "mocapdb/eval/evaluation.hpp"
#include "mocapdb/eval/verdicts.hpp"
#include "ranks_text.hpp"

namespace mocapdb::cli::eval_report {

using eval::EvalResults;
using eval::RunInfo;
using eval::SetResults;

std::string cycles_note(const eval::EvalSetSpec& spec);
std::string fmt(double v, int digits = 3);
std::string fixed(double v, int decimals = 2);
/// "n/a" for a value that does not exist.
std::string fmt(const std::optional<double>& v, int digits = 3);
std::string fixed(const std::optional<double>& v, int decimals = 2);
/// "12 %", or "" for a value that does not exist.
std::string percent(const std::optional<double>& value);
void put(const std::filesystem::path& path, const std::string& text);

// REPORT.md's sections 4-8 (eval_report_later_sections.cpp).
void reduction_section(std::ostream& o, const EvalResults& e);
void skating_section(std::ostream& o, const EvalResults& e);
void compression_section(std::ostream& o, const EvalResults& e);
void runtime_section(std::ostream& o, const EvalResults& e);
void caveats_section(std::ostream& o, const EvalResults& e);

struct Table {
    std::vector<std::string> header;
    std::vector<std::vector<std::string>> rows;
    std::size_t left = 1;  ///< leading text columns (left-aligned)
    std::string str() const {
        std::ostringstream s;
        s << "|";
        for (const auto& h : header) s << " " << h << " |";
        s << "\n|";
        for (std::size_t k = 0; k < header.size(); ++k) s << (k < left ? "---" : "---:") << "|";
        s << "\n";
        for (const auto& r : rows) {
            s << "|";
            for (const auto& c : r) s << " " << c << " |";
            s << "\n";
        }
        return s.str();
    }
};

std::string params_text(const eval::EvalSet& s);
std::string caption(const RunInfo& info, const eval::EvalSet& s, const std::string& parameters);
std::string short_caption(const RunInfo& info, const std::string& data, const std::string& parameters);
std::string svg_note(const RunInfo& info);
std::string method_label(const eval::MethodSpec& m);

std::string loo_csv(const SetResults& r);
std::string loo_frames_csv(const SetResults& r);
std::string constraint_csv(const SetResults& r);
std::string reduction_csv(const SetResults& r);
std::string compression_csv(const SetResults& r);
std::string runtime_csv(const EvalResults& e);
std::string loo_svg(const RunInfo& info, const SetResults& r, bool pose);
std::string reliability_svg(const RunInfo& info, const SetResults& r);
std::string reduction_svg(const RunInfo& info, const SetResults& r);
std::string compression_svg(const RunInfo& info, const SetResults& r);
std::string runtime_svg(const RunInfo& info, const EvalResults& e, bool build);
std::string results_json(const EvalResults& e);

/// The text of one metric's verdict.
struct MetricText {
    std::string name;
    std::string unit;
};
MetricText metric_text(const eval::MetricVerdict& v);
const eval::LooMethodResult* loo_method(const SetResults& r, const std::string& n);
const eval::ConstraintMethodResult* constraint_method(const SetResults& r, const std::string& n);
std::string split_text(const eval::MetricVerdict& v);
/// Why a baseline won a metric, from the results behind the verdict.
std::string why_text(const SetResults& r, const eval::MetricVerdict& v);
std::string losses_section(const EvalResults& e);
std::string report_md(const EvalResults& e);

}  // namespace mocapdb::cli::eval_report
