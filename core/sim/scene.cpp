#include "sim/scene.hpp"

#include "sim/appearance.hpp"
#include "sim/camera_effects.hpp"
#include "sim/figures.hpp"
#include "sim/hand_gestures.hpp"
#include "sim/hand_model.hpp"
#include "sim/motion_script.hpp"
#include "sim/rig.hpp"
#include "sim/scene_checks.hpp"
#include "sim/room.hpp"
#include "sim/variety.hpp"
#include "skin/skin_model.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <mutex>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

namespace gc::sim {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kWallDistanceMm = 3000.0;
constexpr double kMinHandDepthMm = 50.0;  // nearer than this to a camera, the hand is not drawn
constexpr int kMinVisiblePixels = 150;

// Independent random streams of one seed.
enum Stream : std::uint64_t {
    kHandStream = 1,
    kRoomStream,
    kMotionStream,
    kPersonStream,
    kNoiseStream,
    kFrameStream,
    kLooksStream
};

// Direction towards the key light (head frame): above, left, in front.
const cv::Vec3d kLight = cv::normalize(cv::Vec3d(-0.35, -0.6, -0.72));

// The hand's plane in the head frame: u to the fingertip, v to the thumb side, n its normal.
struct HandFrame {
    cv::Vec3d origin, u, v, n;
};

HandFrame hand_frame(const HandPose& p)
{
    const double r = p.roll_deg * kPi / 180.0;
    const cv::Matx33d R = rotation_about_y(p.yaw_deg) * rotation_about_x(p.pitch_deg);
    // At yaw = pitch = 0 the plane faces the cameras; roll turns it in the image plane
    // (counter-clockwise on screen, y down).
    return {p.palm_mm, R * cv::Vec3d(std::cos(r), -std::sin(r), 0.0), R * cv::Vec3d(-std::sin(r), -std::cos(r), 0.0),
            R * cv::Vec3d(0.0, 0.0, -1.0)};
}

// Coverage of each pixel's 3 x 3 neighbourhood by the mask: 255 inside, about half on the
// silhouette.
void box_blur3(const cv::Mat1b& mask, cv::Mat1b& out)
{
    cv::blur(mask, out, cv::Size(3, 3), cv::Point(-1, -1), cv::BORDER_REPLICATE);
    cv::max(out, 128, out);  // a silhouette pixel is at least half hand
}

cv::Point2d nan_point()
{
    const double n = std::numeric_limits<double>::quiet_NaN();
    return {n, n};
}

}  // namespace

namespace {

// The scene's state, or an error for a moved-from scene.
template <class Pointer>
const auto& checked(const Pointer& impl)
{
    if (!impl) throw std::logic_error("gc::sim::Scene: used after being moved from");
    return *impl;
}

}  // namespace

struct Scene::Impl {
    SceneConfig config;
    std::optional<Looks> looks;  // the wide variety's draws; none without variety
    cv::Matx33d K;
    HeadGeometry geometry;
    double distance_mm = 0.0;  // of the hand at rest
    cv::Vec3f skin;
    HandModel hand;  // pointing
    // The same hand open and as a fist, built when first shown from the random state the
    // pointing hand was built from (same size and skin).
    Rng same_hand;
    bool mirrored = false;
    mutable HandModel open_hand, fist_hand;
    mutable std::once_flag open_built, fist_built;
    Wall wall;
    std::unique_ptr<MotionScript> script;
    std::vector<Billboard> people;  // farthest first
    cv::Vec3f sleeve, upper_sleeve;
    std::vector<double> folds;
    cv::Vec3d light = kLight;  // towards the key light
    double ambient = 0.35, diffuse = 0.65;
    SensorNoise noise;
    cv::Mat vignetting;  // wide: CV_16UC3 gains
    double light_phase[2] = {0.0, 0.0};
    // The wall as each eye last saw it: a head at rest sees the same wall every frame, and
    // its warp is most of a frame's rendering.
    struct WallView {
        cv::Matx33d H;
        cv::Mat image;
    };
    mutable std::mutex wall_views_mutex;
    mutable std::array<WallView, 2> wall_views;

