#include "headctl/head_server.hpp"

#include <arpa/inet.h>
#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <iostream>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <stdexcept>

namespace gc::headctl {

struct HeadServer::Client {
    net::Fd fd;
    std::string peer;
    std::string input;       // the unfinished line
    std::string output;      // replies not yet accepted by the socket
    bool discarding = false; // inside an over-long line: drop bytes until its '\n'
    bool authenticated = false;
    int auth_failures = 0;
    bool closing = false;    // close once output is flushed
    bool dead = false;       // close now
};

namespace {

std::string errno_text(const char* what) { return std::string(what) + ": " + std::strerror(errno); }

// Compares without an early exit, so timing does not reveal how much of a token matched.
bool same_token(std::string_view a, std::string_view b) {
    unsigned diff = a.size() == b.size() ? 0u : 1u;
    for (std::size_t i = 0; i < a.size(); ++i) diff |= static_cast<unsigned>(a[i] ^ (i < b.size() ? b[i] : 0));
    return diff == 0;
}

}  // namespace

HeadServer::HeadServer(const HeadServerConfig& config)
    : config_(config), model_(config.model), start_(Clock::now()) {
    if (config_.max_clients == 0) throw std::invalid_argument("the client cap must be at least 1");
    if (config_.token.size() > kMaxTokenLength ||
        std::any_of(config_.token.begin(), config_.token.end(), [](char c) { return c <= 0x20 || c >= 0x7f; }))
        throw std::invalid_argument("a token is 1 to 64 printable characters without blanks");

    sockaddr_storage addr{};
    socklen_t addr_len = 0;
    auto* v4 = reinterpret_cast<sockaddr_in*>(&addr);
    auto* v6 = reinterpret_cast<sockaddr_in6*>(&addr);
    if (::inet_pton(AF_INET, config_.host.c_str(), &v4->sin_addr) == 1) {
        v4->sin_family = AF_INET;
        v4->sin_port = htons(config_.port);
        addr_len = sizeof *v4;
    } else if (::inet_pton(AF_INET6, config_.host.c_str(), &v6->sin6_addr) == 1) {
        v6->sin6_family = AF_INET6;
        v6->sin6_port = htons(config_.port);
        addr_len = sizeof *v6;
    } else {
        throw std::invalid_argument("listen address '" + config_.host + "' is not a numeric IPv4 or IPv6 address");
    }
    listener_ = net::Fd(::socket(addr.ss_family, SOCK_STREAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0));
    if (!listener_) throw std::runtime_error(errno_text("socket"));
    const int one = 1;
    ::setsockopt(listener_.get(), SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
    if (::bind(listener_.get(), reinterpret_cast<sockaddr*>(&addr), addr_len) != 0)
        throw std::runtime_error("cannot bind " + config_.host + ":" + std::to_string(config_.port) + ": " +
                                 std::strerror(errno));
    if (::listen(listener_.get(), 64) != 0) throw std::runtime_error(errno_text("listen"));
    socklen_t len = sizeof addr;
    ::getsockname(listener_.get(), reinterpret_cast<sockaddr*>(&addr), &len);
    port_ = ntohs(addr.ss_family == AF_INET ? v4->sin_port : v6->sin6_port);

    int pipe_fds[2];
    if (::pipe2(pipe_fds, O_CLOEXEC | O_NONBLOCK) != 0) throw std::runtime_error(errno_text("pipe"));
    wake_read_ = net::Fd(pipe_fds[0]);
    wake_write_ = net::Fd(pipe_fds[1]);
}

HeadServer::~HeadServer() = default;

void HeadServer::request_stop() noexcept {
    const char byte = 1;
    [[maybe_unused]] const ssize_t n = ::write(wake_write_.get(), &byte, 1);
}

double HeadServer::now_s() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }

void HeadServer::run() {
    for (;;) {
        poll_set_.clear();
        poll_set_.push_back({wake_read_.get(), POLLIN, 0});
        poll_set_.push_back({listener_.get(), POLLIN, 0});
        for (const auto& c : clients_) {
            short events = 0;
            // A client that does not read its replies is not read either (back-pressure).
            if (!c->closing && c->output.size() < config_.max_pending_output) events |= POLLIN;
            if (!c->output.empty()) events |= POLLOUT;
            poll_set_.push_back({c->fd.get(), events, 0});
        }
        const int n = ::poll(poll_set_.data(), poll_set_.size(), -1);
        if (n < 0) {
            if (errno == EINTR) continue;
            throw std::runtime_error(errno_text("poll"));
        }
        if (poll_set_[0].revents) break;
        for (std::size_t i = 0; i < clients_.size(); ++i) {
            Client& c = *clients_[i];
            const short ev = poll_set_[i + 2].revents;
            if (ev & (POLLERR | POLLNVAL)) c.dead = true;
            if (!c.dead && (ev & (POLLIN | POLLHUP))) read_from(c);
            if (!c.dead && (ev & POLLOUT)) flush(c);
        }
        const auto gone = std::remove_if(clients_.begin(), clients_.end(), [this](const auto& c) {
            const bool remove = c->dead || (c->closing && c->output.empty());
            if (remove && config_.verbose) std::cerr << "headsim: " << c->peer << " disconnected\n";
            return remove;
        });
        clients_.erase(gone, clients_.end());
        if (poll_set_[1].revents & POLLIN) accept_clients();
    }
    clients_.clear();
}

void HeadServer::accept_clients() {
    for (;;) {
        sockaddr_storage addr{};
        socklen_t len = sizeof addr;
        net::Fd fd(::accept4(listener_.get(), reinterpret_cast<sockaddr*>(&addr), &len, SOCK_NONBLOCK | SOCK_CLOEXEC));
        if (!fd) {
            if (errno == EINTR || errno == ECONNABORTED) continue;
            return;  // EAGAIN, or out of descriptors: try again on the next wake-up
        }
        char text[INET6_ADDRSTRLEN] = "?";
        std::uint16_t peer_port = 0;
        if (addr.ss_family == AF_INET) {
            const auto* a = reinterpret_cast<sockaddr_in*>(&addr);
            ::inet_ntop(AF_INET, &a->sin_addr, text, sizeof text);
            peer_port = ntohs(a->sin_port);
        } else if (addr.ss_family == AF_INET6) {
            const auto* a = reinterpret_cast<sockaddr_in6*>(&addr);
            ::inet_ntop(AF_INET6, &a->sin6_addr, text, sizeof text);
            peer_port = ntohs(a->sin6_port);
        }
        const std::string peer = std::string(text) + ":" + std::to_string(peer_port);
        if (clients_.size() >= config_.max_clients) {
            const std::string line = format_reply(make_error_reply(
                                         std::nullopt, ErrorCode::Busy,
                                         "too many clients (at most " + std::to_string(config_.max_clients) + ")")) +
                                     "\n";
            [[maybe_unused]] const ssize_t n = ::send(fd.get(), line.data(), line.size(), MSG_NOSIGNAL | MSG_DONTWAIT);
            if (config_.verbose) std::cerr << "headsim: refused " << peer << ": too many clients\n";
            continue;
        }
        auto c = std::make_unique<Client>();
        c->fd = std::move(fd);
        c->peer = peer;
        c->authenticated = config_.token.empty();
        Greeting g;
        g.caps.auth_required = !config_.token.empty();
        c->output = format_greeting(g) + "\n";
        flush(*c);
        if (config_.verbose) std::cerr << "headsim: " << peer << " connected\n";
        clients_.push_back(std::move(c));
    }
}

void HeadServer::read_from(Client& c) {
    char chunk[4096];
    const ssize_t n = ::recv(c.fd.get(), chunk, sizeof chunk, 0);
    if (n == 0 || (n < 0 && errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR)) {
        c.dead = true;
        return;
    }
    if (n < 0) return;
    std::string_view data(chunk, static_cast<std::size_t>(n));
    while (!data.empty() && !c.closing) {
        const auto nl = data.find('\n');
        const std::string_view piece = data.substr(0, nl);
        if (c.discarding) {
            if (nl != std::string_view::npos) c.discarding = false;
        } else if (c.input.size() + piece.size() > kMaxLineLength + 1) {  // +1: a trailing '\r'
            reply(c, make_error_reply(std::nullopt, ErrorCode::LineTooLong,
                                      "line exceeds " + std::to_string(kMaxLineLength) + " bytes; skipped"));
            c.input.clear();
            c.discarding = nl == std::string_view::npos;
        } else {
            c.input.append(piece);
            if (nl != std::string_view::npos) {
                handle_line(c, c.input);
                c.input.clear();
            }
        }
        data = nl == std::string_view::npos ? std::string_view{} : data.substr(nl + 1);
    }
    flush(c);
}

void HeadServer::handle_line(Client& c, std::string_view line) {
    if (line.find_first_not_of(" \t\r") == std::string_view::npos) return;  // blank lines are no requests
    Request req;
    try {
        req = parse_request(line);
    } catch (const ProtocolError& e) {
        // Still echo the id if the line began with a well-formed one.
        const std::optional<std::uint32_t> id = peek_request_id(line);
        reply(c, make_error_reply(id, e.code(), e.what()));
        return;
    }
    Reply r;
    r.id = req.id;
    if (!c.authenticated && req.command != Command::Auth && req.command != Command::Quit) {
        reply(c, make_error_reply(req.id, ErrorCode::AuthRequired, "authenticate first: AUTH <token>"));
        return;
    }
    const double now = now_s();
    try {
        switch (req.command) {
            case Command::Auth:
                if (!config_.token.empty() && !same_token(req.token, config_.token)) {
                    if (++c.auth_failures >= config_.max_auth_failures) c.closing = true;
                    reply(c, make_error_reply(req.id, ErrorCode::AuthFailed, "wrong token"));
                    return;
                }
                c.authenticated = true;
                break;
            case Command::Status:
                r.body = ReplyBody::State;
                r.state = model_.state(now);
                break;
            case Command::Limits:
                r.body = ReplyBody::Limits;
                r.limits = model_.limits();
                break;
            case Command::MoveAbsolute: model_.move_absolute(req.values, now); break;
            case Command::MoveRelative: model_.move_relative(req.values, now); break;
            case Command::MoveVelocity: model_.move_velocity(req.values, now); break;
            case Command::Stop: model_.stop(now); break;
            case Command::Home: model_.home(now); break;
            case Command::Quit: c.closing = true; break;
        }
    } catch (const std::out_of_range& e) {
        reply(c, make_error_reply(req.id, ErrorCode::OutOfRange, e.what()));
        return;
    } catch (const std::exception& e) {
        reply(c, make_error_reply(req.id, ErrorCode::Internal, e.what()));
        return;
    }
    reply(c, r);
}

void HeadServer::reply(Client& c, const Reply& r) {
    reply_line_ = format_reply(r);
    c.output += reply_line_;
    c.output += '\n';
}

void HeadServer::flush(Client& c) {
    while (!c.output.empty()) {
        const ssize_t n = ::send(c.fd.get(), c.output.data(), c.output.size(), MSG_NOSIGNAL | MSG_DONTWAIT);
        if (n > 0) {
            c.output.erase(0, static_cast<std::size_t>(n));
            continue;
        }
        if (n < 0 && errno == EINTR) continue;
        if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) return;
        c.dead = true;
        return;
    }
}

}  // namespace gc::headctl
