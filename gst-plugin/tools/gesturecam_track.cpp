// gesturecam-track: tracks the pointing hand through a recorded stereo pair (or one view) and
// writes one JSON line per frame (schema: docs/track-tool.md).
//
// Exit status: 0 success (warnings may be printed), 1 an input, calibration or output problem
// (an undecodable frame included, unless --skip-bad-frames), 2 a wrong command line.
#include "common/frame_limits.hpp"
#include "common/line_output.hpp"
#include "tools/cli_app.hpp"
#include "tools/frame_source.hpp"
#include "tracker/analysis_scale.hpp"
#include "tracker/pointing_tracker.hpp"

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <iostream>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>

namespace {

constexpr const char* kUsage = R"(usage: gesturecam-track --left INPUT [--right INPUT] [options]

Tracks the pointing hand in a recorded stereo pair and writes one JSON object per frame.
INPUT is a video file or a printf image-sequence pattern such as left/%05d.png (the
sequence starts at index 0 or 1). Without --right, one view is tracked (mono): the lines
then have no "right" and no "pointing" keys.

options:
  --left INPUT          left view (required)
  --right INPUT         right view; its frames are paired with the left's by index
  --calibration FILE    stereo calibration (OpenCV YAML/XML); default: the nominal rig
                        for the frame size
  --particles N         particles per eye, 1..100000 (default 1000)
  --tracking-width W    track frames wider than W pixels scaled down to W (aspect kept),
                        64..8192; the output stays in the input's pixels (default: track
                        at the input's size)
  --seed S              random seed; same seed and input give the same output (default 1)
  --detector D          how the hand is found: learned (the palm and landmark models,
                        default) or motion (the thesis's waving skin blob, nothing learned)
  --model-dir DIR       folder of the learned models (default: found without configuration)
  --out FILE            output file (default: standard output)
  --fps F               frame rate for pts_ns when the left input carries no timestamps
                        (image sequences); without it pts_ns is null there
  --max-frames N        stop after the first N frames of the input
  --skip-bad-frames     skip a frame that cannot be decoded (with a warning) instead of
                        stopping with an error
  --progress S          a progress line on stderr every S seconds of a run (default 2;
                        0: none)
  --version             the version
  -h, --help            this text

Frames larger than 8192 pixels a side are refused.

exit status: 0 success, 1 input, calibration or output error (an undecodable frame
included, unless --skip-bad-frames), 2 bad command line
)";

struct Options {
    std::string left;
    std::optional<std::string> right;
    std::optional<std::string> calibration;
    gc::TrackerParams params;
    std::optional<std::string> out;
    std::optional<double> fps;
    std::int64_t max_frames = std::numeric_limits<std::int64_t>::max();
    bool skip_bad_frames = false;
    double progress_s = 2.0;  // seconds between progress lines on stderr; 0: none
};

// The values as given, checked and converted once CLI11 has parsed the command line.
struct GivenText {
    std::string particles, tracking_width, seed, detector, fps, max_frames, progress;
};

// The options CLI11 reads into `o` and `t` (convert() then checks and converts them).
void add_options(CLI::App& app, Options& o, GivenText& t)
{
    app.add_option("--left", o.left)->required();
    app.add_option("--right", o.right);
    app.add_option("--calibration", o.calibration);
    app.add_option("--particles", t.particles);
    app.add_option("--tracking-width", t.tracking_width);
    app.add_option("--seed", t.seed);
    app.add_option("--detector", t.detector);
    app.add_option("--model-dir", o.params.model_dir);
    app.add_option("--out", o.out);
    app.add_option("--fps", t.fps);
    app.add_option("--max-frames", t.max_frames);
    app.add_option("--progress", t.progress);
    app.add_flag("--skip-bad-frames", o.skip_bad_frames);
}

void convert(const GivenText& t, Options& o)
{
    using gc::cli::parse_number;
    if (!t.particles.empty()) o.params.particles = parse_number<int>("--particles", t.particles, 1, 100000);
    if (!t.tracking_width.empty())
        o.params.tracking_width =
            parse_number<int>("--tracking-width", t.tracking_width, gc::kMinTrackingWidth, gc::kMaxFrameSide);
    if (!t.seed.empty()) o.params.seed = parse_number<std::uint64_t>("--seed", t.seed);
    if (!t.detector.empty()) {
        if (t.detector != "learned" && t.detector != "motion")
            throw gc::cli::UsageError("--detector must be learned or motion, not " + t.detector);
        o.params.detector = t.detector == "motion" ? gc::HandDetector::Motion : gc::HandDetector::Learned;
    }
    if (!t.fps.empty()) o.fps = parse_number<double>("--fps", t.fps, 1e-3, 1e4);
    if (!t.max_frames.empty())
        o.max_frames =
            parse_number<std::int64_t>("--max-frames", t.max_frames, 1, std::numeric_limits<std::int64_t>::max());
    if (!t.progress.empty()) o.progress_s = parse_number<double>("--progress", t.progress, 0.0, 1e6);
    if (o.right && o.right->empty()) throw gc::cli::UsageError("--right needs a non-empty value");
    if (o.out && o.out->empty()) throw gc::cli::UsageError("--out needs a non-empty value");
}

std::string size_text(const cv::Size& s) { return std::to_string(s.width) + "x" + std::to_string(s.height); }

void warn(const std::string& text) { std::cerr << "gesturecam-track: warning: " << text << '\n'; }

// The inputs read pair by pair (mono: the left alone); frames are paired by their index.
class PairReader {
public:
    explicit PairReader(const Options& o) : left_(o.left, "left"), skip_bad_frames_(o.skip_bad_frames)
    {
        if (o.right) right_.emplace(*o.right, "right");
    }

