// Loopback helpers of the head tests: an in-process simulated head, a raw line client that
// may speak from any 127.x.y.z address, a server that only says one scripted thing, and
// the start of a built program with its output on pipes.
#pragma once

#include "running_head.hpp"
#include "headctl/sim/head_server.hpp"
#include "headctl/sim/onvif_responder.hpp"
#include "headctl/sim/visca_responder.hpp"
#include "headctl/net.hpp"

#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <spawn.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <functional>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

extern char** environ;

namespace gc::headctl::testing {

using namespace std::chrono_literals;

// A HeadServer on 127.0.0.1 serving on its own thread for the lifetime of the object (the
// loopback head of the closed-loop tests); the default port, 5050, becomes any free one.
class RunningServer : public loopback::RunningHead {
public:
    explicit RunningServer(HeadServerConfig config = {}) : RunningHead(any_free_port(config)) {}

private:
    static HeadServerConfig any_free_port(HeadServerConfig config)
    {
        if (config.port == 5050) config.port = 0;
        return config;
    }
};

// A simulated head serving GCHP, ONVIF and VISCA (headsim --onvif --visca) on 127.0.0.1, each on any free port, from its own threads for the lifetime of the object.
class RunningSimHead {
public:
    explicit RunningSimHead(OnvifResponderConfig onvif = {})
        : server_(gchp_config()), onvif_(free_port(onvif), server_), visca_(free_port(ViscaResponderConfig{}), server_)
    {
        thread_ = std::thread([this] { server_.run(); });
    }
    ~RunningSimHead()
    {
        server_.request_stop();
        thread_.join();
    }
    std::string onvif_uri(const std::string& query = "") const
    {
        return "onvif://127.0.0.1:" + std::to_string(onvif_.port()) + query;
    }
    std::string gchp_uri() const { return "tcp://127.0.0.1:" + std::to_string(server_.port()); }
    // The VISCA backend's URI (visca-udp or visca-tcp) naming the head's largest magnification and top speeds, so that
    // zoom positions and drive speed codes mean the same at both ends.
    std::string visca_uri(const std::string& scheme = "visca-udp") const
    {
        const HeadLimits l = default_simulated_limits();
        const auto text = [](double v) { return std::to_string(v); };
        return scheme + "://127.0.0.1:" + std::to_string(visca_.port()) + "?zoom_max=" + text(l[Axis::Zoom].max_deg) +
               "&zoom_max_speed=" + text(l[Axis::Zoom].max_velocity_dps) +
               "&pan_max_speed_dps=" + text(l[Axis::Pan].max_velocity_dps) +
               "&tilt_max_speed_dps=" + text(l[Axis::Tilt].max_velocity_dps);
    }
    std::uint16_t onvif_port() const { return onvif_.port(); }
    OnvifResponder& responder() { return onvif_; }

private:
    static HeadServerConfig gchp_config()
    {
        HeadServerConfig c;
        c.port = 0;
        return c;
    }
    template <class Config>
    static Config free_port(Config c)
    {
        c.port = 0;
        return c;
    }
    HeadServer server_;
    OnvifResponder onvif_;
    ViscaResponder visca_;
    std::thread thread_;
};

// A TCP port on 127.0.0.1 that listens but never accepts: connecting succeeds, the greeting
// never comes (a stuck head), for the lifetime of the object.
class StuckListener {
public:
    StuckListener() : fd_(::socket(AF_INET, SOCK_STREAM, 0))
    {
        sockaddr_in a{};
        a.sin_family = AF_INET;
        a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
        if (::bind(fd_.get(), reinterpret_cast<sockaddr*>(&a), sizeof a) != 0 || ::listen(fd_.get(), 4) != 0)
            throw std::runtime_error("cannot listen on loopback");
        socklen_t len = sizeof a;
        ::getsockname(fd_.get(), reinterpret_cast<sockaddr*>(&a), &len);
        port_ = ntohs(a.sin_port);
    }
    std::string uri() const { return "tcp://127.0.0.1:" + std::to_string(port_); }

private:
    net::Fd fd_;
    std::uint16_t port_ = 0;
};

// The longest of `count` calls of `call(i)`, in microseconds: what a caller that must never
// wait on the network waited at worst.
inline double longest_call_us(int count, const std::function<void(int)>& call)
{
    double worst_us = 0.0;
    for (int i = 0; i < count; ++i) {
        const auto start = std::chrono::steady_clock::now();
        call(i);
        worst_us = std::max(
            worst_us, std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count());
    }
    return worst_us;
}

// A program started with its output on pipes, whose read ends are non-blocking.
struct Spawned {
    pid_t pid = 0;
    net::Fd out;
    net::Fd err;  // only when asked for
};

// Starts `path` with `args` and `env` added to the environment; throws when it cannot.
inline Spawned spawn(const std::string& path, std::vector<std::string> args, const std::vector<std::string>& env,
                     bool capture_err)
{
    args.insert(args.begin(), path);
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    std::vector<std::string> env_text(env);
    for (char** e = environ; *e; ++e) env_text.emplace_back(*e);
    std::vector<char*> envp;
    for (auto& e : env_text) envp.push_back(e.data());
    envp.push_back(nullptr);
    int out[2], err[2] = {-1, -1};
    if (::pipe(out) != 0 || (capture_err && ::pipe(err) != 0)) throw std::runtime_error("pipe");
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, out[1], STDOUT_FILENO);
    posix_spawn_file_actions_addclose(&actions, out[0]);
    if (capture_err) {
        posix_spawn_file_actions_adddup2(&actions, err[1], STDERR_FILENO);
        posix_spawn_file_actions_addclose(&actions, err[0]);
    }
    Spawned s;
    const int rc = ::posix_spawn(&s.pid, path.c_str(), &actions, nullptr, argv.data(), envp.data());
    posix_spawn_file_actions_destroy(&actions);
    ::close(out[1]);
    s.out = net::Fd(out[0]);
    if (capture_err) {
        ::close(err[1]);
        s.err = net::Fd(err[0]);
    }
    if (rc != 0) throw std::runtime_error("cannot run " + path);
    net::set_nonblocking(s.out.get());
    if (s.err) net::set_nonblocking(s.err.get());
    return s;
}

