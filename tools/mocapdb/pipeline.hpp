#pragma once
// The steps of the main job as functions, shared by the single-step commands (import, set create,
// align, compress, report, synth, reliability) and by `mocapdb demo`, which runs them one after the
// other on one database. Each step does its work (through the library and the database file) and
// returns what happened; the commands decide what to print. describe_* give the one-paragraph
// summaries the single-step commands print.
#include <filesystem>
#include <functional>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "json_writer.hpp"
#include "mocapdb/compression/rate_distortion.hpp"
#include "mocapdb/compression/set_model.hpp"
#include "mocapdb/dataset/aligned_set.hpp"
#include "mocapdb/dataset/motion_set.hpp"
#include "mocapdb/dataset/phase_check.hpp"
#include "mocapdb/dataset/param_extractors.hpp"
#include "mocapdb/dataset/set_builder.hpp"
#include "mocapdb/compression/joint_error.hpp"
#include "mocapdb/store/import.hpp"
#include "mocapdb/synthesis/synthesis_model.hpp"
#include "mocapdb/workflow/set_creation.hpp"
#include "set_context.hpp"
#include "svg_heatmap.hpp"

namespace mocapdb::cli {

// ---- import -------------------------------------------------------------------------------------

struct ImportOutcome {
    ImportSummary summary;
    bool existed = false;          ///< the database file existed before
    std::size_t clips_in_db = 0;   ///< clips the database holds afterwards
    std::uint64_t file_bytes = 0;  ///< its size afterwards
    double seconds = 0.0;
};

/// Stores the clip files found under `inputs` in `db` (appending, or a new file when `force`),
/// committing when anything was added (or the file is new). Reader warnings go to stderr, and the
/// message of each file not added (duplicates) to `notes`. InvalidArgument when no clip file is found.
ImportOutcome import_clips(const std::filesystem::path& db, const std::vector<std::filesystem::path>& inputs,
                           const ImportOptions& options, bool force, std::ostream& notes);

/// "imported N clips (...) ...; DB now holds M clips, S MB" (one line, newline-terminated).
std::string describe_import(const std::filesystem::path& db, const ImportOutcome& o);

// ---- set create ---------------------------------------------------------------------------------

struct SetRequest {
    std::string name;
    std::vector<std::string> clips;      ///< clip ids or fnmatch patterns, in sample order
    std::string params_csv;              ///< parameters from a CSV ...
    std::vector<std::string> extract;    ///< ... or measured by these extractors (not both)
    std::vector<std::string> periodic;   ///< "NAME=PERIOD": periodic parameters (bearing is by itself)
    std::string segment = "auto";
    std::string feet;
    bool replace = false;
};

using SetOutcome = workflow::SetOutcome;

/// workflow::create_set with a progress bar; warnings for skipped clips go to stderr.
SetOutcome create_set(const std::string& db, const SetRequest& request);

/// "set 'NAME': N samples (KIND) from C clips, P parameters (SOURCE)\n", then, when dropouts were
/// repaired, "repaired solver dropouts in K clips (R joint runs of up to F frames): CLIPS; ...\n".
std::string describe_set(const SetOutcome& o);

// ---- align --------------------------------------------------------------------------------------

struct AlignRequest {
    std::string set;
    long long frames = 100;
    std::string method = "dtw";
    std::string reference;  ///< sample label, empty = the library's default
};

struct AlignOutcome {
    AlignedSet aligned;
    std::vector<std::string> labels;  ///< sample labels
    double distance = 0.0;            ///< mean pose distance to the reference, cm
    double seconds = 0.0;
    /// Forward-foot agreement per aligned frame (phase_check.hpp); empty when the skeleton's feet are
    /// not found (not a legged figure, or names default_feet does not know).
    std::optional<PhaseCheck> phase;
};

/// Aligns the set's samples and stores the tensor (committed).
AlignOutcome align_set(const std::string& db, const AlignRequest& request);

/// The alignment line, then (with a phase check) "phase check (same forward foot per aligned frame):
/// min M %, mean A %[; below 80 % at aligned frames a-b, ...]".
std::string describe_alignment(const std::string& set, const AlignOutcome& o);

// ---- compress -----------------------------------------------------------------------------------

struct CompressRequest {
    std::string set;
    std::vector<long long> ranks;  ///< explicit ranks (3), or one of the targets below
    double max_error_cm = 0.0;     ///< default target when nothing else is given: 1 cm
    double rmse = -1.0;
    double ratio = 0.0;
    std::string method = "hosvd";  ///< hosvd | sthosvd | hooi
    int max_iterations = 50;
};

struct CompressOutcome {
    std::string criterion;
    bool target_met = false;
    tensor::Dims3 dims{0, 0, 0};
    compression::SetModel model;
    compression::JointErrorStats stats;
    double us_per_pose = 0.0;
    std::uint64_t raw_bytes = 0;     ///< aligned tensor as float32
    std::uint64_t bytes = 0;         ///< float32 model + side information
    std::uint64_t stored_bytes = 0;  ///< the model in the file
    double search_s = 0.0, fit_s = 0.0, total_s = 0.0;
    double kernel_s = 0.0;  ///< fitting the synthesis kernel's variogram stored with the model
    bool kernel_stored = false;  ///< false above synthesis::kStoredKernelMaxSamples samples
    std::string kernel_variogram;  ///< the stored kernel's variogram (empty when not stored)
    std::string kernel_status = "ok";  ///< its fit status (kriging::to_string(FitStatus))
    std::string kernel_warning;    ///< synthesis::fit_status_warning, "" when the fit is clean