    // The next pair whose frames both decode, into `l` and `r`; false when either input has
    // ended (with a warning when the other has not, since the pair is then incomplete). An
    // undecodable frame throws InputError, or is skipped with a warning.
    bool next(cv::Mat& l, cv::Mat& r)
    {
        while (true) {
            const std::int64_t index = left_.next_index();
            const gc::tools::FrameStatus left = left_.read(l);
            if (left == gc::tools::FrameStatus::End) return left_ended(index, r);
            auto right = gc::tools::FrameStatus::Frame;
            if (right_ && (right = right_->read(r)) == gc::tools::FrameStatus::End) return right_ended(index);
            if (left == gc::tools::FrameStatus::Frame && right == gc::tools::FrameStatus::Frame) {
                if (right_ && l.size() != r.size())
                    throw gc::tools::InputError("frame " + std::to_string(index) + ": left frames are " +
                                                size_text(l.size()) + " but right frames are " + size_text(r.size()));
                index_ = index;
                ++pairs_;
                return true;
            }
            undecodable(left == gc::tools::FrameStatus::Frame ? *right_ : left_, index);
        }
    }

    bool stereo() const { return right_.has_value(); }
    std::optional<std::int64_t> frame_count() const { return left_.frame_count(); }
    std::int64_t index() const { return index_; }  // of the pair given last
    std::int64_t next_index() const { return left_.next_index(); }
    std::int64_t skipped() const { return skipped_; }
    std::int64_t timestamp_ns() const { return left_.timestamp_ns(); }

private:
    static constexpr std::int64_t kListedBadFrames = 10;

    bool left_ended(std::int64_t index, cv::Mat& r)
    {
        if (pairs_ == 0) throw gc::tools::InputError(left_.describe() + ": no frame could be read");
        if (right_ && right_->read(r) != gc::tools::FrameStatus::End)
            warn("left input ended after " + std::to_string(index) +
                 " frames but the right input has more; stopped at the shorter");
        return false;
    }

    bool right_ended(std::int64_t index)
    {
        if (pairs_ == 0) throw gc::tools::InputError(right_->describe() + ": no frame could be read");
        warn("right input ended at frame " + std::to_string(index) + " before the left; stopped at the shorter");
        return false;
    }

    void undecodable(const gc::tools::FrameSource& source, std::int64_t index)
    {
        const std::string what = source.describe() + ": " + source.frame_text(index) + " cannot be decoded";
        if (!skip_bad_frames_) throw gc::tools::InputError(what + " (--skip-bad-frames skips such frames)");
        ++skipped_;
        if (skipped_ <= kListedBadFrames)
            warn(what + "; skipped");
        else if (skipped_ == kListedBadFrames + 1)
            warn("further undecodable frames are skipped without a warning; the summary counts them");
    }

