#include "tools/bench_options.hpp"

#include "tools/cli_args.hpp"

#include <optional>
#include <string>

namespace gc::tools {

const std::string_view kBenchUsage = R"(usage: gesturecam-bench [options]

Measures the tracker on the synthetic scenes (640x480): SNR, mean mask IoU, tracked fraction,
lost frames and milliseconds per frame per eye by particle count; OpenCV's trackers (KCF,
CSRT, MedianFlow, CamShift) on the same frames; the 3D step; the stereo throughput.

options:
  --particles LIST   particle counts (default 20,50,100,200,500,1000,2000,5000)
  --scenes LIST      clean,light,heavy,face_pass (default: all four)
  --motion NAME      scripted hand motion: static, translate, rotate, scale, yaw, mixed,
                     leave_return (default mixed)
  --frames N         frames per sequence (default 150)
  --runs R           timed runs per measurement; the median is reported (default 5)
  --seeds LIST       scene seeds; figures are pooled over them (default 1,2,3)
  --peer-particles N our particle count in the comparison with OpenCV's trackers, the 3D
                     step and the throughput (default 1000)
  --no-peers         skip the comparison with OpenCV's trackers
  --quick            a small smoke run: particles 50,200, scenes clean,heavy, 40 frames,
                     1 run, seed 1, 200 particles for the comparisons (options given
                     explicitly still apply)
  --json             JSON lines instead of markdown tables
  --help             this text
)";

BenchOptions parse_bench_options(int argc, char** argv)
{
    using gc::cli::parse_number;
    BenchOptions o;
    gc::cli::ArgReader args(argc, argv);
    bool quick = false;
    std::optional<std::vector<int>> particles;
    std::optional<std::vector<gc::sim::Preset>> scenes;
    std::optional<int> frames, runs, peer_particles;
    std::optional<std::vector<std::uint64_t>> seeds;
    while (args.next()) {
        const std::string_view name = args.name();
        if (name == "--help") {
            args.no_value();
            o.help = true;
        } else if (name == "--json") {
            args.no_value();
            o.json = true;
        } else if (name == "--quick") {
            args.no_value();
            quick = true;
        } else if (name == "--no-peers") {
            args.no_value();
            o.peers = false;
        } else if (name == "--particles") {
            particles = gc::cli::parse_list<int>(name, args.value(), [](auto opt, auto item) {
                return parse_number<int>(opt, item, 1, 100000);
            });
        } else if (name == "--scenes") {
            scenes = gc::cli::parse_list<gc::sim::Preset>(name, args.value(), [](auto opt, auto item) {
                const auto p = gc::sim::preset_from_string(item);
                if (!p)
                    throw gc::cli::UsageError(std::string(opt) + ": unknown scene '" +
                                              std::string(item) +
                                              "' (clean, light, heavy, face_pass)");
                return *p;
            });
        } else if (name == "--motion") {
            const std::string_view v = args.value();
            const auto m = gc::sim::motion_from_string(v);
            if (!m)
                throw gc::cli::UsageError("--motion: unknown motion '" + std::string(v) + "'");
            o.motion = *m;
        } else if (name == "--frames") {
            frames = parse_number<int>(name, args.value(), 10, 100000);
        } else if (name == "--runs") {
            runs = parse_number<int>(name, args.value(), 1, 1000);
        } else if (name == "--seeds") {
            seeds = gc::cli::parse_list<std::uint64_t>(name, args.value(), [](auto opt, auto item) {
                return parse_number<std::uint64_t>(opt, item);
            });
        } else if (name == "--peer-particles") {
            peer_particles = parse_number<int>(name, args.value(), 1, 100000);
        } else {
            throw gc::cli::UsageError("unknown option " + std::string(name));
        }
    }
    if (quick) {
        o.particles = {50, 200};
        o.scenes = {gc::sim::Preset::Clean, gc::sim::Preset::Heavy};
        o.frames = 40;
        o.runs = 1;
        o.seeds = {1};
        o.peer_particles = 200;
    }
    // Explicit options win over --quick.
    if (particles) o.particles = *particles;
    if (scenes) o.scenes = *scenes;
    if (frames) o.frames = *frames;
    if (runs) o.runs = *runs;
    if (seeds) o.seeds = *seeds;
    if (peer_particles) o.peer_particles = *peer_particles;
    return o;
}

}  // namespace gc::tools
