// gesturecam-bench's command line: what to measure and how often.
#pragma once

#include "sim/scene.hpp"
#include "tracker/hand_tracker.hpp"

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace gc::tools {

extern const std::string_view kBenchUsage;

std::string_view detector_name(gc::HandDetector d);

struct BenchOptions {
    std::vector<int> particles{20, 50, 100, 200, 500, 1000, 2000, 5000};
    std::vector<gc::sim::Preset> scenes{gc::sim::Preset::Clean, gc::sim::Preset::Light, gc::sim::Preset::Heavy,
                                        gc::sim::Preset::FacePass};
    gc::sim::Motion motion = gc::sim::Motion::Mixed;
    // The first one is also the one set beside OpenCV's trackers.
    std::vector<gc::HandDetector> detectors{gc::HandDetector::Learned, gc::HandDetector::Motion};
    int frames = 150;
    int runs = 5;
    std::vector<std::uint64_t> seeds{1, 2, 3};
    int peer_particles = 1000;
    bool peers = true;
    std::string real_dir;             // the real pair's folder; empty: skip it
    bool real_dir_given = false;      // named on the command line (else the source tree's)
    int real_frames = 1 << 30;        // the real pair's first frames that are tracked
    double real_noise = 0.0;          // camera noise added to the real pair's frames (grey levels, sd)
    double real_dim = 1.0;            // the real pair's frames dimmed (RealPairOptions::dim)
    bool real_bright_window = false;  // RealPairOptions::bright_window
    int real_tracking_width = 0;      // the pair's views tracked at this width (TrackerParams::tracking_width)
    bool json = false;
};

// Parses the command line into `o`: -1 to go on, else the status to exit with (0 after --help
// or --version, 2 after a one-line hint on a wrong command line).
int parse_bench_options(int argc, char** argv, BenchOptions& o);

}  // namespace gc::tools
