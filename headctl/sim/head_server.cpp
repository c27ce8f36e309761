#include "headctl/sim/head_server.hpp"

#include "headctl/token.hpp"

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
#include <unordered_map>

namespace gc::headctl {

struct HeadServer::Client {
    net::Fd fd;
    std::string peer;         // address:port, for the log
    std::string address;      // what it is counted and throttled under (address_key)
    std::string unread;       // received, not yet handled (the rest of a chunk behind a waiting AUTH)
    std::string input;        // the unfinished line
    std::string output;       // replies not yet accepted by the socket
    bool discarding = false;  // inside an over-long line: drop bytes until its '\n'
    bool authenticated = false;
    int auth_failures = 0;
    Clock::time_point auth_deadline;   // not authenticated by then: dropped
    std::optional<Request> held_auth;  // an AUTH waiting for its address's delay to pass
    bool closing = false;              // close once output is flushed
    bool dead = false;                 // close now
};

namespace {

constexpr int kMaxAcceptsPerWakeUp = 16;  // then the served clients get their turn
constexpr auto kAcceptPause = std::chrono::milliseconds(100);

std::string errno_text(const char* what) { return std::string(what) + ": " + std::strerror(errno); }

std::string peer_text(const sockaddr_storage& addr)
{
    char text[INET6_ADDRSTRLEN] = "?";
    std::uint16_t port = 0;
    if (addr.ss_family == AF_INET) {
        const auto& a = reinterpret_cast<const sockaddr_in&>(addr);
        ::inet_ntop(AF_INET, &a.sin_addr, text, sizeof text);
        port = ntohs(a.sin_port);
    } else if (addr.ss_family == AF_INET6) {
        const auto& a = reinterpret_cast<const sockaddr_in6&>(addr);
        ::inet_ntop(AF_INET6, &a.sin6_addr, text, sizeof text);
        port = ntohs(a.sin6_port);
    }
    return std::string(text) + ":" + std::to_string(port);
}

}  // namespace

bool is_loopback_address(const std::string& host)
{
    in_addr v4{};
    in6_addr v6{};
    if (::inet_pton(AF_INET, host.c_str(), &v4) == 1) return (ntohl(v4.s_addr) >> 24) == 127;
    if (::inet_pton(AF_INET6, host.c_str(), &v6) == 1)
        return IN6_IS_ADDR_LOOPBACK(&v6) || (IN6_IS_ADDR_V4MAPPED(&v6) && v6.s6_addr[12] == 127);
    return false;
}

socklen_t numeric_address(const std::string& host, std::uint16_t port, sockaddr_storage& addr)
{
    addr = {};
    auto* v4 = reinterpret_cast<sockaddr_in*>(&addr);
    auto* v6 = reinterpret_cast<sockaddr_in6*>(&addr);
    if (::inet_pton(AF_INET, host.c_str(), &v4->sin_addr) == 1) {
        v4->sin_family = AF_INET;
        v4->sin_port = htons(port);
        return sizeof *v4;
    }
    if (::inet_pton(AF_INET6, host.c_str(), &v6->sin6_addr) == 1) {
        v6->sin6_family = AF_INET6;
        v6->sin6_port = htons(port);
        return sizeof *v6;
    }
    throw std::invalid_argument("listen address '" + host + "' is not a numeric IPv4 or IPv6 address");
}

std::uint16_t bound_port(int fd)
{
    sockaddr_storage addr{};
    socklen_t len = sizeof addr;
    ::getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len);
    return ntohs(addr.ss_family == AF_INET ? reinterpret_cast<sockaddr_in&>(addr).sin_port
                                           : reinterpret_cast<sockaddr_in6&>(addr).sin6_port);
}

