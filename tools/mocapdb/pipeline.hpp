#pragma once
// The CLI's side of the steps of the main job (the steps themselves are the library's workflow
// module): each wrapper turns command-line shaped arguments into the library's request,
// draws a progress bar, prints what the step reports (warnings), and describe_* / rate_*
// format the outcomes the single-step commands (import, set create, align, compress, report, synth,
// reliability) and `mocapdb demo` print.
#include <filesystem>
#include <iosfwd>
#include <map>
#include <utility>
#include <string>
#include <vector>

#include "ranks_text.hpp"
#include "mocapdb/workflow/clip_import.hpp"
#include "mocapdb/workflow/reliability_map.hpp"
#include "mocapdb/workflow/set_alignment.hpp"
#include "mocapdb/workflow/set_compression.hpp"
#include "mocapdb/workflow/set_creation.hpp"
#include "mocapdb/workflow/set_rate_report.hpp"
#include "svg_heatmap.hpp"

namespace mocapdb::cli {

// ---- import -------------------------------------------------------------------------------------

using ImportOutcome = workflow::ImportOutcome;

/// workflow::import_clips with a progress bar; then the reader warnings and errors go to stderr
/// ("mocapdb: warning: ..."), and the files not added (duplicates) to `notes`: each, or their count
/// past a few.
ImportOutcome import_clips(const std::filesystem::path& db, const std::vector<std::filesystem::path>& inputs,
                           const workflow::ImportOptions& options, bool force, std::ostream& notes);

/// "imported N clips (...) ...; DB now holds M clips, S MB" (one line, newline-terminated).
std::string describe_import(const std::filesystem::path& db, const ImportOutcome& o);

// ---- set create ---------------------------------------------------------------------------------

using SetRequest = workflow::SetRequest;

using SetOutcome = workflow::SetOutcome;

/// workflow::create_set with a progress bar; warnings for skipped clips go to stderr.
SetOutcome create_set(const std::string& db, SetRequest request);
/// `--periodic NAME=PERIOD ...` as the request's (name, period) pairs; InvalidArgument naming the flag.
std::vector<std::pair<std::string, double>> periodic_parameters(const std::vector<std::string>& specs);
/// `--category NAME=REGEX ...` as the request's (name, pattern) pairs; InvalidArgument naming the flag.
std::vector<std::pair<std::string, std::string>> category_parameters(const std::vector<std::string>& specs);

/// "set 'NAME': N samples (KIND) from C clips, P parameters (SOURCE)\n", then, when dropouts were
/// repaired, "repaired solver dropouts in K clips (R joint runs of up to F frames): CLIPS; ...\n".
std::string describe_set(const SetOutcome& o);

// ---- align --------------------------------------------------------------------------------------

using AlignRequest = workflow::AlignRequest;
using AlignOutcome = workflow::AlignOutcome;

/// workflow::align_set with progress bars (reading, aligning).
AlignOutcome align_set(const std::string& db, AlignRequest request);

/// The alignment line, then (with a phase check) "phase check (same forward foot per aligned frame):
/// min M %, mean A %[; below 80 % at aligned frames a-b, ...]".
std::string describe_alignment(const std::string& set, const AlignOutcome& o);

// ---- compress -----------------------------------------------------------------------------------

using CompressRequest = workflow::CompressRequest;

using CompressOutcome = workflow::CompressOutcome;

/// workflow::compress_set with a progress bar.
CompressOutcome compress_set(const std::string& db, CompressRequest request);
/// `--method` names of tensor::TuckerMethod (for CLI11's CheckedTransformer).
const std::map<std::string, tensor::TuckerMethod>& tucker_methods();

std::string describe_compression(const std::string& set, const CompressOutcome& o);
/// The outcome's fields as members of the open JSON object.

// ---- rate-distortion report ---------------------------------------------------------------------

using RateOutcome = workflow::RateOutcome;

/// The table `mocapdb report` prints (header line, one line per row, legend).
std::string rate_table_text(const std::string& set, const RateOutcome& r);
std::string rate_csv(const RateOutcome& r);
/// Ratio against max error, one series per method (rows meeting a lossy target).
std::string rate_svg(const std::string& set, const RateOutcome& r);

// ---- reliability map ----------------------------------------------------------------------------

/// The heat map of a reliability map over gx × gy through `base` (render_heat_map): titled with the
/// set and the model's kind, axes labelled with the parameters' names and units, the samples marked,
/// the fixed axes noted.
HeatMapSpec reliability_heat_map(const synthesis::SynthesisModel& model, const std::string& set,
                                 const workflow::SliceAxis& gx, const workflow::SliceAxis& gy, const VecX& base,
                                 const workflow::ReliabilityMap& map);

}  // namespace mocapdb::cli