    double ratio() const { return static_cast<double>(raw_bytes) / static_cast<double>(bytes); }
};

/// Rank search (or explicit ranks), decomposition, measurement, and the model stored (committed).
CompressOutcome compress_set(const std::string& db, const CompressRequest& request);

std::string ranks_text(const tensor::Ranks& r);
std::string describe_compression(const std::string& set, const CompressOutcome& o);
/// The outcome's fields as members of the open JSON object.
void write_compression_json(JsonWriter& j, const CompressOutcome& o);

// ---- rate-distortion report ---------------------------------------------------------------------

struct RateOutcome {
    compression::RateReport report;
    std::uint64_t clip_bytes = 0;  ///< the samples' source channels as float32
    double seconds = 0.0;          ///< seconds of motion of the samples
    std::size_t joints = 0;        ///< joints with rotations
};

/// The report's table on an aligned set (options.parameters is set from the set).
RateOutcome rate_report(const SetContext& c, compression::RateOptions options);

/// The table `mocapdb report` prints (header line, one line per row, legend).
std::string rate_table_text(const std::string& set, const RateOutcome& r);
std::string rate_csv(const RateOutcome& r);
/// Ratio against max error, one series per method (rows meeting a lossy target).
std::string rate_svg(const std::string& set, const RateOutcome& r);
/// "rows": [...] with every figure of each row, as a member of the open JSON object.
void write_rate_rows_json(JsonWriter& j, const RateOutcome& r);

// ---- synthesis ----------------------------------------------------------------------------------

/// The extractors a set's parameters were measured with (parameter_source "extract:turn,speed"),
/// or none.
std::vector<ParameterExtractor> source_extractors(const std::string& parameter_source);

struct SynthOutcome {
    VecX requested;
    Clip clip;
    synthesis::Timing timing;
    double reliability = 0.0;
    VecX measured;          ///< by the set's extractors, empty when the set's parameters were not extracted
    double seconds = 0.0;   ///< timing + motion + reliability
};

SynthOutcome synthesize(const synthesis::SynthesisModel& model, const MotionSet& set, const VecX& c,
                        Eigen::Index level = 0);

// ---- reliability map ----------------------------------------------------------------------------

/// One axis of a 2-D slice of the control space: `count` values from lo to hi.
struct SliceAxis {
    Eigen::Index axis = 0;
    double lo = 0, hi = 0;
    Eigen::Index count = 0;
    double at(Eigen::Index i) const {
        return count > 1 ? lo + (hi - lo) * static_cast<double>(i) / static_cast<double>(count - 1) : lo;
    }
};

struct ReliabilityMap {
    MatX queries;      ///< gx.count · gy.count by P, x fastest
    VecX rho;          ///< per query
    HeatMapSpec spec;  ///< ready for render_heat_map (samples marked)
    double fraction_trusted = 0.0;  ///< share of cells with rho >= 0.85
};

/// rho over the slice gx × gy through `base` (the other axes' values).
ReliabilityMap reliability_map(const synthesis::SynthesisModel& model, const std::string& set, const SliceAxis& gx,
                               const SliceAxis& gy, const VecX& base);

}  // namespace mocapdb::cli