HeadServer::HeadServer(const HeadServerConfig& config)
    : config_(config), model_(config.model), throttle_(config.auth_delay_initial, config.auth_delay_max),
      start_(Clock::now())
{
    if (config_.max_clients == 0) throw std::invalid_argument("the client cap must be at least 1");
    if (config_.max_unauthenticated == 0 || config_.max_unauthenticated_per_address == 0)
        throw std::invalid_argument("the caps on unauthenticated connections must be at least 1");
    if (config_.auth_timeout.count() <= 0 || config_.auth_delay_initial.count() <= 0)
        throw std::invalid_argument("the authentication timeout and delay must be > 0");
    if (!config_.token.empty()) check_token(config_.token);

    sockaddr_storage addr{};
    const socklen_t addr_len = numeric_address(config_.host, config_.port, addr);
    if (config_.token.empty() && !config_.allow_remote_without_token && !is_loopback_address(config_.host))
        throw std::invalid_argument("refusing to listen on " + config_.host +
                                    " without a token: anyone who reaches it could move the head (give a token, "
                                    "or allow remote clients without one: headsim --allow-remote)");
    listener_ = net::Fd(::socket(addr.ss_family, SOCK_STREAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0));
    if (!listener_) throw std::runtime_error(errno_text("socket"));
    const int one = 1;
    ::setsockopt(listener_.get(), SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
    if (::bind(listener_.get(), reinterpret_cast<sockaddr*>(&addr), addr_len) != 0)
        throw std::runtime_error("cannot bind " + config_.host + ":" + std::to_string(config_.port) + ": " +
                                 std::strerror(errno));
    // A deep queue: a crowd of connections must not keep a client out before it is accepted.
    if (::listen(listener_.get(), SOMAXCONN) != 0) throw std::runtime_error(errno_text("listen"));
    port_ = bound_port(listener_.get());

    int pipe_fds[2];
    if (::pipe2(pipe_fds, O_CLOEXEC | O_NONBLOCK) != 0) throw std::runtime_error(errno_text("pipe"));
    wake_read_ = net::Fd(pipe_fds[0]);
    wake_write_ = net::Fd(pipe_fds[1]);
}

HeadServer::~HeadServer() = default;

void HeadServer::request_stop() noexcept
{
    const char byte = 1;
    [[maybe_unused]] const ssize_t n = ::write(wake_write_.get(), &byte, 1);
}

void HeadServer::with_model(const std::function<void(HeadModel&, double)>& f)
{
    std::lock_guard lock(model_mutex_);
    f(model_, now_s());
}

double HeadServer::now_s() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }

void HeadServer::log(const std::string& peer, const std::string& what) const
{
    if (config_.verbose) std::cerr << "headsim: " << peer << " " << what << "\n";
}

std::size_t HeadServer::count_clients(bool authenticated, const std::string* address) const
{
    return static_cast<std::size_t>(std::count_if(clients_.begin(), clients_.end(), [&](const auto& c) {
        return !c->dead && c->authenticated == authenticated && (!address || c->address == *address);
    }));
}