    gc::tools::FrameSource left_;
    std::optional<gc::tools::FrameSource> right_;
    bool skip_bad_frames_ = false;
    std::int64_t index_ = -1;
    std::int64_t pairs_ = 0;
    std::int64_t skipped_ = 0;
};

// A line on stderr every `interval_s` seconds of a run (none for a shorter run): frames done,
// of how many, and how fast.
class ProgressLine {
public:
    ProgressLine(double interval_s, std::optional<std::int64_t> total)
        : interval_(std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(interval_s))),
          total_(total), start_(Clock::now()), next_(start_ + interval_)
    {
    }

    void frame_done(std::int64_t frames)
    {
        const Clock::time_point now = Clock::now();
        if (interval_.count() <= 0.0 || now < next_) return;
        next_ = now + interval_;
        const double elapsed = std::chrono::duration<double>(now - start_).count();
        char text[160];
        std::snprintf(text, sizeof text, "gesturecam-track: %lld frames%s, %.1f frames/s\n",
                      static_cast<long long>(frames), total_ ? (" of " + std::to_string(*total_)).c_str() : "",
                      elapsed > 0.0 ? static_cast<double>(frames) / elapsed : 0.0);
        std::cerr << text << std::flush;
    }

private:
    using Clock = std::chrono::steady_clock;
    Clock::duration interval_;
    std::optional<std::int64_t> total_;
    Clock::time_point start_;
    Clock::time_point next_;
};

// The JSON line of `result`, numbered with the frame's index in the input (which differs from
// the tracker's count once frames were skipped).
std::string json_line(const gc::FrameResult& result, std::int64_t index)
{
    std::string line;
    if (result.frame == index) {
        line = gc::to_json_line(result);
    } else {
        gc::FrameResult renumbered = result;
        renumbered.frame = index;
        line = gc::to_json_line(renumbered);
    }
    line += '\n';
    return line;
}

// Reads and checks the first pair before opening the output, so that a bad input leaves no
// empty output file behind; then tracks pair by pair, one whole line written per frame.
void run(const Options& o)
{
    PairReader input(o);
    cv::Mat left_frame;
    cv::Mat right_frame;
    input.next(left_frame, right_frame);

    std::optional<gc::StereoCalibration> calibration;
    if (o.calibration) {
        if (input.stereo()) {
            calibration = gc::load_calibration(*o.calibration);
            gc::validate_calibration_size(*calibration, left_frame.size());
        } else {
            warn("--calibration is ignored in mono mode");
        }
    }
    gc::PointingTracker tracker(o.params, calibration);
    gc::LineOutput out = o.out ? gc::LineOutput::create(*o.out) : gc::LineOutput::standard_output();

    std::int64_t frames = 0;
    std::int64_t tracked = 0;
    std::optional<std::int64_t> total = input.frame_count();
    if (total && *total > o.max_frames) total = o.max_frames;
    ProgressLine progress(o.progress_s, total);
    do {
        const std::int64_t index = input.index();
        // The container's time when it has one, else the frame index at --fps.
        std::int64_t pts = input.timestamp_ns();
        if (pts < 0 && o.fps) pts = static_cast<std::int64_t>(static_cast<double>(index) * 1e9 / *o.fps + 0.5);

        const gc::FrameResult& r = input.stereo() ? tracker.process_stereo(left_frame, right_frame, pts)
                                                  : tracker.process_mono(left_frame, pts);
        tracked += r.state == gc::TrackState::Tracking ? 1 : 0;
        out.write_line(json_line(r, index));
        progress.frame_done(++frames);
    } while (input.next_index() < o.max_frames && input.next(left_frame, right_frame) && input.index() < o.max_frames);
    out.close();
    std::cerr << "gesturecam-track: " << frames << " frames, " << tracked << " tracking";
    if (input.skipped() > 0) std::cerr << ", " << input.skipped() << " undecodable skipped";
    std::cerr << '\n';
}

}  // namespace

int main(int argc, char** argv)
{
    Options options;
    GivenText given;
    CLI::App app("Tracks the pointing hand in a recorded stereo pair", "gesturecam-track");
    gc::cli::configure(app, kUsage);
    add_options(app, options, given);
    if (const int status = gc::cli::parse(app, argc, argv); status >= 0) return status;
    try {
        convert(given, options);
    } catch (const gc::cli::UsageError& e) {
        return gc::cli::usage_hint("gesturecam-track", e.what());
    }
    try {
        std::ios::sync_with_stdio(false);
        run(options);
    } catch (const std::exception& e) {
        std::cerr << "gesturecam-track: error: " << e.what() << '\n';
        return 1;
    }
    return 0;
}
