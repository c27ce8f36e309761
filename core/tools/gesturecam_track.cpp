// gesturecam-track: tracks the pointing hand through a recorded stereo pair (or one view) and
// writes one JSON line per frame (schema: docs/track-tool.md).
//
// Exit status: 0 success (warnings may be printed), 1 an input or calibration problem,
// 2 a wrong command line.
#include "tools/cli_args.hpp"
#include "tools/frame_source.hpp"
#include "tracker/pointing_tracker.hpp"

#include <opencv2/core/utils/logger.hpp>

#include <cstdint>
#include <fstream>
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
  --seed S              random seed; same seed and input give the same output (default 1)
  --detector D          how the hand is found: learned (the palm and landmark models,
                        default) or motion (the thesis's waving skin blob, nothing learned)
  --model-dir DIR       folder of the learned models (default: found without configuration)
  --out FILE            output file (default: standard output)
  --fps F               frame rate for pts_ns when the left input carries no timestamps
                        (image sequences); without it pts_ns is null there
  --max-frames N        stop after N frames
  --help                this text

exit status: 0 success, 1 input or calibration error, 2 bad command line
)";

struct Options {
    std::string left;
    std::optional<std::string> right;
    std::optional<std::string> calibration;
    gc::TrackerParams params;
    std::optional<std::string> out;
    std::optional<double> fps;
    std::int64_t max_frames = std::numeric_limits<std::int64_t>::max();
    bool help = false;
};

Options parse_options(int argc, char** argv)
{
    using gc::cli::parse_number;
    Options o;
    gc::cli::ArgReader args(argc, argv);
    while (args.next()) {
        const std::string_view name = args.name();
        if (name == "--help") {
            args.no_value();
            o.help = true;
        } else if (name == "--left") {
            o.left = args.value();
        } else if (name == "--right") {
            o.right = std::string(args.value());
        } else if (name == "--calibration") {
            o.calibration = std::string(args.value());
        } else if (name == "--particles") {
            o.params.particles = parse_number<int>(name, args.value(), 1, 100000);
        } else if (name == "--seed") {
            o.params.seed = parse_number<std::uint64_t>(name, args.value());
        } else if (name == "--detector") {
            const std::string_view d = args.value();
            if (d != "learned" && d != "motion")
                throw gc::cli::UsageError("--detector must be learned or motion, not " + std::string(d));
            o.params.detector = d == "motion" ? gc::HandDetector::Motion : gc::HandDetector::Learned;
        } else if (name == "--model-dir") {
            o.params.model_dir = std::string(args.value());
        } else if (name == "--out") {
            o.out = std::string(args.value());
        } else if (name == "--fps") {
            o.fps = parse_number<double>(name, args.value(), 1e-3, 1e4);
        } else if (name == "--max-frames") {
            o.max_frames = parse_number<std::int64_t>(name, args.value(), 1,
                                                      std::numeric_limits<std::int64_t>::max());
        } else {
            throw gc::cli::UsageError("unknown option " + std::string(name));
        }
    }
    if (!o.help && o.left.empty())
        throw gc::cli::UsageError("--left is required");
    if (o.right && o.right->empty())
        throw gc::cli::UsageError("--right needs a non-empty value");
    if (o.out && o.out->empty())
        throw gc::cli::UsageError("--out needs a non-empty value");
    return o;
}

std::string size_text(const cv::Size& s)
{
    return std::to_string(s.width) + "x" + std::to_string(s.height);
}