// Until the next authentication deadline, held AUTH or end of an accept pause; -1: none.
int HeadServer::poll_timeout_ms(Clock::time_point now) const
{
    auto next = Clock::time_point::max();
    if (accept_paused_until_ > now) next = accept_paused_until_;
    for (const auto& c : clients_) {
        if (c->authenticated) continue;
        next = std::min(next, c->auth_deadline);
        if (c->held_auth) next = std::min(next, throttle_.next_check(c->address));
    }
    if (next == Clock::time_point::max()) return -1;
    const auto ms = std::chrono::ceil<std::chrono::milliseconds>(next - now).count();
    return static_cast<int>(std::clamp<long long>(ms, 0, 60'000));
}

void HeadServer::run()
{
    for (;;) {
        poll_set_.clear();
        poll_set_.push_back({wake_read_.get(), POLLIN, 0});
        poll_set_.push_back(
            {listener_.get(), static_cast<short>(Clock::now() >= accept_paused_until_ ? POLLIN : 0), 0});
        for (const auto& c : clients_) {
            short events = 0;
            // A client that does not read its replies is not read either (back-pressure); one
            // whose AUTH waits is not read until it is checked, only watched for hanging up.
            if (c->held_auth)
                events |= POLLRDHUP;
            else if (!c->closing && c->output.size() < config_.max_pending_output)
                events |= POLLIN;
            if (!c->output.empty()) events |= POLLOUT;
            poll_set_.push_back({c->fd.get(), events, 0});
        }
        const int n = ::poll(poll_set_.data(), poll_set_.size(), poll_timeout_ms(Clock::now()));
        if (n < 0) {
            if (errno == EINTR) continue;
            throw std::runtime_error(errno_text("poll"));
        }
        if (poll_set_[0].revents) break;
        for (std::size_t i = 0; i < clients_.size(); ++i) {
            Client& c = *clients_[i];
            const short ev = poll_set_[i + 2].revents;
            if (ev & (POLLERR | POLLNVAL)) c.dead = true;
            if (c.held_auth && (ev & (POLLRDHUP | POLLHUP))) c.dead = true;
            if (!c.dead && !c.held_auth && (ev & (POLLIN | POLLHUP))) read_from(c);
            if (!c.dead && (ev & POLLOUT)) flush(c);
        }
        expire_and_release(Clock::now());
        const auto gone = std::remove_if(clients_.begin(), clients_.end(), [this](const auto& c) {
            const bool remove = c->dead || (c->closing && c->output.empty());
            if (remove) log(c->peer, "disconnected");
            return remove;
        });
        clients_.erase(gone, clients_.end());
        if (poll_set_[1].revents & POLLIN) accept_clients();
    }
    clients_.clear();
}

// Drops the connections whose time to authenticate is up, and checks the AUTHs whose
// address's delay has passed (one per address: a failure starts the next delay).
void HeadServer::expire_and_release(Clock::time_point now)
{
    for (const auto& client : clients_) {
        Client& c = *client;
        if (c.dead || c.authenticated) continue;
        if (now >= c.auth_deadline) {
            reply(c, make_error_reply(std::nullopt, ErrorCode::AuthRequired,
                                      "not authenticated within " + std::to_string(config_.auth_timeout.count()) +
                                          " ms; closing"));
            flush(c);
            c.dead = true;
            log(c.peer, "dropped: not authenticated in time");
            continue;
        }
        if (c.held_auth && now >= throttle_.next_check(c.address)) {
            const Request auth = *c.held_auth;
            c.held_auth.reset();
            authenticate(c, auth);
            process_input(c);
            flush(c);
        }
    }
}

void HeadServer::accept_clients()
{
    for (int accepted = 0; accepted < kMaxAcceptsPerWakeUp; ++accepted) {
        sockaddr_storage addr{};
        socklen_t len = sizeof addr;
        net::Fd fd(::accept4(listener_.get(), reinterpret_cast<sockaddr*>(&addr), &len, SOCK_NONBLOCK | SOCK_CLOEXEC));
        if (!fd) {
            if (errno == EINTR || errno == ECONNABORTED) continue;
            // Out of descriptors: the pending connection stays queued; polling the listener
            // again at once would only spin.
            if (errno == EMFILE || errno == ENFILE || errno == ENOBUFS || errno == ENOMEM) {
                accept_paused_until_ = Clock::now() + kAcceptPause;
                log("listener", errno_text("accept"));
            }
            return;
        }
        admit(fd, address_key(addr), peer_text(addr));
    }
}

void HeadServer::admit(net::Fd& fd, const std::string& address, const std::string& peer)
{
    if (count_clients(true) >= config_.max_clients) {
        refuse(fd, peer, "too many clients (at most " + std::to_string(config_.max_clients) + ")");
        return;
    }
    const bool needs_auth = !config_.token.empty();
    if (needs_auth) {
        const std::size_t per_address = config_.max_unauthenticated_per_address;
        if (count_clients(false, &address) >= per_address) {
            refuse(fd, peer,
                   "too many unauthenticated connections from " + address + " (at most " + std::to_string(per_address) +
                       ")");
            return;
        }
        if (count_clients(false) >= config_.max_unauthenticated) drop_one_unauthenticated();
    }
    auto c = std::make_unique<Client>();
    c->fd = std::move(fd);
    c->peer = peer;
    c->address = address;
    c->authenticated = !needs_auth;
    c->auth_deadline = Clock::now() + config_.auth_timeout;
    Greeting g;
    g.caps.auth_required = needs_auth;
    g.caps.presets = true;
    c->output = format_greeting(g) + "\n";
    flush(*c);
    log(peer, "connected");
    clients_.push_back(std::move(c));
}

// Makes room for a newcomer: the oldest connection of the address holding the most
// unauthenticated ones goes, so a crowd from a few addresses pushes out its own members
// first and a client arriving alone keeps its few seconds to authenticate.
void HeadServer::drop_one_unauthenticated()
{
    std::unordered_map<std::string, std::size_t> per_address;
    for (const auto& c : clients_)
        if (!c->dead && !c->authenticated) ++per_address[c->address];
    if (per_address.empty()) return;
    const auto crowded = std::max_element(per_address.begin(), per_address.end(),
                                          [](const auto& a, const auto& b) { return a.second < b.second; });
    const auto victim = std::find_if(clients_.begin(), clients_.end(), [&](const auto& c) {
        return !c->dead && !c->authenticated && c->address == crowded->first;
    });
    log((*victim)->peer, "dropped: too many unauthenticated connections");
    clients_.erase(victim);
}

void HeadServer::refuse(net::Fd& fd, const std::string& peer, const std::string& why)
{
    const std::string line = format_reply(make_error_reply(std::nullopt, ErrorCode::Busy, why)) + "\n";
    [[maybe_unused]] const ssize_t n = ::send(fd.get(), line.data(), line.size(), MSG_NOSIGNAL | MSG_DONTWAIT);
    log(peer, "refused: " + why);
}

void HeadServer::read_from(Client& c)
{
    char chunk[4096];
    const ssize_t n = ::recv(c.fd.get(), chunk, sizeof chunk, 0);
    if (n == 0 || (n < 0 && errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR)) {
        c.dead = true;
        return;
    }
    if (n < 0) return;
    c.unread.append(chunk, static_cast<std::size_t>(n));
    process_input(c);
    flush(c);
}

// Handles the complete lines received, up to an AUTH that has to wait (the rest waits with it).
void HeadServer::process_input(Client& c)
{
    const std::string_view data(c.unread);
    std::size_t used = 0;
    while (used < data.size() && !c.closing && !c.held_auth) {
        const auto nl = data.find('\n', used);
        const std::string_view piece =
            data.substr(used, nl == std::string_view::npos ? std::string_view::npos : nl - used);
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
        used = nl == std::string_view::npos ? data.size() : nl + 1;
    }
    c.unread.erase(0, used);
}

void HeadServer::handle_line(Client& c, std::string_view line)
{
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
    std::lock_guard lock(model_mutex_);
    const double now = now_s();
    try {
        switch (req.command) {
        case Command::Auth:
            if (config_.token.empty()) break;
            if (!c.authenticated && Clock::now() < throttle_.next_check(c.address))
                c.held_auth = req;
            else
                authenticate(c, req);
            return;
        case Command::Status:
            r.body = ReplyBody::State;
            r.state = model_.state(now);
            break;
        case Command::Limits:
            r.body = ReplyBody::Limits;
            r.limits = model_.limits();
            break;
        case Command::MoveAbsolute:
            model_.move_absolute(req.values, now);
            break;
        case Command::MoveRelative:
            model_.move_relative(req.values, now);
            break;
        case Command::MoveVelocity:
            model_.move_velocity(req.values, now);
            break;
        case Command::Stop:
            model_.stop(now);
            break;
        case Command::Home:
            model_.home(now);
            break;
        case Command::PresetSave:
            model_.save_preset(req.preset, now);
            break;
        case Command::PresetRecall:
            model_.recall_preset(req.preset, now);
            break;
        case Command::Quit:
            c.closing = true;
            break;
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

// Checks an AUTH now; a wrong token makes the next one from that address wait.
void HeadServer::authenticate(Client& c, const Request& auth)
{
    if (!same_secret(auth.token, config_.token)) {
        throttle_.failed(c.address, Clock::now());
        if (++c.auth_failures >= config_.max_auth_failures) c.closing = true;
        reply(c, make_error_reply(auth.id, ErrorCode::AuthFailed, "wrong token"));
        log(c.peer, "sent a wrong token");
        return;
    }
    throttle_.succeeded(c.address);
    if (!c.authenticated && count_clients(true) >= config_.max_clients) {
        reply(c, make_error_reply(auth.id, ErrorCode::Busy,
                                  "too many clients (at most " + std::to_string(config_.max_clients) + ")"));
        c.closing = true;
        return;
    }
    c.authenticated = true;
    Reply ok;
    ok.id = auth.id;
    reply(c, ok);
}

void HeadServer::reply(Client& c, const Reply& r)
{
    reply_line_ = format_reply(r);
    c.output += reply_line_;
    c.output += '\n';
}

void HeadServer::flush(Client& c)
{
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
