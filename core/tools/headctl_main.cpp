// headctl: command-line client of a head (GCHP/1 or VISCA).
#include "headctl/head_backend.hpp"
#include "headctl/protocol.hpp"
#include "headctl/token.hpp"

#include <getopt.h>
#include <signal.h>

#include <atomic>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <optional>
#include <thread>

namespace {

using namespace gc::headctl;

// Exit codes.
constexpr int kExitUsage = 2;
constexpr int kExitConnection = 3;
constexpr int kExitRefused = 4;

std::atomic<bool> g_interrupted{false};
void on_signal(int) { g_interrupted = true; }

const char* kUsage = R"(usage: headctl [--uri URI] [--token-file FILE | --token TOKEN] [--timeout MS] COMMAND [ARGS]
Commands:
  status                         print every axis's angle and motion
  limits                         print soft limits, maximum velocity and acceleration
  move [abs|rel|vel] AXIS=VALUE...   move (default abs): degrees, or deg/s for vel;
                                 zoom is a magnification (1 = widest, 2 = twice), or per s for vel
  home                           move every angle to 0 and the zoom to 1
  preset save|recall N           store where the head is as preset N (0..127), or go back there
  stop                           stop every axis
  watch [INTERVAL_MS [COUNT]]    print the status repeatedly (default 200 ms, until Ctrl-C)
URI: tcp://HOST:PORT (GCHP, default tcp://127.0.0.1:5050), visca-udp://HOST[:52381],
     visca-tcp://HOST[:5678], visca-serial:///dev/ttyUSB0?baud=9600,
     pelco-d:///dev/ttyUSB0?address=1&baud=2400. Axes: pan, tilt, verge_l, verge_r, zoom.
Token (GCHP): --token-file FILE (its first line), else --token, else the URI's ?token=,
     else GESTURECAM_HEAD_TOKEN. A token on the command line is blanked there once read.
Exit status: 0 done, 2 usage error, 3 head unreachable, 4 head refused the command.
)";

class UsageError : public std::invalid_argument {
public:
    using std::invalid_argument::invalid_argument;
};

double number(std::string_view what, std::string_view text) {
    double v = 0.0;
    auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    if (ec != std::errc{} || ptr != text.data() + text.size() || !std::isfinite(v))
        throw UsageError(std::string(what) + ": '" + std::string(text) + "' is not a finite number");
    return v;
}

void print_state(const HeadState& s) {
    std::printf("t=%lld pan=%.3f tilt=%.3f verge_l=%.3f verge_r=%.3f zoom=%.3f moving=%d,%d,%d,%d,%d\n",
                static_cast<long long>(s.server_time_us), s.pose.pan_deg, s.pose.tilt_deg, s.pose.verge_left_deg,
                s.pose.verge_right_deg, s.pose.zoom, s.moving[0], s.moving[1], s.moving[2], s.moving[3], s.moving[4]);
    std::fflush(stdout);
}

HeadCommand parse_move(int argc, char** argv, int i) {
    HeadCommand c{CommandKind::Absolute, {}};
    if (i < argc) {
        const std::string_view mode = argv[i];
        if (mode == "abs" || mode == "rel" || mode == "vel") {
            c.kind = mode == "abs" ? CommandKind::Absolute : mode == "rel" ? CommandKind::Relative : CommandKind::Velocity;
            ++i;
        }
    }
    for (; i < argc; ++i) {
        const std::string_view arg = argv[i];
        const auto eq = arg.find('=');
        if (eq == std::string_view::npos) throw UsageError("move: expected AXIS=VALUE, got '" + std::string(arg) + "'");
        const auto axis = axis_from_name(arg.substr(0, eq));
        if (!axis) throw UsageError("move: unknown axis '" + std::string(arg.substr(0, eq)) + "'");
        if (c.values.has(*axis)) throw UsageError("move: axis " + std::string(arg.substr(0, eq)) + " given twice");
        c.values.set(*axis, number(arg.substr(0, eq), arg.substr(eq + 1)));
    }
    if (c.values.empty()) throw UsageError("move: name at least one AXIS=VALUE");
    return c;
}

HeadCommand parse_preset(int argc, char** argv, int i) {
    if (argc - i != 2) throw UsageError("preset: expected save|recall N");
    const std::string_view action = argv[i];
    if (action != "save" && action != "recall")
        throw UsageError("preset: expected save or recall, got '" + std::string(action) + "'");
    const double n = number("preset number", argv[i + 1]);
    if (n < 0 || n > kMaxPreset || n != std::floor(n))
        throw UsageError("preset: the number must be a whole number in 0..127");
    return preset_command(action == "save" ? CommandKind::SavePreset : CommandKind::RecallPreset, static_cast<int>(n));
}

// What the command line asks for.
struct CommandLine {
    std::string uri_text = "tcp://127.0.0.1:5050";
    std::string token;
    double timeout_ms = 2000;
    std::string command;
    int first_arg = 0;  // the index of the command's first argument
};

