#pragma once
// `mocapdb set create` as a library step: select stored clips by id or pattern, build the
// motion set (segmentation; parameters measured by extractors, then read from a CSV (a column of level
// names is categorical), then categorical ones from the clip ids; periodic parameters; dropout repairs;
// dataset/set_builder.hpp) and store it, committed. Nothing is printed: the clips that
// gave no sample and the samples that are twins (overlapping or duplicated frames) are in the outcome.
//
// Errors: InvalidArgument (no clips stored, a pattern that matches nothing, the set exists and
// replace is false, a parameter given twice, an unknown periodic parameter, a category pattern that
// misses a clip, a level with too few samples, a set that cannot tell motions apart), ParseError naming the CSV's line, StoreError / IoError from the database. Nothing is
// stored when it throws. Threads: the database's writer lock serializes writers (store/writer_lock.hpp).
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "mocapdb/core/progress.hpp"
#include "mocapdb/dataset/motion_set.hpp"
#include "mocapdb/dataset/sample_twins.hpp"
#include "mocapdb/dataset/set_builder.hpp"

namespace mocapdb {
class Database;
}

namespace mocapdb::workflow {

struct SetRequest {
    std::string name;
    std::vector<std::string> clips;    ///< clip ids or fnmatch patterns, in sample order
    std::filesystem::path params_csv;  ///< parameters from a CSV (first column: sample labels)
    std::vector<std::string> extract;  ///< parameters measured by these extractors (first)
    /// Categorical parameters from the clip ids: name and pattern (levels_from_clip_names), last.
    std::vector<std::pair<std::string, std::string>> categories;
    std::vector<std::pair<std::string, double>> periodic;  ///< parameter name and period (bearing is by itself)
    std::string segment = "auto";                          ///< parse_segmentation's spec
    std::vector<std::string> feet;                         ///< left, right foot joints; empty: found by name
    bool replace = false;                                  ///< replace a set of the same name
    ProgressCallback progress;                             ///< per clip loaded and measured; may be empty
};

struct SetOutcome {
    MotionSet set;
    std::size_t clips = 0;                                 ///< clips selected
    std::vector<std::string> skipped;                      ///< clips that gave no sample
    Segmentation segmentation = Segmentation::WholeClips;  ///< what the samples are (auto resolved)
    bool auto_segmentation = false;                        ///< the request left the choice to the data
    SampleTwins twins;  ///< samples showing the same frames (dataset/sample_twins.hpp), default options
};

/// Builds the set from the database's clips and stores it (committed).
SetOutcome create_set(const std::filesystem::path& db, const SetRequest& request);

/// Clip ids matching the patterns (fnmatch), in pattern order (ids sorted within a pattern), each once.
/// InvalidArgument naming `db_name` (the file the user gave) when a pattern matches nothing.
std::vector<std::string> select_clips(const Database& db, const std::string& db_name,
                                      const std::vector<std::string>& patterns);

}  // namespace mocapdb::workflow