// A TCP connection to 127.0.0.1:port from the loopback address `source` (any 127.x.y.z
// works on Linux), so one test can play clients on many addresses.
inline net::Fd connect_from(const char* source, std::uint16_t port)
{
    net::Fd fd(::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0));
    sockaddr_in from{};
    from.sin_family = AF_INET;
    if (!fd || ::inet_pton(AF_INET, source, &from.sin_addr) != 1 ||
        ::bind(fd.get(), reinterpret_cast<sockaddr*>(&from), sizeof from) != 0)
        throw net::NetError(std::string("cannot bind a client socket to ") + source);
    sockaddr_in to{};
    to.sin_family = AF_INET;
    to.sin_port = htons(port);
    to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (::connect(fd.get(), reinterpret_cast<sockaddr*>(&to), sizeof to) != 0)
        throw net::NetError(std::string("cannot connect from ") + source);
    net::set_nonblocking(fd.get());
    return fd;
}

// A blocking line client with deadlines, to talk to the server byte by byte.
class LineClient {
public:
    explicit LineClient(std::uint16_t port, const char* source = "127.0.0.1") : fd_(connect_from(source, port)) {}
    void send(std::string_view text)
    {
        net::send_all(fd_.get(), std::span<const char>(text.data(), text.size()), net::Clock::now() + 2s);
    }
    std::optional<std::string> line(std::chrono::milliseconds timeout = 2000ms)
    {
        return reader_.read_line(fd_.get(), net::Clock::now() + timeout);
    }
    std::string request(std::string_view text)
    {
        send(std::string(text) + "\n");
        auto l = line();
        return l ? *l : std::string("<timeout>");
    }
    int fd() const { return fd_.get(); }
    void close() { fd_.reset(); }

private:
    net::Fd fd_;
    net::LineReader reader_{8192};
};

// Accepts connections on 127.0.0.1, sends each one `script` and closes it: a head that
// connects and then fails, or one that sends a line of a chosen length. With `hold_open` it
// sends the script a moment after accepting (once a request has arrived, unread) and keeps
// the connection open: a camera that answers garbage, or nothing when the script is empty.
class ScriptedServer {
public:
    explicit ScriptedServer(std::string script, bool hold_open = false)
        : script_(std::move(script)), hold_open_(hold_open)
    {
        listener_ = net::Fd(::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0));
        sockaddr_in a{};
        a.sin_family = AF_INET;
        a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
        socklen_t len = sizeof a;
        if (::bind(listener_.get(), reinterpret_cast<sockaddr*>(&a), sizeof a) != 0 ||
            ::listen(listener_.get(), 16) != 0 ||
            ::getsockname(listener_.get(), reinterpret_cast<sockaddr*>(&a), &len) != 0)
            throw net::NetError("cannot listen on 127.0.0.1");
        port_ = ntohs(a.sin_port);
        thread_ = std::thread([this] { run(); });
    }
    ~ScriptedServer()
    {
        stop_ = true;
        thread_.join();
    }
    std::string uri() const { return "tcp://127.0.0.1:" + std::to_string(port_); }
    std::uint16_t port() const { return port_; }
    int accepted() const { return accepted_; }

private:
    void run()
    {
        std::vector<net::Fd> held;
        while (!stop_) {
            pollfd p{listener_.get(), POLLIN, 0};
            if (::poll(&p, 1, 20) <= 0) continue;
            net::Fd c(::accept4(listener_.get(), nullptr, nullptr, SOCK_CLOEXEC));
            if (!c) continue;
            ++accepted_;
            if (hold_open_) std::this_thread::sleep_for(20ms);
            [[maybe_unused]] const ssize_t n = ::send(c.get(), script_.data(), script_.size(), MSG_NOSIGNAL);
            if (hold_open_) held.push_back(std::move(c));
        }
    }

    std::string script_;
    bool hold_open_ = false;
    net::Fd listener_;
    std::uint16_t port_ = 0;
    std::atomic<bool> stop_{false};
    std::atomic<int> accepted_{0};
    std::thread thread_;
};

// An ONVIF camera on loopback that answers every request with `reply` (nothing when empty).
class HttpScriptedServer : public ScriptedServer {
public:
    explicit HttpScriptedServer(std::string reply) : ScriptedServer(std::move(reply), true) {}
    std::string uri(const std::string& query = "") const
    {
        return "onvif://127.0.0.1:" + std::to_string(port()) + query;
    }
};

}  // namespace gc::headctl::testing
