// OpenCV's own single-object trackers, run beside ours by gesturecam-bench on the same frames:
// KCF, CSRT and MedianFlow from opencv_contrib, and CamShift on the skin probability map.
#pragma once

#include "skin/skin_model.hpp"

#include <opencv2/core.hpp>
#include <opencv2/tracking.hpp>
#include <opencv2/tracking/tracking_legacy.hpp>
#include <opencv2/video/tracking.hpp>

#include <memory>
#include <optional>
#include <string_view>
#include <vector>

namespace gc::tools {

// A box tracker initialised from a true box; update() gives the box or nothing (lost).
class PeerTracker {
public:
    virtual ~PeerTracker() = default;
    virtual std::string_view name() const = 0;
    // `mask` is the true hand mask of the first frame (used by trackers that learn colour).
    virtual void init(const cv::Mat& bgr, const cv::Rect& box, const cv::Mat1b& mask) = 0;
    virtual std::optional<cv::Rect> update(const cv::Mat& bgr) = 0;
};

// The cv::Tracker family (KCF, CSRT).
class ModernPeer : public PeerTracker {
public:
    using Factory = cv::Ptr<cv::Tracker> (*)();
    ModernPeer(std::string_view name, Factory factory) : name_(name), factory_(factory) {}
    std::string_view name() const override { return name_; }
    void init(const cv::Mat& bgr, const cv::Rect& box, const cv::Mat1b&) override
    {
        tracker_ = factory_();
        tracker_->init(bgr, box);
    }
    std::optional<cv::Rect> update(const cv::Mat& bgr) override
    {
        cv::Rect box;
        if (!tracker_->update(bgr, box)) return std::nullopt;
        return box;
    }

private:
    std::string_view name_;
    Factory factory_;
    cv::Ptr<cv::Tracker> tracker_;
};

class MedianFlowPeer : public PeerTracker {
public:
    std::string_view name() const override { return "medianflow"; }
    void init(const cv::Mat& bgr, const cv::Rect& box, const cv::Mat1b&) override
    {
        tracker_ = cv::legacy::TrackerMedianFlow::create();
        tracker_->init(bgr, cv::Rect2d(box));
    }
    std::optional<cv::Rect> update(const cv::Mat& bgr) override
    {
        cv::Rect2d box;
        if (!tracker_->update(bgr, box)) return std::nullopt;
        return cv::Rect(box);
    }

private:
    cv::Ptr<cv::legacy::TrackerMedianFlow> tracker_;
};

// CamShift (Bradski 1998) on our skin probability map, the model fitted to the true hand
// pixels of the first frame: the classic colour-blob hand tracker.
class CamShiftPeer : public PeerTracker {
public:
    std::string_view name() const override { return "camshift"; }
    void init(const cv::Mat& bgr, const cv::Rect& box, const cv::Mat1b& mask) override
    {
        model_ = SkinModel::fit(bgr, mask);
        window_ = box;
    }
    std::optional<cv::Rect> update(const cv::Mat& bgr) override
    {
        if (window_.area() <= 0) return std::nullopt;  // collapsed earlier: CamShift cannot recover by itself
        model_->probability(bgr, probability_);
        const cv::RotatedRect r = cv::CamShift(
            probability_, window_, cv::TermCriteria(cv::TermCriteria::EPS | cv::TermCriteria::COUNT, 10, 1.0));
        const cv::Rect box = r.boundingRect() & cv::Rect(0, 0, bgr.cols, bgr.rows);
        if (box.area() <= 0) return std::nullopt;
        return box;
    }

private:
    std::optional<SkinModel> model_;
    cv::Rect window_;
    cv::Mat1b probability_;
};

inline std::vector<std::unique_ptr<PeerTracker>> make_peer_trackers()
{
    std::vector<std::unique_ptr<PeerTracker>> peers;
    peers.push_back(std::make_unique<ModernPeer>("kcf", [] { return cv::Ptr<cv::Tracker>(cv::TrackerKCF::create()); }));
    peers.push_back(
        std::make_unique<ModernPeer>("csrt", [] { return cv::Ptr<cv::Tracker>(cv::TrackerCSRT::create()); }));
    peers.push_back(std::make_unique<MedianFlowPeer>());
    peers.push_back(std::make_unique<CamShiftPeer>());
    return peers;
}

}  // namespace gc::tools
