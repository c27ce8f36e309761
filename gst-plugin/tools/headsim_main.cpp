// headsim: the simulated head server (GCHP/1 over TCP; ONVIF PTZ and VISCA on request).
#include "headctl/sim/head_server.hpp"
#include "headctl/sim/onvif_responder.hpp"
#include "headctl/sim/visca_responder.hpp"
#include "headctl/token.hpp"
#include "tools/cli_app.hpp"

#include <signal.h>

#include <charconv>
#include <cmath>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

namespace {

using namespace gc::headctl;

HeadServer* g_server = nullptr;

void on_signal(int)
{
    if (g_server) g_server->request_stop();
}

const char* kUsage = R"(usage: headsim [options]
Simulated motorised head serving GCHP/1 (docs/head-protocol.md).
  --listen ADDR:PORT     address to bind (default 127.0.0.1:5050; port 0 = any free port)
  --token-file FILE      require AUTH with the token in FILE's first line before any other
                         request (or set GESTURECAM_HEAD_TOKEN)
  --token TOKEN          the same, given on the command line (blanked there once read, but
                         visible to other users until then: prefer the file)
  --onvif ADDR:PORT      also serve the ONVIF PTZ service (SOAP over HTTP) on the same head;
                         with a token, requests need a UsernameToken digest of it
  --onvif-user USER      the ONVIF user name (default gesturecam)
  --visca ADDR:PORT      also serve VISCA over IP (UDP) and raw VISCA over TCP on that port of
                         the same head: 16 units per degree, zoom position 0x4000 at the
                         largest magnification; no authentication
  --allow-remote         listen beyond loopback without a token, and serve VISCA there (anyone
                         reaching the port moves the head)
  --max-clients N        connections served at once (default 16)
  --latency-ms MS        delay from a command's arrival to its effect (default 0)
  --angle-error DEG      std. deviation of the reached angle around a target (default 0)
  --seed N               seed of the angle error (default 1)
  --limits AXIS=MIN:MAX:VMAX:AMAX
                         soft limits (deg), velocity (deg/s) and acceleration (deg/s^2)
                         of one axis (pan, tilt, verge_l, verge_r; zoom in magnification,
                         MIN 1, default 1:20:8:30); repeatable
  --velocity-timeout S   a velocity move not renewed within S seconds stops (default 1; 0 = never)
  --verbose              log connections on stderr
  --version              the version
  -h, --help             this text
On start it prints "listening ADDR:PORT" on stdout, then "onvif listening ADDR:PORT" with
--onvif and "visca listening ADDR:PORT" with --visca.
SIGTERM or SIGINT stops it cleanly.
)";

double number(const char* option, std::string_view text)
{
    double v = 0.0;
    auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    if (ec != std::errc{} || ptr != text.data() + text.size() || !std::isfinite(v))
        throw std::invalid_argument(std::string(option) + ": '" + std::string(text) + "' is not a number");
    return v;
}

template <class Config>
void parse_listen(std::string_view text, Config& config, const std::string& option = "--listen")
{
    const auto colon = text.rfind(':');
    if (colon == std::string_view::npos || colon == 0) throw std::invalid_argument(option + ": expected ADDR:PORT");
    std::string_view host = text.substr(0, colon);
    if (host.size() >= 2 && host.front() == '[' && host.back() == ']') host = host.substr(1, host.size() - 2);
    const double port = number((option + " port").c_str(), text.substr(colon + 1));
    if (port < 0 || port > 65535 || port != std::floor(port))
        throw std::invalid_argument(option + ": port must be 0..65535");
    config.host = std::string(host);
    config.port = static_cast<std::uint16_t>(port);
}

void parse_limits(std::string_view text, HeadLimits& limits)
{
    const auto eq = text.find('=');
    if (eq == std::string_view::npos) throw std::invalid_argument("--limits: expected AXIS=MIN:MAX:VMAX:AMAX");
    const auto axis = axis_from_name(text.substr(0, eq));
    if (!axis) throw std::invalid_argument("--limits: unknown axis '" + std::string(text.substr(0, eq)) + "'");
    double v[4];
    std::string_view rest = text.substr(eq + 1);
    for (int i = 0; i < 4; ++i) {
        const auto colon = rest.find(':');
        if ((i < 3) == (colon == std::string_view::npos))
            throw std::invalid_argument("--limits: expected MIN:MAX:VMAX:AMAX");
        v[i] = number("--limits", rest.substr(0, colon));
        rest = i < 3 ? rest.substr(colon + 1) : std::string_view{};
    }
    limits[*axis] = AxisLimits{v[0], v[1], v[2], v[3]};
}

// The options' texts as CLI11 read them, converted by apply().
struct GivenText {
    std::optional<std::string> listen, token, token_file, max_clients, latency_ms, angle_error, seed, velocity_timeout;
    std::optional<std::string> onvif, onvif_user, visca;
    std::vector<std::string> limits;
};