// Reads the options and the command; an exit status when the program ends here (--help, an
// unknown option). Throws UsageError on a bad value.
std::optional<int> parse_command_line(int argc, char** argv, CommandLine& cl) {
    const option options[] = {
        {"uri", required_argument, nullptr, 'u'},
        {"token", required_argument, nullptr, 't'},
        {"token-file", required_argument, nullptr, 'f'},
        {"timeout", required_argument, nullptr, 'T'},
        {"help", no_argument, nullptr, 'h'},
        {nullptr, 0, nullptr, 0},
    };
    int opt;
    // '+': options end at the command, so "move rel pan=-5" keeps its minus sign.
    while ((opt = getopt_long(argc, argv, "+h", options, nullptr)) != -1) {
        switch (opt) {
            case 'u':
                cl.uri_text = optarg;
                hide_token_in_uri_argument(optarg);
                break;
            case 't':
            case 'f':
                if (!cl.token.empty()) throw UsageError("give one of --token and --token-file");
                cl.token = opt == 'f' ? read_token_file(optarg) : optarg;
                if (opt == 't') hide_argument(optarg);
                break;
            case 'T':
                cl.timeout_ms = number("--timeout", optarg);
                if (cl.timeout_ms <= 0 || cl.timeout_ms > 600'000)
                    throw UsageError("--timeout: must be in (0, 600000] ms");
                break;
            case 'h': std::cout << kUsage; return 0;
            default: std::cerr << kUsage; return kExitUsage;
        }
    }
    if (optind >= argc) throw UsageError("no command given");
    cl.command = argv[optind];
    cl.first_arg = optind + 1;
    return std::nullopt;
}

// The move that `command` asks for, if any; throws UsageError on an unknown command or wrong arguments.
std::optional<HeadCommand> parse_command(const CommandLine& cl, int argc, char** argv) {
    const std::string& command = cl.command;
    std::optional<HeadCommand> move;
    if (command == "move") move = parse_move(argc, argv, cl.first_arg);
    else if (command == "home") move = HeadCommand{CommandKind::Home, {}};
    else if (command == "preset") move = parse_preset(argc, argv, cl.first_arg);
    else if (command == "stop") move = HeadCommand{CommandKind::Stop, {}};
    else if (command != "status" && command != "limits" && command != "watch")
        throw UsageError("unknown command '" + command + "'");
    const int extra = argc - cl.first_arg;
    if ((command == "status" || command == "limits" || command == "home" || command == "stop") && extra != 0)
        throw UsageError(command + " takes no arguments");
    if (command == "watch" && extra > 2) throw UsageError("watch takes at most INTERVAL_MS and COUNT");
    return move;
}

int print_limits(HeadBackend& head, std::chrono::steady_clock::time_point deadline) {
    const auto limits = head.query_limits(deadline);
    if (!limits) {
        std::cerr << "headctl: " << head.name() << " does not report its limits\n";
        return kExitRefused;
    }
    for (Axis a : kAllAxes) {
        const AxisLimits& l = (*limits)[a];
        std::printf("%-8s min=%.3f max=%.3f max_velocity=%.3f max_acceleration=%.3f\n",
                    std::string(axis_name(a)).c_str(), l.min_deg, l.max_deg, l.max_velocity_dps,
                    l.max_acceleration_dps2);
    }
    return 0;
}

// Prints the status every INTERVAL_MS (default 200), COUNT times (default 0: until a signal).
template <typename Deadline>
void watch(HeadBackend& head, int argc, char** argv, int first_arg, Deadline deadline) {
    const int extra = argc - first_arg;
    const double interval = extra >= 1 ? number("watch interval", argv[first_arg]) : 200.0;
    const double count = extra >= 2 ? number("watch count", argv[first_arg + 1]) : 0.0;
    if (interval < 1 || interval > 60'000) throw UsageError("watch interval must be 1..60000 ms");
    if (count < 0 || count != std::floor(count)) throw UsageError("watch count must be a whole number >= 0");
    struct sigaction sa{};
    sa.sa_handler = on_signal;
    sigaction(SIGINT, &sa, nullptr);
    sigaction(SIGTERM, &sa, nullptr);
    for (long n = 0; !g_interrupted && (count == 0 || n < static_cast<long>(count)); ++n) {
        if (n) std::this_thread::sleep_for(std::chrono::microseconds(static_cast<long long>(interval * 1000)));
        print_state(head.query_state(deadline()));
    }
}

// Runs the command on the head; the exit status.
int run(HeadBackend& head, const CommandLine& cl, int argc, char** argv) {
    const auto timeout = std::chrono::microseconds(static_cast<long long>(cl.timeout_ms * 1000));
    auto deadline = [&] { return std::chrono::steady_clock::now() + timeout; };
    const std::optional<HeadCommand> move = parse_command(cl, argc, argv);
    head.open(deadline());
    if (move) {
        head.send(*move, deadline());
        std::cout << "ok " << describe(*move) << "\n";
    } else if (cl.command == "status") {
        print_state(head.query_state(deadline()));
    } else if (cl.command == "limits") {
        return print_limits(head, deadline());
    } else {
        watch(head, argc, argv, cl.first_arg, deadline);
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    CommandLine cl;
    std::unique_ptr<HeadBackend> head;
    try {
        if (const std::optional<int> status = parse_command_line(argc, argv, cl)) return *status;
        const HeadUri uri = parse_head_uri(cl.uri_text);
        if (cl.token.empty() && !uri.param("token")) cl.token = token_from_environment();
        head = make_backend(uri, cl.token);
    } catch (const std::invalid_argument& e) {
        std::cerr << "headctl: " << e.what() << "\n" << kUsage;
        return kExitUsage;
    }

    try {
        return run(*head, cl, argc, argv);
    } catch (const UsageError& e) {
        std::cerr << "headctl: " << e.what() << "\n";
        return kExitUsage;
    } catch (const HeadRejected& e) {
        std::cerr << "headctl: " << e.what() << "\n";
        return kExitRefused;
    } catch (const gc::headctl::net::NetError& e) {
        std::cerr << "headctl: " << e.what() << "\n";
        return kExitConnection;
    } catch (const std::exception& e) {
        std::cerr << "headctl: " << e.what() << "\n";
        return kExitRefused;
    }
}
