// The learned hand landmark model (MediaPipe's, 224x224 input): 21 points of one hand from a
// rotated square crop around it, and the crops that feed it, from a palm detection or from
// the previous frame's points.
#pragma once

#include "detect/palm_detector.hpp"

#include <opencv2/core.hpp>
#include <opencv2/dnn.hpp>

#include <array>
#include <filesystem>
#include <string>
#include <vector>

namespace gc {

// The 21 landmarks in the model's order: wrist, then four joints per finger from the base
// (CMC/MCP) to the tip, thumb first.
enum class HandPoint {
    Wrist = 0,
    ThumbCmc,
    ThumbMcp,
    ThumbIp,
    ThumbTip,
    IndexMcp,
    IndexPip,
    IndexDip,
    IndexTip,
    MiddleMcp,
    MiddlePip,
    MiddleDip,
    MiddleTip,
    RingMcp,
    RingPip,
    RingDip,
    RingTip,
    PinkyMcp,
    PinkyPip,
    PinkyDip,
    PinkyTip,
};
inline constexpr int kHandPoints = 21;

struct HandKeyPoints {
    std::array<cv::Point2f, kHandPoints> points;  // frame pixels, HandPoint order
    float presence = 0.0f;                        // probability that the crop holds a hand, 0..1
    float handedness = 0.0f;                      // the model's left/right score, 0..1
    cv::Point2f point(HandPoint p) const { return points[static_cast<int>(p)]; }
};

// A rotated square of the frame: its centre and side in frame pixels, and the rotation
// (radians, clockwise on screen) that takes the crop's up direction to the hand's: the
// crop's up axis points along (sin r, -cos r) in the frame.
struct HandCrop {
    cv::Point2f centre;
    float side = 0.0f;
    float rotation_rad = 0.0f;

    // Finite, and at least a pixel a side: a crop from key points collapsed into one point
    // or gone non-finite, or from a palm box regressed inside out, is not.
    bool usable() const;
};

// The crop for the landmark model around a detected palm: about 2.6 palm sizes, shifted
// towards the fingers and rotated so that wrist -> middle-finger MCP points up.
HandCrop crop_from_palm(const PalmDetection& palm);

// The crop for the next frame from a hand's landmarks: the box of its palm and the fingers'
// near joints, doubled (again about 2.6 palm sizes), rotated the same way.
HandCrop crop_from_landmarks(const HandKeyPoints& hand);

// The 2x3 affine map from crop coordinates (0..side_px across the square, continuous, y
// down) to frame coordinates.
cv::Matx23f crop_to_frame(const HandCrop& crop, int side_px);

inline constexpr const char* kLandmarkModelFile = "hand_landmark.onnx";

// The network and the input buffers are reused from call to call: one instance per thread.
class LandmarkModel {
public:
    // Throws std::runtime_error naming the file when it is missing or not the landmark model.
    explicit LandmarkModel(const std::filesystem::path& model_path);

    // The hand in `crop` of `bgr` (CV_8UC3), its points in frame pixels. Throws
    // std::invalid_argument on an empty or non-BGR frame or an empty crop.
    HandKeyPoints run(const cv::Mat& bgr, const HandCrop& crop);

private:
    cv::dnn::Net net_;
    std::vector<std::string> output_names_;
    // Preallocated per-call buffers: the warped crop, its float copy, the blob.
    cv::Mat3b crop_;
    cv::Mat1b grey_;
    cv::Mat3f scaled_;
    cv::Mat blob_;
    std::vector<cv::Mat> outputs_;
};

}  // namespace gc