    explicit Impl(const SceneConfig& c);
    void draw_wall(const cv::Matx33d& H, Eye eye, cv::Mat& bgr) const;
    void pick_hand(Rng& hand_rng);
    void place_face_pass(double half_x, double half_y);
    void place_people(double half_x, double half_y);
    void draw_arm(cv::Mat& bgr, const EyeCamera& cam, const HandPose& pose, const HandFrame& f) const;
    const HandModel& model(Gesture g) const;
    void draw_hand(cv::Mat& bgr, const EyeCamera& cam, const HandModel& model, const HandFrame& f, cv::Point2d smear,
                   EyeTruth* truth) const;
    cv::Point2d hand_smear(const EyeCamera& cam, int frame) const;
    HandTruth hand_truth(const HandPose& pose) const;
    void apply_lighting(cv::Mat& bgr, int frame, Eye eye) const;
    void apply_noise(cv::Mat& bgr, int frame, Eye eye) const;
    void apply_camera(cv::Mat& bgr, int frame, Eye eye) const;
    void render(const HandPose& pose, cv::Point2d smear, int frame, Eye eye, const HeadPose& head, cv::Mat& bgr,
                EyeTruth* truth) const;
};

Scene::Impl::Impl(const SceneConfig& c) : config(c)
{
    validate(c);
    K = rig_intrinsics(c);
    geometry = rig_geometry(c);
    const double half_x = 0.5 * (c.width - 1) / K(0, 0), half_y = 0.5 * (c.height - 1) / K(1, 1);

    Rng hand_rng(mix_seed(c.seed, kHandStream));
    pick_hand(hand_rng);
    for (int i = 0; i < 3; ++i) folds.push_back(uniform(hand_rng, 0.15, 0.85));
    if (looks && looks->bare_forearm) folds.clear();

    // The rest view of both eyes on the wall.
    const double D = kWallDistanceMm;
    const cv::Rect2d view(-0.5 * c.baseline_mm - D * half_x, -D * half_y, c.baseline_mm + 2.0 * D * half_x,
                          2.0 * D * half_y);
    const double texel = std::clamp(D / K(0, 0), 2.0, 12.0);
    Rng room_rng(mix_seed(c.seed, kRoomStream));
    wall = build_wall(c.preset, skin, view, D, texel, room_rng);

    Rng motion_rng(mix_seed(c.seed, kMotionStream));
    SceneConfig moved = c;
    moved.hand_distance_mm = distance_mm;
    script = std::make_unique<MotionScript>(moved, half_x, half_y, hand.finger_length_mm, motion_rng);
    light_phase[0] = uniform(motion_rng, 0, 2 * kPi);
    light_phase[1] = uniform(motion_rng, 0, 2 * kPi);

    if (c.preset == Preset::FacePass) place_face_pass(half_x, half_y);
    if (c.preset == Preset::Varied) place_people(half_x, half_y);

    const double sigma = looks ? looks->camera.noise_sigma : c.noise_sigma;
    if (sigma > 0.0) {
        noise = SensorNoise({c.width, c.height}, sigma, mix_seed(c.seed, kNoiseStream));
    }
    if (looks) vignetting = vignetting_gains({c.width, c.height}, looks->camera.vignetting);
}

// The hand's skin, shape and sleeve: one shape and the presets' tones without variety, all
// drawn from the seed with it.
void Scene::Impl::pick_hand(Rng& hand_rng)
{
    distance_mm = config.hand_distance_mm;
    if (config.variety != Variety::Wide && config.preset != Preset::Varied) {
        skin = pick_skin_tone(hand_rng);
        mirrored = uniform(hand_rng, 0, 1) < 0.5;
        same_hand = hand_rng;
        hand = build_hand_model(skin, mirrored, hand_rng);
        sleeve = non_skin_colour(hand_rng, 0.15, 0.6, 0.6);
        upper_sleeve = sleeve * 0.9f;
        return;
    }
    Rng looks_rng(mix_seed(config.seed, kLooksStream));
    looks = draw_looks(config.noise_sigma, looks_rng);
    skin = looks->skin.palm;
    mirrored = uniform(looks_rng, 0, 1) < 0.5;
    same_hand = hand_rng;
    hand = build_hand_model(skin, mirrored, hand_rng, looks->shape, &looks->skin);
    sleeve = looks->forearm;
    upper_sleeve = looks->upper_arm;
    light = looks->light;
    ambient = looks->ambient;
    diffuse = 1.0 - looks->ambient;
    distance_mm = std::clamp(config.hand_distance_mm * looks->distance_factor, 300.0, 2500.0);
}

