// The frame pipeline shared by the handtracker element and gesturecam-track: both eyes'
// trackers, the 3D step, the overall state, and the JSON line of one frame.
#include "tracker/pointing_tracker.hpp"

#include "common/json_text.hpp"
#include "tracker/analysis_scale.hpp"

#include <initializer_list>
#include <numbers>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>

namespace gc {
namespace {

std::string size_text(const cv::Size& s) { return std::to_string(s.width) + "x" + std::to_string(s.height); }

void check_frame(const cv::Mat& frame, std::string_view what)
{
    if (frame.empty()) throw std::invalid_argument(std::string(what) + " frame is empty");
    if (frame.type() != CV_8UC3)
        throw std::invalid_argument(std::string(what) + " frame must be CV_8UC3 (BGR), got " +
                                    cv::typeToString(frame.type()));
}

TrackState overall_state(std::initializer_list<TrackState> eyes)
{
    bool all_tracking = true;
    for (TrackState s : eyes) {
        if (s == TrackState::Lost) return TrackState::Lost;
        all_tracking = all_tracking && s == TrackState::Tracking;
    }
    return all_tracking ? TrackState::Tracking : TrackState::Acquiring;
}

// Whether a stereo frame may give a ray: both eyes track, at least one sees a pointing
// hand, and neither sees an open hand or a fist (a gesture seen by one eye only, the other
// unsure, still counts; a contradiction does not).
bool points_in_both(const EyeEstimate& l, const EyeEstimate& r)
{
    const auto not_pointing = [](Gesture g) { return g == Gesture::Open || g == Gesture::Fist; };
    return l.valid() && r.valid() && (l.pointing() || r.pointing()) && !not_pointing(l.gesture) &&
           !not_pointing(r.gesture);
}

}  // namespace

struct PointingTracker::Impl {
    enum class Mode { Unset, Stereo, Mono };

    TrackerParams params;
    std::optional<StereoCalibration> calibration;
    StereoHandTracker stereo;
    std::optional<HandTracker> mono;             // created on the first mono frame
    std::optional<PointingEstimator> estimator;  // created on the first stereo frame
    Mode mode = Mode::Unset;
    AnalysisScale scale;  // the frames' size and the one they are tracked at
    cv::Mat analysed[2];  // the views at the analysed size, when smaller
    DownscaleBuffers downscaling[2];
    std::vector<Particle> frame_particles[2];  // the eyes' particles in the frame's pixels
    FrameResult result;
    std::int64_t next_frame = 0;

    Impl(const TrackerParams& p, std::optional<StereoCalibration> c) : params(p), calibration(std::move(c)), stereo(p)
    {
    }

    // The mode and frame size are fixed by the first frame after construction or reset.
    void check_continuity(Mode m, const cv::Size& size) const
    {
        const auto name = [](Mode x) { return x == Mode::Mono ? "mono" : "stereo"; };
        if (mode != Mode::Unset && mode != m)
            throw std::logic_error(std::string("PointingTracker: a ") + name(m) + " frame after " + name(mode) +
                                   " frames; call reset() to change mode");
        if (mode == m && size != scale.frame)
            throw std::invalid_argument("frame size changed from " + size_text(scale.frame) + " to " + size_text(size) +
                                        " without reset()");
    }

    void begin_frame(Mode m, const cv::Size& size)
    {
        mode = m;
        scale = analysis_scale(size, params.tracking_width);
    }

    // The calibration is the frames' (checked at their size), scaled to the analysed size.
    PointingEstimator& estimator_for(const cv::Size& size)
    {
        if (!estimator) {
            if (calibration && calibration->image_size != size)
                throw std::invalid_argument("frames are " + size_text(size) + " but the calibration '" +
                                            calibration->source + "' is for " + size_text(calibration->image_size));
            const StereoCalibration frames = calibration ? *calibration : default_calibration(size);
            const AnalysisScale a = analysis_scale(size, params.tracking_width);
            estimator.emplace(a.active() ? scaled_calibration(frames, a) : frames);
        }
        return *estimator;
    }

    // The view the eye's tracker sees: the frame itself, or its copy at the analysed size.
    const cv::Mat& analysed_view(const cv::Mat& frame, int eye)
    {
        if (!scale.active()) return frame;
        downscale(frame, scale.analysed, downscaling[eye], analysed[eye]);
        return analysed[eye];
    }

    // The estimates and particles back in the frame's pixels.
    void results_to_frame(std::initializer_list<std::pair<EyeEstimate*, std::span<const Particle>>> eyes)
    {
        if (!scale.active()) return;
        int i = 0;
        for (const auto& [estimate, particles] : eyes) {
            to_frame(*estimate, scale);
            to_frame(particles, scale, frame_particles[i++]);
        }
    }

