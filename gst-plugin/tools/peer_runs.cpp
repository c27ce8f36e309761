#include "tools/peer_runs.hpp"

#include "tools/bench_stats.hpp"
#include "tools/peer_trackers.hpp"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <optional>

namespace gc::tools {

namespace {

double box_iou(const cv::Rect& a, const cv::Rect& b)
{
    const double inter = (a & b).area();
    const double uni = static_cast<double>(a.area()) + b.area() - inter;
    return uni > 0.0 ? inter / uni : 0.0;
}

void score_boxes(const Sequence& seq, int from, const std::vector<std::optional<cv::Rect>>& boxes, PeerScore& score)
{
    for (int f = from; f < static_cast<int>(seq.frames.size()); ++f) {
        if (!seq.visible[f]) continue;
        score.iou_sum += boxes[f] ? box_iou(*boxes[f], seq.boxes[f]) : 0.0;
        ++score.frames;
    }
}

// One peer from the true box at frame `init`; scored as never finding the hand when it
// cannot start, so the tables stay comparable.
void run_peer(PeerTracker& peer, const Sequence& seq, int init, const std::string& where, PeerScore& score)
{
    const int frames = static_cast<int>(seq.frames.size());
    std::vector<std::optional<cv::Rect>> boxes(frames);
    try {
        peer.init(seq.frames[init], seq.boxes[init], seq.masks[init]);
    } catch (const std::exception& e) {
        std::cerr << "gesturecam-bench: warning: " << peer.name() << " could not start on " << where << ": " << e.what()
                  << '\n';
        score_boxes(seq, init + 1, boxes, score);
        return;
    }
    double total = 0.0;
    for (int f = init + 1; f < frames; ++f) {
        const auto t0 = BenchClock::now();
        boxes[f] = peer.update(seq.frames[f]);
        total += ms_since(t0);
    }
    score_boxes(seq, init + 1, boxes, score);
    score.ms.push_back(total / (frames - init - 1));
}

}  // namespace

void compare_with_peers(const Sequence& seq, const gc::TrackerParams& params, const std::string& where,
                        std::map<std::string, PeerScore>& scores)
{
    const int frames = static_cast<int>(seq.frames.size());
    std::vector<cv::Rect> our_boxes;
    AccuracyRow ours_row;
    const double our_ms = run_tracker(seq, params, 1, &ours_row, &our_boxes).ms;
    // Peers start where we acquire, or where the hand first shows if we never do.
    int init = ours_row.acquired_at.front() >= 0 ? ours_row.acquired_at.front() : seq.first_visible;
    while (init >= 0 && init < frames && !seq.visible[init]) ++init;
    if (init < 0 || init >= frames - 1) return;  // the hand never shows: nothing to compare
    std::vector<std::optional<cv::Rect>> boxes(frames);
    for (int f = 0; f < frames; ++f)
        if (our_boxes[f].area() > 0) boxes[f] = our_boxes[f];
    PeerScore& ours = scores["gesturecam"];
    score_boxes(seq, init + 1, boxes, ours);
    ours.ms.push_back(our_ms);
    for (auto& peer : make_peer_trackers()) run_peer(*peer, seq, init, where, scores[std::string(peer->name())]);
}

void append_peer_rows(const std::string& scene, const std::map<std::string, PeerScore>& scores,
                      std::vector<PeerRow>& rows)
{
    for (const auto& [name, score] : scores)
        rows.push_back({scene, name, score.frames > 0 ? score.iou_sum / score.frames : std::nan(""), mean(score.ms),
                        score.frames});
    std::stable_partition(rows.end() - static_cast<std::ptrdiff_t>(scores.size()), rows.end(),
                          [](const PeerRow& r) { return r.tracker == "gesturecam"; });
}

}  // namespace gc::tools
