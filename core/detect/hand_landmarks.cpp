#include "detect/hand_landmarks.hpp"

#include "detect/dnn_input.hpp"
#include "detect/model_files.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace gc {

namespace {

constexpr int kInputSide = 224;
// How a crop follows from a box around the palm (along the crop's axes): the box's long
// side enlarged by `scale`, its centre moved `shift_up` box heights towards the fingers.
// MediaPipe's values for this model: the detector's palm box x2.6, shifted 0.5; the box of
// the palm and near finger joints (about 1.3 palm boxes) x2.0, shifted 0.1.
struct CropRule {
    float scale;
    float shift_up;
};
constexpr CropRule kFromPalmBox{2.6f, 0.5f};
constexpr CropRule kFromLandmarkBox{2.0f, 0.1f};
// The landmarks the next crop is fitted to: the wrist, the thumb's base joints, the knuckles
// and middle joints of the fingers. The middle joints keep the box from resting on the
// wrist, the point this model places least steadily (a crop fitted to the palm alone
// shrinks from frame to frame); the fingertips are left out so that a finger that curls
// or stretches does not resize the crop.
constexpr HandPoint kCropPoints[] = {HandPoint::Wrist,     HandPoint::ThumbCmc,  HandPoint::ThumbMcp,
                                     HandPoint::ThumbIp,   HandPoint::IndexMcp,  HandPoint::IndexPip,
                                     HandPoint::MiddleMcp, HandPoint::MiddlePip, HandPoint::RingMcp,
                                     HandPoint::RingPip,   HandPoint::PinkyMcp,  HandPoint::PinkyPip};

// The rotation that turns the line from `wrist` to `middle_mcp` upright (see HandCrop).
float upright_rotation(cv::Point2f wrist, cv::Point2f middle_mcp)
{
    const double angle = std::numbers::pi / 2 - std::atan2(-(middle_mcp.y - wrist.y), middle_mcp.x - wrist.x);
    return float(std::remainder(angle, 2 * std::numbers::pi));
}

// The crop for a box of `size` (along the crop's axes) at `centre`, turned by `rotation`.
HandCrop crop_around_box(cv::Point2f centre, cv::Size2f size, float rotation, CropRule rule)
{
    const cv::Point2f up(std::sin(rotation), -std::cos(rotation));
    return {centre + up * (rule.shift_up * size.height), rule.scale * std::max(size.width, size.height), rotation};
}

}  // namespace

bool HandCrop::usable() const
{
    return std::isfinite(centre.x) && std::isfinite(centre.y) && std::isfinite(rotation_rad) && std::isfinite(side) &&
           side >= 1.0f;
}

HandCrop crop_from_palm(const PalmDetection& palm)
{
    const cv::Point2f centre(palm.box.x + palm.box.width / 2, palm.box.y + palm.box.height / 2);
    return crop_around_box(centre, palm.box.size(),
                           upright_rotation(palm.point(PalmPoint::Wrist), palm.point(PalmPoint::MiddleMcp)),
                           kFromPalmBox);
}

HandCrop crop_from_landmarks(const HandKeyPoints& hand)
{
    const float rotation = upright_rotation(hand.point(HandPoint::Wrist), hand.point(HandPoint::MiddleMcp));
    // The points' box in the crop's axes (u right, v down), then its centre back in the frame.
    const float c = std::cos(rotation), s = std::sin(rotation);
    float u_min = INFINITY, u_max = -INFINITY, v_min = INFINITY, v_max = -INFINITY;
    for (HandPoint p : kCropPoints) {
        const cv::Point2f q = hand.point(p);
        const float u = c * q.x + s * q.y, v = -s * q.x + c * q.y;
        u_min = std::min(u_min, u), u_max = std::max(u_max, u);
        v_min = std::min(v_min, v), v_max = std::max(v_max, v);
    }
    const float u = (u_min + u_max) / 2, v = (v_min + v_max) / 2;
    const cv::Point2f centre(c * u - s * v, s * u + c * v);
    return crop_around_box(centre, cv::Size2f(u_max - u_min, v_max - v_min), rotation, kFromLandmarkBox);
}

cv::Matx23f crop_to_frame(const HandCrop& crop, int side_px)
{
    const float k = crop.side / float(side_px);
    const float c = std::cos(crop.rotation_rad) * k, s = std::sin(crop.rotation_rad) * k;
    const float half = side_px / 2.0f;
    return {c, -s, crop.centre.x - (c - s) * half, s, c, crop.centre.y - (s + c) * half};
}

LandmarkModel::LandmarkModel(const std::filesystem::path& model_path)
    : net_(load_onnx_model(model_path, {"Identity", "Identity_1", "Identity_2"})), output_names_{"Identity",
                                                                                                 "Identity_1",
                                                                                                 "Identity_2"},
      crop_(kInputSide, kInputSide), scaled_(kInputSide, kInputSide), blob_(make_square_blob(kInputSide))
{
}

HandKeyPoints LandmarkModel::run(const cv::Mat& bgr, const HandCrop& crop)
{
    if (bgr.empty() || bgr.type() != CV_8UC3)
        throw std::invalid_argument("LandmarkModel: expected a non-empty CV_8UC3 (BGR) frame");
    if (!crop.usable()) throw std::invalid_argument("LandmarkModel: empty or non-finite crop");
    const cv::Matx23f to_frame = crop_to_frame(crop, kInputSide);
    // warpAffine maps pixel indices; a pixel's centre lies at index + 0.5 in the continuous
    // coordinates of crop_to_frame, in the crop as in the frame.
    cv::Matx23f sample = to_frame;
    sample(0, 2) += 0.5f * (to_frame(0, 0) + to_frame(0, 1)) - 0.5f;
    sample(1, 2) += 0.5f * (to_frame(1, 0) + to_frame(1, 1)) - 0.5f;
    cv::warpAffine(bgr, crop_, sample, crop_.size(), cv::INTER_LINEAR | cv::WARP_INVERSE_MAP, cv::BORDER_CONSTANT,
                   cv::Scalar::all(0));
    // A hand in a dark picture (an underexposed camera, a backlit room) is shown to the
    // model at a normal exposure.
    brighten_if_dark(crop_, grey_);
    fill_rgb_blob(crop_, 1.0 / 255.0, 0.0, scaled_, blob_);
    net_.setInput(blob_);
    net_.forward(outputs_, output_names_);
    if (outputs_[0].total() != size_t(3 * kHandPoints) || outputs_[1].total() != 1 || outputs_[2].total() != 1)
        throw std::runtime_error("LandmarkModel: the network's outputs are not 63, 1 and 1 values");
    HandKeyPoints hand;
    const float* xyz = outputs_[0].ptr<float>();
    for (int i = 0; i < kHandPoints; ++i) hand.points[i] = to_frame * cv::Vec3f(xyz[3 * i], xyz[3 * i + 1], 1.0f);
    hand.presence = outputs_[1].ptr<float>()[0];
    hand.handedness = outputs_[2].ptr<float>()[0];
    return hand;
}

}  // namespace gc
