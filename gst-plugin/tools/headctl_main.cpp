// headctl: command-line client of a head (GCHP/1, VISCA over IP or serial, Pelco-D, ONVIF).
#include "headctl/head_backend.hpp"
#include "headctl/token.hpp"
#include "tools/cli_app.hpp"
#include "tools/json_writer.hpp"

#include <atomic>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <functional>
#include <iostream>
#include <thread>

namespace {

using namespace gc::headctl;

// Exit codes.
constexpr int kExitConnection = 3;
constexpr int kExitRefused = 4;

std::atomic<bool> g_interrupted{false};
void on_signal(int) { g_interrupted = true; }

const char* kUsage =
    R"(usage: headctl [--uri URI] [--token-file FILE | --token TOKEN] [--timeout MS] [--json] COMMAND [ARGS]
Commands:
  status                         print every axis's angle and motion
  limits                         print soft limits, maximum velocity and acceleration
  move [abs|rel|vel] AXIS=VALUE...   move (default abs): degrees, or deg/s for vel
  home                           move every axis to 0
  stop                           stop every axis
  watch [INTERVAL_MS [COUNT]]    print the status repeatedly (default 200 ms, until Ctrl-C)
  preset save|recall N           store where the head is as preset N (0..127), or go back there
URI: tcp://HOST:PORT (GCHP, default tcp://127.0.0.1:5050), visca-udp://HOST[:52381],
     visca-tcp://HOST[:5678], visca-serial:///dev/ttyUSB0?baud=9600,
     pelco-d:///dev/ttyUSB0?address=1&baud=2400, onvif://HOST[:80][/PATH]?user=USER.
     Axes: pan, tilt, verge_l, verge_r, zoom.
Token (GCHP; ONVIF: the password): --token-file FILE (its first line), else --token, else the URI's ?token=,
     else GESTURECAM_HEAD_TOKEN. A token on the command line is blanked there once read.
--json: one JSON object per line: status and watch {"t_us", "pan", "tilt", "verge_l", "verge_r",
     "pan_moving", ...}, limits one {"axis", "min", "max", "max_velocity", "max_acceleration"}
     per axis, move/home/stop {"ok": true, "command"}.
--version prints the version, -h/--help this text.
Exit status: 0 done, 2 usage error, 3 head unreachable, 4 head refused the command.
)";

using UsageError = gc::cli::UsageError;

double number(std::string_view what, std::string_view text)
{
    double v = 0.0;
    auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    if (ec != std::errc{} || ptr != text.data() + text.size() || !std::isfinite(v))
        throw UsageError(std::string(what) + ": '" + std::string(text) + "' is not a finite number");
    return v;
}

void print_state(const HeadState& s, bool json)
{
    if (json) {
        gc::tools::JsonObject o;
        o.add("t_us", static_cast<std::int64_t>(s.server_time_us));
        const double angles[] = {s.pose.pan_deg, s.pose.tilt_deg, s.pose.verge_left_deg, s.pose.verge_right_deg,
                                 s.pose.zoom};
        for (Axis a : kAllAxes) o.add(axis_name(a), angles[static_cast<int>(a)], 3);
        for (Axis a : kAllAxes) o.add(std::string(axis_name(a)) + "_moving", bool(s.moving[static_cast<int>(a)]));
        std::printf("%s\n", o.str().c_str());
    } else {
        std::printf("t=%lld pan=%.3f tilt=%.3f verge_l=%.3f verge_r=%.3f zoom=%.3f moving=%d,%d,%d,%d,%d\n",
                    static_cast<long long>(s.server_time_us), s.pose.pan_deg, s.pose.tilt_deg, s.pose.verge_left_deg,
                    s.pose.verge_right_deg, s.pose.zoom, s.moving[0], s.moving[1], s.moving[2], s.moving[3],
                    s.moving[4]);
    }
    std::fflush(stdout);
}

void print_limits(const HeadLimits& limits, bool json)
{
    for (Axis a : kAllAxes) {
        const AxisLimits& l = limits[a];
        const std::string name(axis_name(a));
        if (json)
            std::printf("%s\n", gc::tools::JsonObject()
                                    .add("axis", name)
                                    .add("min", l.min_deg, 3)
                                    .add("max", l.max_deg, 3)
                                    .add("max_velocity", l.max_velocity_dps, 3)
                                    .add("max_acceleration", l.max_acceleration_dps2, 3)
                                    .str()
                                    .c_str());
        else
            std::printf("%-8s min=%.3f max=%.3f max_velocity=%.3f max_acceleration=%.3f\n", name.c_str(), l.min_deg,
                        l.max_deg, l.max_velocity_dps, l.max_acceleration_dps2);
    }
}

