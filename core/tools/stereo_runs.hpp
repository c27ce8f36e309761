// gesturecam-bench's stereo figures on the clean synthetic scene: the 3D step's cost and
// accuracy against the scene's truth, and the whole stereo pipeline's throughput.
#pragma once

#include "tools/bench_options.hpp"

#include <cmath>

namespace gc::tools {

struct StereoFigures {
    int frames = 0;
    int valid = 0;
    double estimate_ms = std::nan("");
    double direction_error_deg = std::nan("");
    double palm_error_mm = std::nan("");
    double fps = std::nan("");
};

StereoFigures measure_stereo(const BenchOptions& o);

}  // namespace gc::tools