void add_options(CLI::App& app, HeadServerConfig& config, GivenText& t)
{
    app.add_option("--listen", t.listen);
    CLI::Option* token = app.add_option("--token", t.token);
    app.add_option("--token-file", t.token_file)->excludes(token);
    app.add_flag("--allow-remote", config.allow_remote_without_token);
    app.add_option("--onvif", t.onvif);
    app.add_option("--onvif-user", t.onvif_user);
    app.add_option("--visca", t.visca);
    app.add_option("--max-clients", t.max_clients);
    app.add_option("--latency-ms", t.latency_ms);
    app.add_option("--angle-error", t.angle_error);
    app.add_option("--seed", t.seed);
    app.add_option("--limits", t.limits)->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
    app.add_option("--velocity-timeout", t.velocity_timeout);
    app.add_flag("--verbose", config.verbose);
}

// The ONVIF responder's settings, when --onvif asks for one (after apply()).
std::optional<OnvifResponderConfig> onvif_config(const GivenText& t, const HeadServerConfig& config)
{
    if (!t.onvif) return std::nullopt;
    OnvifResponderConfig onvif;
    parse_listen(*t.onvif, onvif, "--onvif");
    if (t.onvif_user) onvif.user = *t.onvif_user;
    onvif.password = config.token;
    onvif.allow_remote_without_password = config.allow_remote_without_token;
    return onvif;
}

// The VISCA responder's settings, when --visca asks for one.
std::optional<ViscaResponderConfig> visca_config(const GivenText& t, const HeadServerConfig& config)
{
    if (!t.visca) return std::nullopt;
    ViscaResponderConfig visca;
    parse_listen(*t.visca, visca, "--visca");
    visca.allow_remote = config.allow_remote_without_token;
    return visca;
}

// Checks and converts the texts into `config`; throws std::invalid_argument.
void apply(const GivenText& t, HeadServerConfig& config)
{
    if (t.listen) parse_listen(*t.listen, config);
    if (t.token) {
        config.token = *t.token;
        if (config.token.empty()) throw std::invalid_argument("--token: must not be empty");
    }
    if (t.token_file) config.token = read_token_file(*t.token_file);
    if (t.max_clients) {
        const double n = number("--max-clients", *t.max_clients);
        if (n < 1 || n > 10000 || n != std::floor(n)) throw std::invalid_argument("--max-clients: must be 1..10000");
        config.max_clients = static_cast<std::size_t>(n);
    }
    if (t.latency_ms) config.model.latency_s = number("--latency-ms", *t.latency_ms) / 1000.0;
    if (t.angle_error) config.model.angle_error_deg = number("--angle-error", *t.angle_error);
    if (t.seed) {
        const double n = number("--seed", *t.seed);
        if (n < 0 || n != std::floor(n)) throw std::invalid_argument("--seed: must be a non-negative integer");
        config.model.seed = static_cast<std::uint64_t>(n);
    }
    for (const std::string& l : t.limits) parse_limits(l, config.model.limits);
    if (t.velocity_timeout) config.model.velocity_timeout_s = number("--velocity-timeout", *t.velocity_timeout);
    if (config.token.empty()) config.token = token_from_environment();
    config.model.validate();
}

std::string address_text(const std::string& host, std::uint16_t port)
{
    const bool v6 = host.find(':') != std::string::npos;
    return (v6 ? "[" + host + "]" : host) + ":" + std::to_string(port);
}

struct Responders {
    std::optional<OnvifResponderConfig> onvif;
    std::optional<ViscaResponderConfig> visca;
};

// Serves until SIGTERM or SIGINT.
void serve(const HeadServerConfig& config, const Responders& configs)
{
    HeadServer server(config);
    std::optional<OnvifResponder> onvif;
    if (configs.onvif) onvif.emplace(*configs.onvif, server);
    std::optional<ViscaResponder> visca;
    if (configs.visca) visca.emplace(*configs.visca, server);
    if (config.token.empty() && !is_loopback_address(config.host))
        std::cerr << "headsim: warning: listening on " << config.host
                  << " without a token: anyone who can reach this port can move the head\n";
    g_server = &server;
    gc::cli::on_stop_signals(on_signal);
    signal(SIGPIPE, SIG_IGN);
    std::cout << "listening " << address_text(server.host(), server.port()) << std::endl;
    if (onvif) std::cout << "onvif listening " << address_text(onvif->host(), onvif->port()) << std::endl;
    if (visca) std::cout << "visca listening " << address_text(visca->host(), visca->port()) << std::endl;
    server.run();
    g_server = nullptr;
    std::cerr << "headsim: stopped\n";
}

}  // namespace

int main(int argc, char** argv)
{
    HeadServerConfig config;
    GivenText given;
    CLI::App app("Simulated motorised head serving GCHP/1", "headsim");
    gc::cli::configure(app, kUsage);
    add_options(app, config, given);
    if (const int status = gc::cli::parse(app, argc, argv); status >= 0) return status;
    hide_secret_arguments(argc, argv);
    Responders responders;
    try {
        apply(given, config);
        responders.onvif = onvif_config(given, config);
        responders.visca = visca_config(given, config);
    } catch (const std::exception& e) {
        return gc::cli::usage_hint("headsim", e.what());
    }
    try {
        serve(config, responders);
    } catch (const std::invalid_argument& e) {
        std::cerr << "headsim: " << e.what() << "\n";
        return 2;
    } catch (const std::exception& e) {
        std::cerr << "headsim: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