    void stamp(std::int64_t pts_ns)
    {
        result.frame = next_frame++;
        result.pts_ns = pts_ns < 0 ? -1 : pts_ns;
    }
};

PointingTracker::PointingTracker(const TrackerParams& params, std::optional<StereoCalibration> calibration)
    : impl_(std::make_unique<Impl>(params, std::move(calibration)))
{
}

PointingTracker::~PointingTracker() = default;

const FrameResult& PointingTracker::process_stereo(const cv::Mat& left_bgr, const cv::Mat& right_bgr,
                                                   std::int64_t pts_ns, const std::optional<HeadPose>& head,
                                                   const ImageMotion& left_motion, const ImageMotion& right_motion)
{
    check_frame(left_bgr, "left");
    check_frame(right_bgr, "right");
    if (left_bgr.size() != right_bgr.size())
        throw std::invalid_argument("left frame is " + size_text(left_bgr.size()) + " but right frame is " +
                                    size_text(right_bgr.size()));
    Impl& d = *impl_;
    // Everything is validated before any state changes: a rejected frame leaves no trace.
    d.check_continuity(Impl::Mode::Stereo, left_bgr.size());
    PointingEstimator& estimator = d.estimator_for(left_bgr.size());
    d.begin_frame(Impl::Mode::Stereo, left_bgr.size());

    const cv::Mat& left = d.analysed_view(left_bgr, 0);
    const cv::Mat& right = d.analysed_view(right_bgr, 1);
    StereoEstimate eyes =
        d.stereo.process(left, right, to_analysed(left_motion, d.scale), to_analysed(right_motion, d.scale));
    FrameResult& r = d.result;
    d.stamp(pts_ns);
    r.stereo = true;
    r.left = std::move(eyes.left);
    r.right = std::move(eyes.right);
    r.state = overall_state({r.left.state, r.right.state});
    r.head = head;
    const auto back_to_frame = [&] {
        d.results_to_frame(
            {{&r.left, d.stereo.eye(Eye::Left).particles()}, {&r.right, d.stereo.eye(Eye::Right).particles()}});
    };
    try {
        r.pointing = points_in_both(r.left, r.right)
                         ? estimator.estimate(left, right, r.left, r.right, head.value_or(HeadPose{}))
                         : Pointing3D{};
    } catch (...) {
        back_to_frame();  // whatever the caller does next, last() speaks in the frame's pixels
        throw;
    }
    back_to_frame();
    return r;
}

const FrameResult& PointingTracker::process_mono(const cv::Mat& bgr, std::int64_t pts_ns, const ImageMotion& motion)
{
    check_frame(bgr, "mono");
    Impl& d = *impl_;
    d.check_continuity(Impl::Mode::Mono, bgr.size());
    d.begin_frame(Impl::Mode::Mono, bgr.size());
    if (!d.mono) d.mono.emplace(d.params);
    FrameResult& r = d.result;
    r.left = d.mono->process(d.analysed_view(bgr, 0), to_analysed(motion, d.scale));
    d.results_to_frame({{&r.left, d.mono->particles()}});
    d.stamp(pts_ns);
    r.stereo = false;
    r.right = EyeEstimate{};
    r.state = overall_state({r.left.state});
    r.head.reset();
    r.pointing = Pointing3D{};
    return r;
}

void PointingTracker::reset()
{
    Impl& d = *impl_;
    d.stereo.reset();
    d.mono.reset();  // destroyed; re-created by the next mono frame
    d.mode = Impl::Mode::Unset;
    d.scale = {};
    d.next_frame = 0;
    d.result = FrameResult{};
    // A new stream may have another frame size: the estimator is re-created and the size
    // re-validated against the calibration on its first stereo frame.
    d.estimator.reset();
}

const FrameResult& PointingTracker::last() const { return impl_->result; }

std::span<const Particle> PointingTracker::particles(Eye eye) const
{
    const Impl& d = *impl_;
    if (d.scale.active() && d.mode != Impl::Mode::Unset) {
        if (d.mode == Impl::Mode::Mono && eye == Eye::Right) return {};
        return d.frame_particles[static_cast<int>(eye)];
    }
    switch (d.mode) {
    case Impl::Mode::Mono:
        return eye == Eye::Left && d.mono ? d.mono->particles() : std::span<const Particle>{};
    case Impl::Mode::Stereo:
        return d.stereo.eye(eye).particles();
    case Impl::Mode::Unset:
        break;
    }
    return {};
}

// ---------------------------------------------------------------------------------------
// JSON. Numbers are written by json::append_number (std::to_chars: locale-independent, the
// shortest exact digits of the rounded value); non-finite values become null so every line
// stays valid JSON.
namespace {

class JsonLine {
public:
    explicit JsonLine(std::string& out) : out_(out) {}

