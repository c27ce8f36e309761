// gesturecam-bench's stereo figures on the clean synthetic scene: the 3D step's cost and
// accuracy against the scene's truth, and the whole stereo pipeline's throughput, with and
// without rendering the two views.
#pragma once

#include "tools/bench_options.hpp"

#include <cmath>

namespace gc::tools {

struct StereoFigures {
    gc::HandDetector detector = gc::HandDetector::Learned;
    int frames = 0;
    int valid = 0;
    double estimate_ms = std::nan("");
    double direction_error_deg = std::nan("");
    double palm_error_mm = std::nan("");
    double fps = std::nan("");            // frames rendered beforehand
    double cpu_ms = std::nan("");         // ... CPU time per stereo frame, all threads
    double rendering_fps = std::nan("");  // both views rendered in the timed loop
    double rendering_cpu_ms = std::nan("");
    double models_share = std::nan("");  // eye-frames on which the learned models ran
};

StereoFigures measure_stereo(const BenchOptions& o, gc::HandDetector detector);

}  // namespace gc::tools
