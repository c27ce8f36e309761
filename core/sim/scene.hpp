// The synthetic stereo scene: a room, a person's forearm and hand in a rigid gesture
// (pointing, open or fist), seen by the two cameras of the motorised head. The embedded default input of the
// plugin and the test bed of the tracker; every frame comes with its ground truth.
#pragma once

#include "common/types.hpp"
#include "stereo/calibration.hpp"

#include <opencv2/core.hpp>

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

namespace gc::sim {

// Background clutter; measured skin-pixel fractions near the thesis's scenes:
// clean 0.03 %, light 3.74 %, heavy 9.35 %; face-pass: light clutter plus a face that the
// hand's path crosses. varied: a room drawn from many kinds (wall materials, photo-like
// posters of faces and hands, skin-coloured walls and objects, none to two people), always
// with the wide variety.
enum class Preset { Clean, Light, Heavy, FacePass, Varied };

// How much a scene varies from seed to seed besides its layout and motion. None: one hand
// shape, the camera and light of the presets as they always were. Wide: the hand's shape and
// skin, the sleeve, the people, the light and the camera (noise, blur, exposure, white
// balance, vignetting, compression) are drawn from the seed too.
enum class Variety { None, Wide };

// Scripted hand motions. Every script starts with a short wave (so that motion-based
// acquisition has something to find) and then runs its motion.
enum class Motion {
    Static,       // holds still after the wave
    Translate,    // moves in the image plane
    Rotate,       // in-plane rotation of the pointing direction
    Scale,        // towards and away from the cameras
    Yaw,          // out-of-plane rotation of the hand plane about the vertical
    Mixed,        // all of the above at once
    LeaveReturn,  // leaves the view, stays out for a while, comes back
};

std::optional<Preset> preset_from_string(std::string_view name);
std::optional<Motion> motion_from_string(std::string_view name);
std::string_view to_string(Preset p);
std::string_view to_string(Motion m);
std::optional<Variety> variety_from_string(std::string_view name);
std::string_view to_string(Variety v);

struct SceneConfig {
    Preset preset = Preset::Clean;
    Motion motion = Motion::Mixed;
    std::uint64_t seed = 1;           // background layout, skin tone, noise: same seed, same scene
    Variety variety = Variety::None;  // the varied preset is wide whatever this says
    int width = 640;
    int height = 480;
    double fps = 30.0;
    double focal_px = 0.0;  // 0: a 60 degree horizontal field of view
    double baseline_mm = 120.0;
    double hand_distance_mm = 1000.0;  // of the palm from the head at rest
    double noise_sigma = 2.0;          // sensor noise, grey levels (wide: scaled by 0.5-4 per seed)
    bool lighting_change = false;      // a slow global change of brightness and colour temperature
    // At rest the finger points from the palm at this head-frame point (mm), e.g. at something
    // across the room; unset: the seed's direction, obliquely up to one side.
    std::optional<cv::Vec3d> aim_mm;
    // The hand's gesture: Pointing, Open or Fist. With gesture_cycle_s = T > 0 the hand
    // holds `gesture` for T seconds, then points for T seconds, and so on; 0 holds it.
    Gesture gesture = Gesture::Pointing;
    double gesture_cycle_s = 0.0;
};

// The hand in the head frame (see stereo/head_geometry.hpp), millimetres.
struct HandPose {
    cv::Vec3d palm_mm{0.0, 0.0, 1000.0};  // palm centre
    double roll_deg = 0.0;                // in the hand plane: 0 = finger points to +x (right), 90 = up
    double yaw_deg = 0.0;                 // hand plane about the vertical; 0 = palm faces the cameras
    double pitch_deg = 0.0;               // hand plane about the horizontal
    double forearm_mm = 260.0;            // palm centre to elbow, opposite to the finger
    Gesture gesture = Gesture::Pointing;  // Pointing, Open or Fist
};

// Ground truth of the hand in 3D for one frame (head frame, millimetres). Only a pointing
// hand has a pointing ray; for open and fist, the "fingertip" is the hand's farthest reach
// along its long axis (a fingertip of the open hand, the knuckles of the fist), and
// `direction` that axis.
struct HandTruth {
    cv::Vec3d fingertip_mm;
    cv::Vec3d palm_mm;  // centroid of the palm
    cv::Vec3d elbow_mm;
    cv::Vec3d direction;  // unit, palm -> fingertip
    Gesture gesture = Gesture::Pointing;
    bool points() const { return gesture == Gesture::Pointing; }
};

// Ground truth of one eye for one frame (image pixels).
struct EyeTruth {
    cv::Mat1b mask;        // 255 on the hand (palm, fingers, thumb; not the forearm)
    bool visible = false;  // enough of the hand in view to be trackable
    cv::Point2d palm_px;
    cv::Point2d fingertip_px;
    double pointing_deg = 0.0;  // palm -> fingertip, 0 = +x, counter-clockwise, y up
    cv::Rect bbox;              // of the mask
    cv::Mat1b face;             // 255 where people's skin is (behind the hand); empty without people
    Gesture gesture = Gesture::Pointing;  // fingertip_px and pointing_deg as in HandTruth
};

class Scene {
public:
    explicit Scene(const SceneConfig& config);
    ~Scene();
    Scene(Scene&&) noexcept;
    Scene& operator=(Scene&&) noexcept;

    const SceneConfig& config() const;

    // The scripted hand pose at frame index `frame` (time = frame / fps).
    HandPose hand_pose(int frame) const;
    HandTruth hand_truth(const HandPose& pose) const;

    // Renders one eye as CV_8UC3 BGR of config size into `bgr` (reusing its buffer).
    void render(int frame, Eye eye, const HeadPose& head, cv::Mat& bgr, EyeTruth* truth = nullptr) const;
    // The same with an explicit hand pose (for 3D experiments).
    void render_pose(const HandPose& hand, int frame, Eye eye, const HeadPose& head, cv::Mat& bgr,
                     EyeTruth* truth = nullptr) const;

    // The exact calibration of the simulated rig (no distortion), with head geometry.
    StereoCalibration calibration() const;

    // Fraction of background pixels (outside the hand mask) that the skin segmentation,
    // fitted on the hand's own pixels, classifies as skin: the thesis's clutter measure.
    double measured_skin_fraction(int frame = 0) const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace gc::sim
