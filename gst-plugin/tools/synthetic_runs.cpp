#include "tools/synthetic_runs.hpp"

#include "tools/bench_stats.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>

namespace gc::tools {

Sequence render_sequence(const gc::sim::Scene& scene, int frames, gc::Eye eye)
{
    Sequence s;
    s.frames.resize(frames);
    s.masks.resize(frames);
    s.boxes.resize(frames);
    s.visible.resize(frames);
    gc::sim::EyeTruth truth;
    for (int f = 0; f < frames; ++f) {
        scene.render(f, eye, gc::HeadPose{}, s.frames[f], &truth);
        s.masks[f] = truth.mask.clone();
        s.boxes[f] = truth.bbox;
        s.visible[f] = truth.visible;
        if (truth.visible && s.first_visible < 0) s.first_visible = f;
    }
    return s;
}

TrackerCost run_tracker(const Sequence& seq, const gc::TrackerParams& params, int runs, AccuracyRow* row,
                        std::vector<cv::Rect>* boxes)
{
    const int n = static_cast<int>(seq.frames.size());
    const cv::Size size = seq.frames.front().size();
    const cv::Mat1b empty(size, 0);
    std::vector<double> per_run, cpu_per_run;
    for (int run = 0; run < runs; ++run) {
        gc::HandTracker tracker(params);
        double total_ms = 0.0, total_cpu_ms = 0.0;
        int acquired = -1;
        for (int f = 0; f < n; ++f) {
            const auto t0 = BenchClock::now();
            const double cpu0 = thread_cpu_ms();
            const gc::EyeEstimate& e = tracker.process(seq.frames[f]);
            total_cpu_ms += thread_cpu_ms() - cpu0;
            total_ms += ms_since(t0);
            if (run != 0) continue;
            const bool tracking = e.state == gc::TrackState::Tracking;
            if (boxes) boxes->push_back(tracking && !e.contour.empty() ? cv::boundingRect(e.contour) : cv::Rect());
            if (!row) continue;
            if (tracking && acquired < 0) acquired = f;
            if (seq.first_visible >= 0 && f >= seq.first_visible && seq.visible[f]) {
                ++row->visible;
                row->tracked += tracking ? 1 : 0;
            }
            if (acquired >= 0 && e.state == gc::TrackState::Lost) ++row->lost;
            // Scored from the first frame where the hand shows: the acquisition delay, like
            // any frame where we do not track, counts as an empty silhouette.
            if (seq.first_visible < 0 || f < seq.first_visible) continue;
            const cv::Mat1b tracked = tracking && !e.contour.empty() ? gc::contour_mask(e.contour, size) : empty;
            row->snr.add(seq.masks[f], tracked);
            row->iou_sum += gc::mask_iou(seq.masks[f], tracked);
            ++row->iou_frames;
        }
        if (run == 0 && row) row->acquired_at.push_back(acquired);
        per_run.push_back(total_ms / n);
        cpu_per_run.push_back(total_cpu_ms / n);
    }
    return {median(per_run), median(cpu_per_run)};
}

Baseline measure_baseline(const Sequence& seq, int runs)
{
    cv::Mat copy, converted;
    std::vector<double> copy_runs, convert_runs;
    const double n = static_cast<double>(seq.frames.size());
    for (int run = 0; run < std::max(runs, 5); ++run) {
        auto t0 = BenchClock::now();
        for (const cv::Mat& f : seq.frames) f.copyTo(copy);
        copy_runs.push_back(ms_since(t0) / n);
        t0 = BenchClock::now();
        for (const cv::Mat& f : seq.frames) cv::cvtColor(f, converted, cv::COLOR_BGR2RGB);
        convert_runs.push_back(ms_since(t0) / n);
    }
    return {median(copy_runs), median(convert_runs)};
}

}  // namespace gc::tools