const HandModel& Scene::Impl::model(Gesture g) const
{
    if (g == Gesture::Pointing) return hand;
    HandModel& other = g == Gesture::Open ? open_hand : fist_hand;
    std::call_once(g == Gesture::Open ? open_built : fist_built, [&] {
        Rng rng = same_hand;
        other = looks ? build_hand_model(skin, mirrored, rng, looks->shape, &looks->skin, g)
                      : build_hand_model(skin, mirrored, rng, {}, nullptr, g);
    });
    return other;
}

// face-pass: a person sits behind the hand's path, and the hand starts (waves, is acquired)
// beside the face, not on it: the face is a hand's reach plus the face's own half height
// (in the hand's plane) away from where the palm waves, to one side towards the image
// centre, and the hand makes a seeded pass across it 2.2-3.2 s after the wave (the
// crossing, whatever the motion does meanwhile; after the return for leave-return).
void Scene::Impl::place_face_pass(double half_x, double half_y)
{
    const SceneConfig& c = config;
    Rng person_rng(mix_seed(c.seed, kPersonStream));
    Rng pass_rng(mix_seed(c.seed, kPersonStream) ^ 0x9A55ULL);
    const double depth = distance_mm + 600.0;
    // Wide: the person's size and skin vary (half the time the hand's own tone).
    double scale = 1.0;
    cv::Vec3f tone = skin;
    if (looks) {
        Rng size_rng(mix_seed(c.seed, kPersonStream) ^ 0x5CA1EULL);
        scale = uniform(size_rng, 0.85, 1.2);
        if (uniform(size_rng, 0, 1) < 0.5) tone = pick_wide_skin(size_rng).palm;
    }
    cv::Vec2d wave(0.0, 0.0);
    int samples = 0;
    for (double t = 0.0; t <= MotionScript::kWaveSeconds; t += 0.05, ++samples)
        wave += cv::Vec2d(script->at(t).palm_mm[0], script->at(t).palm_mm[1]) * (1.0 / script->at(t).palm_mm[2]);
    wave *= 1.0 / samples;
    const double reach = (hand.finger_length_mm + 15.0) / distance_mm + 110.0 * scale / depth;
    const double angle = uniform(pass_rng, -0.45, 0.45);  // radians off the horizontal
    const double side = wave[0] > 0.0 ? -1.0 : 1.0;       // towards the image centre
    const cv::Vec2d target = wave + reach * cv::Vec2d(side * std::cos(angle), std::sin(angle));
    const double after = c.motion == Motion::LeaveReturn ? 11.0 : 0.0;  // back in view
    const double start = MotionScript::kWaveSeconds + after + uniform(person_rng, 0.2, 1.2);
    script->set_pass(start, 4.0, target);
    people.push_back(build_person(cv::Vec3d(target[0] * depth, target[1] * depth, depth), tone, person_rng, scale,
                                  looks.has_value()));
    if (looks && uniform(pass_rng, 0, 1) < 0.3) {  // someone else further back
        const double far = depth + uniform(pass_rng, 300.0, 900.0);
        const cv::Vec2d at(uniform(pass_rng, -0.8, 0.8) * half_x, uniform(pass_rng, -0.5, 0.2) * half_y);
        people.insert(people.begin(),
                      build_person(cv::Vec3d(at[0] * far, at[1] * far, far), pick_wide_skin(pass_rng).palm, pass_rng,
                                   uniform(pass_rng, 0.85, 1.2), true));
    }
}