HeadCommand parse_move(const std::vector<std::string>& args)
{
    HeadCommand c{CommandKind::Absolute, {}};
    std::size_t i = 0;
    if (!args.empty() && (args[0] == "abs" || args[0] == "rel" || args[0] == "vel")) {
        c.kind = args[0] == "abs"   ? CommandKind::Absolute
                 : args[0] == "rel" ? CommandKind::Relative
                                    : CommandKind::Velocity;
        ++i;
    }
    for (; i < args.size(); ++i) {
        const std::string_view arg = args[i];
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

HeadCommand parse_preset(const std::vector<std::string>& args)
{
    if (args.size() != 2) throw UsageError("preset: expected save|recall N");
    const std::string& action = args[0];
    if (action != "save" && action != "recall")
        throw UsageError("preset: expected save or recall, got '" + action + "'");
    const double n = number("preset number", args[1]);
    if (n < 0 || n > kMaxPreset || n != std::floor(n))
        throw UsageError("preset: the number must be a whole number in 0..127");
    return preset_command(action == "save" ? CommandKind::SavePreset : CommandKind::RecallPreset, static_cast<int>(n));
}

// The command line: options, then the command and its arguments.
struct CommandLine {
    std::string uri = "tcp://127.0.0.1:5050";
    std::string token, token_file, timeout;
    double timeout_ms = 2000;
    bool json = false;
    std::string command;
    std::vector<std::string> args;
};

// Parses the command line: -1 to go on, else the status to exit with. Options end at the
// command, so "move rel pan=-5" keeps its minus sign.
int parse_command_line(int argc, char** argv, CommandLine& c)
{
    CLI::App app("Command-line client of a head", "headctl");
    gc::cli::configure(app, kUsage);
    app.prefix_command();
    app.add_option("--uri", c.uri);
    CLI::Option* token = app.add_option("--token", c.token);
    app.add_option("--token-file", c.token_file)->excludes(token);
    app.add_option("--timeout", c.timeout);
    app.add_flag("--json", c.json);
    if (const int status = gc::cli::parse(app, argc, argv); status >= 0) return status;
    std::vector<std::string> rest = app.remaining();
    if (rest.empty()) return gc::cli::usage_hint("headctl", "no command given");
    c.command = rest.front();
    c.args.assign(rest.begin() + 1, rest.end());
    return -1;
}

// The head the command line names, with its token; throws UsageError or std::invalid_argument.
std::unique_ptr<HeadBackend> open_backend(CommandLine& c)
{
    if (!c.timeout.empty()) {
        c.timeout_ms = number("--timeout", c.timeout);
        if (c.timeout_ms <= 0 || c.timeout_ms > 600'000) throw UsageError("--timeout: must be in (0, 600000] ms");
    }
    std::string token = c.token_file.empty() ? c.token : read_token_file(c.token_file);
    const HeadUri uri = parse_head_uri(c.uri);
    if (token.empty() && !uri.param("token")) token = token_from_environment();
    return make_backend(uri, token);
}

void check_arguments(const CommandLine& c)
{
    const std::string& command = c.command;
    if (command.starts_with("-")) throw UsageError("unknown option " + command);
    if (command != "move" && command != "home" && command != "stop" && command != "status" && command != "limits" &&
        command != "watch" && command != "preset")
        throw UsageError("unknown command '" + command + "'");
    if ((command == "status" || command == "limits" || command == "home" || command == "stop") && !c.args.empty())
        throw UsageError(command + " takes no arguments");
    if (command == "watch" && c.args.size() > 2) throw UsageError("watch takes at most INTERVAL_MS and COUNT");
}

void watch(HeadBackend& head, const CommandLine& c, const std::function<HeadBackend::Deadline()>& deadline)
{
    const double interval = c.args.size() >= 1 ? number("watch interval", c.args[0]) : 200.0;
    const double count = c.args.size() >= 2 ? number("watch count", c.args[1]) : 0.0;
    if (interval < 1 || interval > 60'000) throw UsageError("watch interval must be 1..60000 ms");
    if (count < 0 || count != std::floor(count)) throw UsageError("watch count must be a whole number >= 0");
    gc::cli::on_stop_signals(on_signal);
    for (long n = 0; !g_interrupted && (count == 0 || n < static_cast<long>(count)); ++n) {
        if (n) std::this_thread::sleep_for(std::chrono::microseconds(static_cast<long long>(interval * 1000)));
        print_state(head.query_state(deadline()), c.json);
    }
}

// Runs the command against the head; returns the exit status.
int run_command(HeadBackend& head, const CommandLine& c)
{
    const auto timeout = std::chrono::microseconds(static_cast<long long>(c.timeout_ms * 1000));
    const std::function<HeadBackend::Deadline()> deadline = [&] { return std::chrono::steady_clock::now() + timeout; };
    std::optional<HeadCommand> move;
    if (c.command == "move")
        move = parse_move(c.args);
    else if (c.command == "home")
        move = HeadCommand{CommandKind::Home, {}};
    else if (c.command == "preset")
        move = parse_preset(c.args);
    else if (c.command == "stop")
        move = HeadCommand{CommandKind::Stop, {}};
    head.open(deadline());
    if (move) {
        head.send(*move, deadline());
        if (c.json)
            std::cout << gc::tools::JsonObject().add("ok", true).add("command", describe(*move)).str() << "\n";
        else
            std::cout << "ok " << describe(*move) << "\n";
    } else if (c.command == "status") {
        print_state(head.query_state(deadline()), c.json);
    } else if (c.command == "limits") {
        const auto limits = head.query_limits(deadline());
        if (!limits) {
            std::cerr << "headctl: " << head.name() << " does not report its limits\n";
            return kExitRefused;
        }
        print_limits(*limits, c.json);
    } else {
        watch(head, c, deadline);
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv)
{
    CommandLine c;
    if (const int status = parse_command_line(argc, argv, c); status >= 0) return status;
    hide_secret_arguments(argc, argv);
    std::unique_ptr<HeadBackend> head;
    try {
        check_arguments(c);
        head = open_backend(c);
    } catch (const std::invalid_argument& e) {  // a URI or token file that will not do
        return gc::cli::usage_hint("headctl", e.what());
    } catch (const UsageError& e) {
        return gc::cli::usage_hint("headctl", e.what());
    }
    try {
        return run_command(*head, c);
    } catch (const UsageError& e) {
        return gc::cli::usage_hint("headctl", e.what());
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