// Reads the next frame of each input into `l` / `r`; false when either input has ended (with
// a warning when the other has not, since the pair is then incomplete).
bool read_pair(gc::tools::FrameSource& left, std::optional<gc::tools::FrameSource>& right,
               std::int64_t frame, cv::Mat& l, cv::Mat& r)
{
    if (!left.read(l)) {
        if (frame == 0)
            throw gc::tools::InputError(left.describe() + ": no frame could be read");
        if (right && right->read(r))
            std::cerr << "gesturecam-track: warning: left input ended after " << frame
                      << " frames but the right input has more; stopped at the shorter\n";
        return false;
    }
    if (right && !right->read(r)) {
        if (frame == 0)
            throw gc::tools::InputError(right->describe() + ": no frame could be read");
        std::cerr << "gesturecam-track: warning: right input ended at frame " << frame
                  << " before the left; stopped at the shorter\n";
        return false;
    }
    if (right && l.size() != r.size())
        throw gc::tools::InputError("frame " + std::to_string(frame) + ": left frames are " +
                                    size_text(l.size()) + " but right frames are " +
                                    size_text(r.size()));
    return true;
}

// Opens the inputs and checks the first frames before opening the output, so that a bad
// input leaves no empty output file behind; then tracks frame by frame.
void run(const Options& o)
{
    gc::tools::FrameSource left(o.left, "left");
    std::optional<gc::tools::FrameSource> right;
    if (o.right)
        right.emplace(*o.right, "right");

    cv::Mat left_frame;
    cv::Mat right_frame;
    read_pair(left, right, 0, left_frame, right_frame);

    // Checked before the output is opened, so a rejected input leaves no output file.
    if (right && left_frame.size() != right_frame.size())
        throw std::invalid_argument("the left input is " + std::to_string(left_frame.cols) + "x" +
                                    std::to_string(left_frame.rows) + " but the right input is " +
                                    std::to_string(right_frame.cols) + "x" + std::to_string(right_frame.rows));
    std::optional<gc::StereoCalibration> calibration;
    if (o.calibration) {
        if (right) {
            calibration = gc::load_calibration(*o.calibration);
            gc::validate_calibration_size(*calibration, left_frame.size());
        } else {
            std::cerr << "gesturecam-track: warning: --calibration is ignored in mono mode\n";
        }
    }
    gc::PointingTracker tracker(o.params, calibration);

    std::ofstream file;
    if (o.out) {
        file.open(*o.out, std::ios::out | std::ios::trunc);
        if (!file)
            throw std::runtime_error("cannot open output file '" + *o.out + "'");
    }
    std::ostream& out = o.out ? static_cast<std::ostream&>(file) : std::cout;

    std::int64_t frame = 0;
    std::int64_t tracked = 0;
    do {
        // The container's time when it has one, else the frame index at --fps.
        std::int64_t pts = left.timestamp_ns();
        if (pts < 0 && o.fps)
            pts = static_cast<std::int64_t>(static_cast<double>(frame) * 1e9 / *o.fps + 0.5);

        const gc::FrameResult& r = right ? tracker.process_stereo(left_frame, right_frame, pts)
                                         : tracker.process_mono(left_frame, pts);
        tracked += r.state == gc::TrackState::Tracking ? 1 : 0;
        out << gc::to_json_line(r) << '\n';
        if (!out)
            throw std::runtime_error("cannot write the output");
        ++frame;
    } while (frame < o.max_frames && read_pair(left, right, frame, left_frame, right_frame));
    out.flush();
    if (!out)
        throw std::runtime_error("cannot write the output");
    std::cerr << "gesturecam-track: " << frame << " frames, " << tracked << " tracking\n";
}

}  // namespace

int main(int argc, char** argv)
{
    Options options;
    try {
        options = parse_options(argc, argv);
    } catch (const gc::cli::UsageError& e) {
        std::cerr << "gesturecam-track: " << e.what() << "\n\n" << kUsage;
        return 2;
    }
    if (options.help) {
        std::cout << kUsage;
        return 0;
    }
    // The image-sequence reader warns when it reaches the end of a sequence: not news here.
    cv::utils::logging::setLogLevel(cv::utils::logging::LOG_LEVEL_ERROR);
    try {
        std::ios::sync_with_stdio(false);
        run(options);
    } catch (const std::exception& e) {
        std::cerr << "gesturecam-track: error: " << e.what() << '\n';
        return 1;
    }
    return 0;
}