// varied: none, one or two people anywhere in the view between the hand and the wall.
void Scene::Impl::place_people(double half_x, double half_y)
{
    Rng rng(mix_seed(config.seed, kPersonStream));
    const double u = uniform(rng, 0, 1);
    const int count = u < 0.25 ? 0 : (u < 0.7 ? 1 : 2);
    std::vector<std::pair<double, Billboard>> placed;
    for (int i = 0; i < count; ++i) {
        const double depth = std::min(kWallDistanceMm - 300.0, distance_mm + uniform(rng, 450.0, 1700.0));
        const cv::Vec2d at(uniform(rng, -0.85, 0.85) * half_x, uniform(rng, -0.5, 0.3) * half_y);
        const cv::Vec3f tone = uniform(rng, 0, 1) < 0.4 ? skin : pick_wide_skin(rng).palm;
        placed.emplace_back(depth, build_person(cv::Vec3d(at[0] * depth, at[1] * depth, depth), tone, rng,
                                                uniform(rng, 0.85, 1.2), true));
    }
    std::sort(placed.begin(), placed.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
    for (auto& [depth, person] : placed) people.push_back(std::move(person));
}

void Scene::Impl::draw_arm(cv::Mat& bgr, const EyeCamera& cam, const HandPose& pose, const HandFrame& f) const
{
    const cv::Vec3d back = hand.palm_axis.x * f.u + hand.palm_axis.y * f.v;  // towards the elbow
    const cv::Vec3d elbow = f.origin + pose.forearm_mm * back;
    // The upper arm runs from the elbow down and back to the shoulder of a person standing
    // behind the hand.
    const cv::Vec3d shoulder = elbow + 320.0 * cv::normalize(0.35 * back + cv::Vec3d(0.0, 0.75, 0.6));
    draw_tube(bgr, cam, {elbow, shoulder, 50.0, 58.0}, upper_sleeve, {0.5});
    draw_tube(bgr, cam, {f.origin + 0.8 * hand.wrist_mm * back, elbow, 36.0, 47.0}, sleeve, folds);
}

void Scene::Impl::draw_hand(cv::Mat& bgr, const EyeCamera& cam, const HandModel& model, const HandFrame& f,
                            cv::Point2d smear, EyeTruth* truth) const
{
    thread_local std::vector<std::vector<cv::Point>> parts;
    thread_local cv::Mat1b roi_mask;
    thread_local cv::Mat warped;
    thread_local cv::Mat1b alpha;
    const cv::Rect frame(0, 0, bgr.cols, bgr.rows);

    parts.resize(model.parts.size());
    bool in_front = true;
    cv::Rect box;
    for (std::size_t i = 0; i < model.parts.size() && in_front; ++i) {
        in_front = project_polygon(cam, f.origin, f.u, f.v, model.parts[i], parts[i], {}, kMinHandDepthMm);
        for (const cv::Point& p : parts[i]) {
            const cv::Rect px(p.x >> kDrawShift, p.y >> kDrawShift, 2, 2);
            box = box.empty() ? px : (box | px);
        }
    }
    // A moving hand smears beyond its outline while the shutter is open.
    const int reach = smear == cv::Point2d() ? 0 : int(std::ceil(0.5 * std::hypot(smear.x, smear.y))) + 1;
    const cv::Rect roi =
        in_front ? ((box + cv::Size(2 * reach, 2 * reach) - cv::Point(reach, reach)) & frame) : cv::Rect();
    if (truth) {
        truth->mask.create(bgr.size());
        truth->mask.setTo(0);
        truth->bbox = cv::Rect();
    }
    if (roi.empty()) return;

    roi_mask.create(roi.size());
    roi_mask.setTo(0);
    const cv::Point shift(roi.x << kDrawShift, roi.y << kDrawShift);
    for (auto& part : parts) {
        for (cv::Point& p : part) p -= shift;
        cv::fillConvexPoly(roi_mask, part, cv::Scalar(255), cv::LINE_8, kDrawShift);
    }

    // The skin texture through the homography of the hand's plane, lit by its orientation.
    const cv::Matx33d to_roi(1, 0, -roi.x, 0, 1, -roi.y, 0, 0, 1);
    const cv::Matx33d H = to_roi * cam.plane_homography(f.origin, f.u, f.v) * model.texel_to_model();
    cv::warpPerspective(model.texture, warped, H, roi.size(), cv::INTER_LINEAR, cv::BORDER_REPLICATE);
    const double rest = ambient + diffuse * std::abs(light[2]);
    const double brightness = looks ? looks->hand_light : 1.0;
    const float lit = float((ambient + diffuse * std::abs(f.n.dot(light))) / rest * brightness);

    // Composite with the lens's soft edge kept inside the mask: the silhouette pixels mix
    // with the background, but no skin leaks outside the truth (unless it is smeared).
    box_blur3(roi_mask, alpha);
    cv::Mat target = bgr(roi);
    if (reach > 0) {
        alpha.setTo(0, roi_mask == 0);
        composite_smeared(target, warped, alpha, lit, motion_kernel(smear));
    }
    for (int y = 0; y < roi.height && reach == 0; ++y) {
        const std::uint8_t* m = roi_mask.ptr<std::uint8_t>(y);
        const std::uint8_t* a = alpha.ptr<std::uint8_t>(y);
        const cv::Vec3b* src = warped.ptr<cv::Vec3b>(y);
        cv::Vec3b* dst = target.ptr<cv::Vec3b>(y);
        for (int x = 0; x < roi.width; ++x) {
            if (!m[x]) continue;
            const float k = lit * float(a[x]) / 255.0f, keep = 1.0f - float(a[x]) / 255.0f;
            for (int c = 0; c < 3; ++c) dst[x][c] = cv::saturate_cast<std::uint8_t>(k * src[x][c] + keep * dst[x][c]);
        }
    }

    if (truth) {
        roi_mask.copyTo(truth->mask(roi));
        const cv::Rect b = cv::boundingRect(roi_mask);
        truth->bbox = b.empty() ? cv::Rect() : b + roi.tl();
    }
}

void Scene::Impl::apply_lighting(cv::Mat& bgr, int frame, Eye eye) const
{
    if (!config.lighting_change && !looks) return;
    const double t = frame / config.fps;
    double gain[3] = {1.0, 1.0, 1.0};
    if (config.lighting_change) {
        const double brightness = 1.0 + 0.2 * std::sin(2.0 * kPi * t / 9.0 + light_phase[0]);
        const double warmth = 0.07 * std::sin(2.0 * kPi * t / 13.0 + light_phase[1]);
        gain[0] = brightness * (1.0 - warmth);
        gain[1] = brightness;
        gain[2] = brightness * (1.0 + warmth);
    }
    if (looks) {  // the exposure and the white balance of the camera
        const double exposure = looks->camera.gain(t, eye);
        for (int c = 0; c < 3; ++c) gain[c] *= exposure * looks->camera.white_balance[c];
    }
    // A per-channel table: one lookup per sample instead of floating-point arithmetic.
    thread_local cv::Mat lut(1, 256, CV_8UC3);
    for (int v = 0; v < 256; ++v)
        for (int c = 0; c < 3; ++c) lut.at<cv::Vec3b>(0, v)[c] = cv::saturate_cast<std::uint8_t>(v * gain[c]);
    cv::LUT(bgr, lut, bgr);
}

// Wide: the lens darkens the corners and may be out of focus; after the sensor's gain and
// noise, some cameras compress.
void Scene::Impl::apply_camera(cv::Mat& bgr, int frame, Eye eye) const
{
    if (!looks) {
        apply_lighting(bgr, frame, eye);
        apply_noise(bgr, frame, eye);
        return;
    }
    apply_vignetting(bgr, vignetting);
    if (looks->camera.defocus_sigma_px > 0.0)
        cv::GaussianBlur(bgr, bgr, cv::Size(0, 0), looks->camera.defocus_sigma_px);
    apply_lighting(bgr, frame, eye);
    apply_noise(bgr, frame, eye);
    if (looks->camera.jpeg_quality > 0) jpeg_round_trip(bgr, looks->camera.jpeg_quality);
}

// Wide: how far the hand's projection moves while the shutter is open (mean of the palm's
// and the fingertip's motion), centred on the frame's time.
cv::Point2d Scene::Impl::hand_smear(const EyeCamera& cam, int frame) const
{
    if (!looks) return {};
    const double t = frame / config.fps, half = 0.5 * looks->camera.shutter_s;
    auto points = [&](double when) {
        const HandPose p = script->at(std::max(0.0, when));
        const HandFrame f = hand_frame(p);
        return std::pair{cam.to_camera(f.origin), cam.to_camera(f.origin + hand.finger_length_mm * f.u)};
    };
    const auto [palm0, tip0] = points(t - half);
    const auto [palm1, tip1] = points(t + half);
    if (palm0[2] <= kMinHandDepthMm || tip0[2] <= kMinHandDepthMm || palm1[2] <= kMinHandDepthMm ||
        tip1[2] <= kMinHandDepthMm)
        return {};
    const cv::Point2d d = 0.5 * (cam.project_camera(palm1) - cam.project_camera(palm0) + cam.project_camera(tip1) -
                                 cam.project_camera(tip0));
    return std::hypot(d.x, d.y) < 0.75 ? cv::Point2d() : d;
}

void Scene::Impl::apply_noise(cv::Mat& bgr, int frame, Eye eye) const
{
    // The pool's window is chosen by (seed, frame, eye).
    noise.apply(bgr,
                mix_seed(config.seed ^ (std::uint64_t(frame) << 1 | std::uint64_t(eye == Eye::Right)), kFrameStream));
}

Scene::Scene(const SceneConfig& config) : impl_(std::make_unique<Impl>(config)) {}
Scene::~Scene() = default;
Scene::Scene(Scene&&) noexcept = default;
Scene& Scene::operator=(Scene&&) noexcept = default;

const SceneConfig& Scene::config() const { return checked(impl_).config; }

HandPose Scene::hand_pose(int frame) const
{
    const Impl& s = checked(impl_);
    require_valid(frame >= 0, "Scene::hand_pose: negative frame index " + std::to_string(frame));
    const double t = frame / s.config.fps;
    HandPose pose = s.script->at(t);
    pose.gesture = gesture_at(s.config.gesture, s.config.gesture_cycle_s, t);
    return pose;
}

HandTruth Scene::hand_truth(const HandPose& pose) const { return checked(impl_).hand_truth(pose); }

HandTruth Scene::Impl::hand_truth(const HandPose& pose) const
{
    validate(pose);
    const HandFrame f = hand_frame(pose);
    const cv::Vec3d back = hand.palm_axis.x * f.u + hand.palm_axis.y * f.v;
    return {f.origin + model(pose.gesture).finger_length_mm * f.u, f.origin, f.origin + pose.forearm_mm * back, f.u,
            pose.gesture};
}

void Scene::render(int frame, Eye eye, const HeadPose& head, cv::Mat& bgr, EyeTruth* truth) const
{
    const HandPose pose = hand_pose(frame);
    validate(head);
    const Impl& s = checked(impl_);
    require_valid(eye == Eye::Left || eye == Eye::Right, "Scene::render: unknown eye");
    const cv::Point2d smear = s.hand_smear(eye_camera(s.K, s.geometry, head, eye), frame);
    s.render(pose, smear, frame, eye, head, bgr, truth);
}

void Scene::render_pose(const HandPose& pose, int frame, Eye eye, const HeadPose& head, cv::Mat& bgr,
                        EyeTruth* truth) const
{
    checked(impl_).render(pose, {}, frame, eye, head, bgr, truth);
}

void Scene::Impl::draw_wall(const cv::Matx33d& H, Eye eye, cv::Mat& bgr) const
{
    const std::lock_guard<std::mutex> lock(wall_views_mutex);
    WallView& seen = wall_views[eye == Eye::Left ? 0 : 1];
    if (seen.image.size() != bgr.size() || seen.H != H) {
        cv::warpPerspective(wall.image, seen.image, H, bgr.size(), cv::INTER_LINEAR, cv::BORDER_REFLECT_101);
        seen.H = H;
    }
    seen.image.copyTo(bgr);
}

void Scene::Impl::render(const HandPose& pose, cv::Point2d smear, int frame, Eye eye, const HeadPose& head,
                         cv::Mat& bgr, EyeTruth* truth) const
{
    require_valid(frame >= 0, "Scene::render: negative frame index " + std::to_string(frame));
    require_valid(eye == Eye::Left || eye == Eye::Right, "Scene::render: unknown eye");
    validate(head);
    validate(pose);
    const EyeCamera cam = eye_camera(K, geometry, head, eye);
    const cv::Size size(config.width, config.height);

    // Every corner ray must meet the wall in front of the head.
    for (const cv::Point2d corner : {cv::Point2d(0, 0), cv::Point2d(size.width - 1, 0), cv::Point2d(0, size.height - 1),
                                     cv::Point2d(size.width - 1, size.height - 1)}) {
        const cv::Vec3d ray = cam.ray_in_head(corner.x, corner.y);
        require_valid(ray[2] > 0.1 * cv::norm(ray), "Scene::render: head pose (pan " + number_text(head.pan_deg) +
                                                        ", tilt " + number_text(head.tilt_deg) +
                                                        ") looks past the simulated room's wall");
    }

    bgr.create(size, CV_8UC3);
    draw_wall(cam.plane_homography({wall.origin_mm.x, wall.origin_mm.y, wall.distance_mm}, {wall.texel_mm, 0, 0},
                                   {0, wall.texel_mm, 0}),
              eye, bgr);
    if (truth && !people.empty()) {
        truth->face.create(size);
        truth->face.setTo(0);
    } else if (truth) {
        truth->face.release();
    }
    for (const Billboard& person : people) draw_billboard(bgr, cam, person, truth ? &truth->face : nullptr);

    const HandFrame f = hand_frame(pose);
    draw_arm(bgr, cam, pose, f);
    draw_hand(bgr, cam, model(pose.gesture), f, smear, truth);
    apply_camera(bgr, frame, eye);

    if (truth) {
        const HandTruth t3 = hand_truth(pose);
        truth->gesture = t3.gesture;
        const cv::Vec3d palm_c = cam.to_camera(t3.palm_mm), tip_c = cam.to_camera(t3.fingertip_mm);
        truth->palm_px = palm_c[2] > 0 ? cam.project_camera(palm_c) : nan_point();
        truth->fingertip_px = tip_c[2] > 0 ? cam.project_camera(tip_c) : nan_point();
        const cv::Point2d d = truth->fingertip_px - truth->palm_px;
        truth->pointing_deg = std::atan2(-d.y, d.x) * 180.0 / kPi;
        const cv::Rect2d frame_box(0, 0, size.width, size.height);
        truth->visible = frame_box.contains(truth->palm_px) && frame_box.contains(truth->fingertip_px) &&
                         cv::countNonZero(truth->mask) >= kMinVisiblePixels;
    }
}

StereoCalibration Scene::calibration() const { return rig_calibration(checked(impl_).config); }

double Scene::measured_skin_fraction(int frame) const
{
    cv::Mat bgr;
    EyeTruth truth;
    render(frame, Eye::Left, HeadPose{}, bgr, &truth);
    const int hand_pixels = cv::countNonZero(truth.mask);
    if (hand_pixels < kMinVisiblePixels)
        throw std::runtime_error("Scene::measured_skin_fraction: the hand is not in view at frame " +
                                 std::to_string(frame));
    const SkinModel model = SkinModel::fit(bgr, truth.mask);
    cv::Mat1b skin = model.segment(bgr);
    skin.setTo(0, truth.mask);
    const double background = double(truth.mask.total()) - hand_pixels;
    return cv::countNonZero(skin) / background;
}

}  // namespace gc::sim
