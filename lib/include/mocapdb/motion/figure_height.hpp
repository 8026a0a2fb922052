#pragma once
// How tall a figure stands: the check that catches a skeleton read in the wrong length unit or with
// its position channels read in the wrong convention (every bone doubled).
#include <string>

#include "mocapdb/motion/clip.hpp"

namespace mocapdb {

/// Vertical extent (+Y) of the body in one frame row, cm: highest minus lowest of the motion root and
/// every joint and end site below it (a static ROOT above the body is not part of the figure).
double figure_height(const Skeleton& skeleton, const double* row);

/// Heights a human figure plausibly has at frame 0, cm (a child crouching .. arms raised overhead).
constexpr double kPlausibleFigureMinCm = 50.0;
constexpr double kPlausibleFigureMaxCm = 250.0;

/// A sentence when `height_cm` lies outside the plausible range, naming the usual causes; empty
/// otherwise.
std::string figure_height_warning(double height_cm);

}  // namespace mocapdb
