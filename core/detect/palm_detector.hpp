// The learned palm detector (MediaPipe's BlazePalm, 128x128 input): finds palms in a whole
// frame, each with its box and seven key points, to start the landmark model on.
#pragma once

#include <opencv2/core.hpp>
#include <opencv2/dnn.hpp>

#include <array>
#include <filesystem>
#include <string>
#include <vector>

namespace gc {

// The palm key points in the detector's order. The wrist and the middle MCP, which orient
// the landmark model's crop, lie close to their joints; the others are rough.
enum class PalmPoint { Wrist = 0, IndexMcp, MiddleMcp, RingMcp, PinkyMcp, ThumbCmc, ThumbMcp };
inline constexpr int kPalmPoints = 7;

struct PalmDetection {
    cv::Rect2f box;                               // frame pixels, the palm without the fingers
    float score = 0.0f;                           // probability of a palm, 0..1
    std::array<cv::Point2f, kPalmPoints> points;  // frame pixels, PalmPoint order
    cv::Point2f point(PalmPoint p) const { return points[static_cast<int>(p)]; }
};

inline constexpr const char* kPalmModelFile = "palm_detection.onnx";

// The network and the input buffers are reused from call to call: one instance per thread.
class PalmDetector {
public:
    // Throws std::runtime_error naming the file when it is missing or not the palm model.
    explicit PalmDetector(const std::filesystem::path& model_path);

    // Palms in `bgr` (CV_8UC3, any size) scoring at least `min_score`, overlapping boxes
    // suppressed, best first. Throws std::invalid_argument on an empty or non-BGR frame.
    std::vector<PalmDetection> detect(const cv::Mat& bgr, float min_score);

private:
    void prepare_input(const cv::Mat& bgr);
    void decode(float min_score);
    cv::Point2f to_frame(int row, float dx, float dy) const;

    cv::dnn::Net net_;
    std::vector<std::string> output_names_;
    std::vector<cv::Point2f> anchors_;  // centres, in units of the input side
    // Preallocated per-call buffers: the letterboxed input, its float copy, the blob.
    cv::Mat3b letterbox_;
    cv::Mat3f scaled_;
    cv::Mat1b grey_;  // the letterboxed picture in grey, to judge its exposure
    cv::Mat blob_;
    std::vector<cv::Mat> outputs_;
    // Letterbox geometry of the last frame: input pixel = frame pixel * scale + offset.
    float scale_ = 1.0f;
    cv::Point2f offset_;
    // Candidates above the score threshold before suppression.
    std::vector<cv::Rect2d> candidate_boxes_;
    std::vector<float> candidate_scores_;
    std::vector<int> candidate_rows_;
    std::vector<int> kept_;
};

}  // namespace gc
