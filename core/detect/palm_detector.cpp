#include "detect/palm_detector.hpp"

#include "detect/dnn_input.hpp"
#include "detect/model_files.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace gc {

namespace {

constexpr int kInputSide = 128;
constexpr int kAnchorCount = 896;
constexpr int kRegressorWidth = 18;  // box cx, cy, w, h, then 7 key points (x, y)
// Boxes overlapping a better one by more than this (intersection over union) are dropped.
constexpr float kOverlapLimit = 0.3f;
// Raw scores are clamped before the sigmoid, as the model's own pipeline does.
constexpr float kLogitClamp = 100.0f;

// SSD anchor centres in input units: a 16x16 grid with 2 anchors per cell (stride 8), then
// an 8x8 grid with 6 per cell (stride 16), cell by cell in row-major order.
std::vector<cv::Point2f> make_anchors()
{
    std::vector<cv::Point2f> anchors;
    anchors.reserve(kAnchorCount);
    const struct {
        int grid, per_cell;
    } layers[] = {{16, 2}, {8, 6}};
    for (const auto& layer : layers)
        for (int y = 0; y < layer.grid; ++y)
            for (int x = 0; x < layer.grid; ++x)
                for (int k = 0; k < layer.per_cell; ++k)
                    anchors.emplace_back((x + 0.5f) / layer.grid, (y + 0.5f) / layer.grid);
    return anchors;
}

float sigmoid(float logit) { return 1.0f / (1.0f + std::exp(-std::clamp(logit, -kLogitClamp, kLogitClamp))); }

}  // namespace

PalmDetector::PalmDetector(const std::filesystem::path& model_path)
    : net_(load_onnx_model(model_path, {"regressors", "classificators"})), output_names_{"regressors",
                                                                                         "classificators"},
      anchors_(make_anchors()), letterbox_(kInputSide, kInputSide), scaled_(kInputSide, kInputSide),
      blob_(make_square_blob(kInputSide))
{
}

// Letterboxes the frame into the square input (centred, black bars), RGB in [-1, 1], planar.
void PalmDetector::prepare_input(const cv::Mat& bgr)
{
    scale_ = float(kInputSide) / float(std::max(bgr.cols, bgr.rows));
    const int w = std::clamp(int(std::lround(bgr.cols * scale_)), 1, kInputSide);
    const int h = std::clamp(int(std::lround(bgr.rows * scale_)), 1, kInputSide);
    const cv::Rect inner((kInputSide - w) / 2, (kInputSide - h) / 2, w, h);
    offset_ = cv::Point2f(float(inner.x), float(inner.y));
    letterbox_.setTo(cv::Scalar::all(0));
    cv::Mat3b target = letterbox_(inner);
    cv::resize(bgr, target, inner.size(), 0, 0, cv::INTER_AREA);
    // A dark frame is brightened as the landmark crop is (docs/adr/0041); its exposure is
    // judged on the picture, not the bars.
    brighten_if_dark(target, grey_);
    fill_rgb_blob(letterbox_, 1.0 / 127.5, -1.0, scaled_, blob_);
}

// A regressed offset (input pixels) from anchor `row`'s centre, in frame pixels.
cv::Point2f PalmDetector::to_frame(int row, float dx, float dy) const
{
    return (anchors_[row] * float(kInputSide) + cv::Point2f(dx, dy) - offset_) / scale_;
}

// Candidate boxes above the threshold, in frame pixels, and the rows they came from.
void PalmDetector::decode(float min_score)
{
    const float* regressors = outputs_[0].ptr<float>();
    const float* logits = outputs_[1].ptr<float>();
    candidate_boxes_.clear();
    candidate_scores_.clear();
    candidate_rows_.clear();
    for (int i = 0; i < kAnchorCount; ++i) {
        const float score = sigmoid(logits[i]);
        if (score < min_score) continue;
        const float* r = regressors + i * kRegressorWidth;
        // A box regressed inside out (negative width or height) is no palm; its crop would be.
        if (!(r[2] > 0.0f && r[3] > 0.0f && std::isfinite(r[0] + r[1] + r[2] + r[3]))) continue;
        const cv::Point2f corner = to_frame(i, r[0] - r[2] / 2, r[1] - r[3] / 2);
        candidate_boxes_.emplace_back(corner.x, corner.y, r[2] / scale_, r[3] / scale_);
        candidate_scores_.push_back(score);
        candidate_rows_.push_back(i);
    }
}

std::vector<PalmDetection> PalmDetector::detect(const cv::Mat& bgr, float min_score)
{
    if (bgr.empty() || bgr.type() != CV_8UC3)
        throw std::invalid_argument("PalmDetector: expected a non-empty CV_8UC3 (BGR) frame");
    prepare_input(bgr);
    net_.setInput(blob_);
    net_.forward(outputs_, output_names_);
    if (outputs_[0].total() != size_t(kAnchorCount) * kRegressorWidth || outputs_[1].total() != size_t(kAnchorCount))
        throw std::runtime_error("PalmDetector: the network's outputs are not 896x18 and 896x1");
    decode(min_score);
    cv::dnn::NMSBoxes(candidate_boxes_, candidate_scores_, min_score, kOverlapLimit, kept_);
    std::vector<PalmDetection> palms;
    palms.reserve(kept_.size());
    const float* regressors = outputs_[0].ptr<float>();
    for (int k : kept_) {
        const int row = candidate_rows_[k];
        const float* r = regressors + row * kRegressorWidth;
        PalmDetection palm;
        palm.box = cv::Rect2f(candidate_boxes_[k]);
        palm.score = candidate_scores_[k];
        for (int p = 0; p < kPalmPoints; ++p) palm.points[p] = to_frame(row, r[4 + 2 * p], r[5 + 2 * p]);
        palms.push_back(palm);
    }
    return palms;
}

}  // namespace gc
