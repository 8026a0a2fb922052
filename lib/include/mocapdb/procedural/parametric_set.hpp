#pragma once
// Parametric motion sets: the generators run over a grid of control parameters, giving clips and
// their parameter table, ready for `mocapdb import` and `mocapdb set create --params`.
//
// On disk (write_parametric_set): one BVH file per clip, named CLIP.bvh (the clip name becomes the
// clip id on import), and params.csv with the header "sample,NAME[UNIT],..." and one row per clip,
// labelled by the clip name (the label `set create --params` expects for whole-clip samples).
//   walk:  speed[cm/s], turn[rad]  (the names, units and definitions of the `speed` and `turn`
//          extractors, so `--params params.csv` and `--extract speed turn` agree)
//   reach: angle[deg], height[cm], distance[cm]  (the target, see reach.hpp)
#include <filesystem>
#include <string>
#include <vector>

#include "mocapdb/core/types.hpp"
#include "mocapdb/motion/clip.hpp"
#include "mocapdb/procedural/reach.hpp"
#include "mocapdb/procedural/walk.hpp"

namespace mocapdb::procedural {

/// One axis of a grid: `count` values evenly spaced from `low` to `high` (count 1: low only).
struct GridAxis {
    std::string name;
    double low = 0.0;
    double high = 0.0;
    std::size_t count = 1;

    /// Value i of the axis.
    double value(std::size_t i) const;
};

/// Parses "NAME=LOW:HIGH:COUNT" or "NAME=VALUE" (InvalidArgument naming the text otherwise).
GridAxis parse_grid_axis(const std::string& spec);

/// Axes of a walk grid: speed in m/s, turn in degrees over the clip, stride in m (0 = from speed).
struct WalkGrid {
    GridAxis speed{"speed", 0.9, 1.7, 3};
    GridAxis turn{"turn", -60.0, 60.0, 5};
    GridAxis stride{"stride", 0.0, 0.0, 1};
    WalkOptions options;
};

/// Axes of a reach grid: target angle (degrees), height (cm), distance (cm).
struct ReachGrid {
    GridAxis angle{"angle", -90.0, 90.0, 5};
    GridAxis height{"height", 60.0, 160.0, 3};
    GridAxis distance{"distance", 55.0, 55.0, 1};
    ReachOptions options;
};

/// Generated clips with their control parameters (N by P, row i for clips[i]).
struct ParametricSet {
    std::string kind;         ///< "walk" or "reach"
    std::vector<Clip> clips;  ///< named uniquely (walk_s130_t+030, reach_a+045_h120_d55)
    std::vector<std::string> parameter_names;
    std::vector<std::string> parameter_units;
    MatX parameters;
};

/// Sets the grid's keys from "NAME=..." specs (names: speed, turn, stride / angle, height, distance);
/// InvalidArgument for an unknown name.
void apply_grid_specs(WalkGrid& grid, const std::vector<std::string>& specs);
void apply_grid_specs(ReachGrid& grid, const std::vector<std::string>& specs);

/// Every grid point (first axis slowest). InvalidArgument (naming the point) when one is out of range.
ParametricSet generate_walk_set(const WalkGrid& grid);
ParametricSet generate_reach_set(const ReachGrid& grid);

/// Writes DIR/CLIP.bvh for every clip and DIR/params.csv (each file atomically; `precision`
/// significant digits in the BVH). Creates DIR. Refuses (IoError, before writing anything) to overwrite an existing
/// file unless `overwrite`. Returns the paths written, params.csv last.
std::vector<std::filesystem::path> write_parametric_set(const std::filesystem::path& dir, const ParametricSet& set,
                                                        bool overwrite = false, int precision = 9);

}  // namespace mocapdb::procedural
