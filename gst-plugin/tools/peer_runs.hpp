// gesturecam-bench beside OpenCV's trackers: each starts from the true box at the frame
// where ours acquires and is scored by box IoU against the truth on the same later frames.
#pragma once

#include "tools/synthetic_runs.hpp"

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace gc::tools {

// Box IoU and cost of one tracker over the frames after its initialisation frame.
struct PeerScore {
    double iou_sum = 0.0;
    std::int64_t frames = 0;
    std::vector<double> ms;
};

// One tracker's figures on one scene, pooled over seeds.
struct PeerRow {
    std::string scene;
    std::string tracker;
    double iou = 0.0;
    double ms = 0.0;
    std::int64_t frames = 0;
};

// Runs ours (`params`) and every peer on `seq`, adding to `scores` by tracker name
// ("gesturecam" for ours). `where` names the sequence in warnings.
void compare_with_peers(const Sequence& seq, const gc::TrackerParams& params, const std::string& where,
                        std::map<std::string, PeerScore>& scores);

// Appends one row per tracker of `scores` to `rows`: ours first, then OpenCV's by name.
void append_peer_rows(const std::string& scene, const std::map<std::string, PeerScore>& scores,
                      std::vector<PeerRow>& rows);

}  // namespace gc::tools