    void key(std::string_view k)
    {
        separator();
        out_ += '"';
        out_.append(k);
        out_ += "\":";
        fresh_ = true;
    }

    void begin(char bracket)
    {
        separator();
        out_ += bracket;
        fresh_ = true;
    }

    void end(char bracket)
    {
        out_ += bracket;
        fresh_ = false;
    }

    // `decimals` digits after the point at most; trailing zeros dropped.
    void number(double v, int decimals)
    {
        separator();
        json::append_number(out_, v, decimals);
    }

    void integer(std::int64_t v)
    {
        separator();
        json::append_integer(out_, v);
    }

    void string(std::string_view s)
    {
        separator();
        json::append_string(out_, s);
    }

    void null()
    {
        separator();
        out_ += "null";
    }

    void point(const cv::Point2f& p, int decimals)
    {
        begin('[');
        number(p.x, decimals);
        number(p.y, decimals);
        end(']');
    }

    void vec3(const cv::Vec3d& v, int decimals)
    {
        begin('[');
        for (int i = 0; i < 3; ++i) number(v[i], decimals);
        end(']');
    }

private:
    void separator()
    {
        if (!fresh_) out_ += ',';
        fresh_ = false;
    }

    std::string& out_;
    bool fresh_ = true;
};

constexpr int kPixelDecimals = 2;   // 0.01 px
constexpr int kDegreeDecimals = 2;  // 0.01 deg
constexpr int kMmDecimals = 1;      // 0.1 mm
constexpr int kRatioDecimals = 3;   // scale, confidence
constexpr int kUnitDecimals = 4;    // unit direction vectors

double degrees(double radians) { return radians * 180.0 / std::numbers::pi; }

// An eye with no contour has no estimate (acquiring before its first detection, or lost):
// null. Otherwise the estimate is written.
void write_eye(JsonLine& j, const EyeEstimate& e)
{
    if (e.contour.empty()) {
        j.null();
        return;
    }
    j.begin('{');
    j.key("x");
    j.number(e.mean.x, kPixelDecimals);
    j.key("y");
    j.number(e.mean.y, kPixelDecimals);
    j.key("rotation_deg");
    j.number(degrees(e.mean.rotation), kDegreeDecimals);
    j.key("scale");
    j.number(e.mean.scale, kRatioDecimals);
    j.key("confidence");
    j.number(e.confidence, kRatioDecimals);
    j.key("bbox");
    j.begin('[');
    j.integer(e.bbox.x);
    j.integer(e.bbox.y);
    j.integer(e.bbox.width);
    j.integer(e.bbox.height);
    j.end(']');
    j.key("contour");
    j.begin('[');
    for (const cv::Point2f& p : e.contour) j.point(p, kPixelDecimals);
    j.end(']');
    j.key("fingertip");
    j.point(e.fingertip, kPixelDecimals);
    j.key("pointing_deg");
    j.number(e.pointing_deg, kDegreeDecimals);
    j.key("gesture");
    j.string(to_string(e.gesture));
    if (!e.landmarks.empty()) {
        j.key("landmarks");
        j.begin('[');
        for (const cv::Point2f& p : e.landmarks) j.point(p, kPixelDecimals);
        j.end(']');
    }
    j.end('}');
}

void write_pointing(JsonLine& j, const Pointing3D& p)
{
    if (!p.valid) {
        j.null();
        return;
    }
    j.begin('{');
    j.key("fingertip_mm");
    j.vec3(p.fingertip_mm, kMmDecimals);
    j.key("palm_mm");
    j.vec3(p.palm_mm, kMmDecimals);
    j.key("direction");
    j.vec3(p.direction, kUnitDecimals);
    j.key("azimuth_deg");
    j.number(p.azimuth_deg, kDegreeDecimals);
    j.key("elevation_deg");
    j.number(p.elevation_deg, kDegreeDecimals);
    j.end('}');
}

}  // namespace

std::string to_json_line(const FrameResult& result)
{
    std::string out;
    out.reserve(256 + 24 * (result.left.contour.size() + result.right.contour.size()));
    JsonLine j(out);
    j.begin('{');
    j.key("frame");
    j.integer(result.frame);
    j.key("pts_ns");
    if (result.pts_ns >= 0)
        j.integer(result.pts_ns);
    else
        j.null();
    j.key("state");
    j.string(to_string(result.state));
    j.key("left");
    write_eye(j, result.left);
    if (result.stereo) {
        j.key("right");
        write_eye(j, result.right);
        j.key("pointing");
        write_pointing(j, result.pointing);
    }
    j.end('}');
    return out;
}

}  // namespace gc
