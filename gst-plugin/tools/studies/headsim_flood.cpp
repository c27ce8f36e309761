// Benchmark, not a test: one authenticated client's STATUS round trip to a headsim process
// while a crowd of connections without the token (1000 by default, from addresses spread over
// 127.0.0.0/8, eight per address) sits idle, trickles a byte a second, guesses tokens or
// sends requests, and reconnects whenever it is dropped or refused. Prints the round trip's
// percentiles without and with the crowd, and what the crowd met.
//
//   build/gst-plugin/tools/studies/headsim_flood [--connections N] [--seconds S] [--headsim PATH]
#include "headctl/net.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

extern char** environ;

namespace {

using namespace gc::headctl;
using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;

constexpr const char* kToken = "bench-Token-7f3a";

struct Options {
    int connections = 1000;
    double seconds = 10.0;
    std::string headsim;
};

Options parse_options(int argc, char** argv)
{
    Options o;
    const char* root = std::getenv("GESTURECAM_BUILD_ROOT");
    o.headsim = root ? std::string(root) + "/gst-plugin/tools/headsim" : "";
    if (o.headsim.empty()) {  // beside the build tree this program sits in
        char self[4096] = {};
        const ssize_t n = ::readlink("/proc/self/exe", self, sizeof self - 1);
        const std::string dir = n > 0 ? std::string(self, static_cast<std::size_t>(n)) : std::string("./x");
        o.headsim = dir.substr(0, dir.rfind('/')) + "/../headsim";
    }
    for (int i = 1; i + 1 < argc; i += 2) {
        const std::string key = argv[i];
        if (key == "--connections")
            o.connections = std::max(1, std::atoi(argv[i + 1]));
        else if (key == "--seconds")
            o.seconds = std::max(1.0, std::atof(argv[i + 1]));
        else if (key == "--headsim")
            o.headsim = argv[i + 1];
        else
            throw std::invalid_argument("unknown option " + key);
    }
    return o;
}

// Every connection is a descriptor: the soft limit goes up to the hard one.
void raise_descriptor_limit(int needed)
{
    rlimit l{};
    ::getrlimit(RLIMIT_NOFILE, &l);
    l.rlim_cur = l.rlim_max;
    ::setrlimit(RLIMIT_NOFILE, &l);
    if (l.rlim_cur < static_cast<rlim_t>(needed))
        std::fprintf(stderr, "descriptor limit %llu is below the %d needed: raise it with ulimit -n\n",
                     static_cast<unsigned long long>(l.rlim_cur), needed);
}

// headsim on 127.0.0.1 with the token in a file; its pid and port.
struct Headsim {
    pid_t pid = 0;
    std::uint16_t port = 0;
    std::string token_file;
};

Headsim start_headsim(const std::string& path)
{
    Headsim h;
    char name[] = "/tmp/gesturecam-bench-token-XXXXXX";
    const int fd = ::mkstemp(name);
    const std::string text = std::string(kToken) + "\n";
    if (fd < 0 || ::write(fd, text.data(), text.size()) != static_cast<ssize_t>(text.size()))
        throw std::runtime_error("cannot write the token file");
    ::close(fd);
    h.token_file = name;
    int out[2];
    if (::pipe(out) != 0) throw std::runtime_error("pipe");
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, out[1], STDOUT_FILENO);
    posix_spawn_file_actions_addclose(&actions, out[0]);
    std::vector<std::string> args{path, "--listen", "127.0.0.1:0", "--token-file", h.token_file};
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    const int rc = ::posix_spawn(&h.pid, path.c_str(), &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    ::close(out[1]);
    net::Fd read_end(out[0]);
    if (rc != 0) throw std::runtime_error("cannot run " + path);
    net::set_nonblocking(read_end.get());
    net::LineReader reader(256);
    const auto line = reader.read_line(read_end.get(), Clock::now() + 5s);
    if (!line || line->rfind(':') == std::string::npos) throw std::runtime_error("headsim did not start");
    h.port = static_cast<std::uint16_t>(std::stoi(line->substr(line->rfind(':') + 1)));
    return h;
}

void stop_headsim(const Headsim& h)
{
    ::kill(h.pid, SIGTERM);
    ::waitpid(h.pid, nullptr, 0);
    ::unlink(h.token_file.c_str());
}

// What the crowd met, counted by its thread.
struct CrowdCounts {
    std::atomic<long> connects{0}, greeted{0}, refused{0}, closed_by_server{0}, wrong_token_replies{0};
};

// The crowd: one thread, one poll() loop over every hostile connection.
class Crowd {
public:
    Crowd(std::uint16_t port, int size) : port_(port), slots_(static_cast<std::size_t>(size)) {}
    void run(Clock::time_point end);
    CrowdCounts counts;

private:
    struct Slot {
        net::Fd fd;
        std::string source;
        Clock::time_point next_action;
        std::string seen;  // what the server said, for counting
    };
    enum Kind { Idle, Trickle, Guess, Ask };
    void open(std::size_t i);
    void act(std::size_t i, Clock::time_point now);
    void read(std::size_t i);

    std::uint16_t port_;
    std::vector<Slot> slots_;
};

// Eight connections per address, the addresses spread over 127.0.0.0/8.
std::string source_of(std::size_t i)
{
    const std::size_t a = i / 8;
    return "127." + std::to_string(1 + a % 200) + "." + std::to_string(a / 200 % 250) + "." +
           std::to_string(2 + a % 250);
}

void Crowd::open(std::size_t i)
{
    Slot& s = slots_[i];
    s.fd = net::Fd(::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0));
    s.source = source_of(i);
    s.seen.clear();
    sockaddr_in from{}, to{};
    from.sin_family = to.sin_family = AF_INET;
    ::inet_pton(AF_INET, s.source.c_str(), &from.sin_addr);
    to.sin_port = htons(port_);
    to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (::bind(s.fd.get(), reinterpret_cast<sockaddr*>(&from), sizeof from) != 0 ||
        (::connect(s.fd.get(), reinterpret_cast<sockaddr*>(&to), sizeof to) != 0 && errno != EINPROGRESS)) {
        s.fd.reset();
        s.next_action = Clock::now() + 100ms;
        return;
    }
    ++counts.connects;
    s.next_action = Clock::now() + 50ms;
}

// Each kind does its part of the attack when its time comes.
void Crowd::act(std::size_t i, Clock::time_point now)
{
    Slot& s = slots_[i];
    std::string text;
    switch (static_cast<Kind>(i % 4)) {
    case Idle:
        s.next_action = now + 1h;
        return;
    case Trickle:
        text = "S";
        s.next_action = now + 1s;
        break;
    case Guess:
        text = "AUTH guess" + std::to_string(now.time_since_epoch().count() % 100000) + "\n";
        s.next_action = now + 20ms;
        break;
    case Ask:
        text = "#1 STATUS\n";
        s.next_action = now + 20ms;
        break;
    }
    [[maybe_unused]] const ssize_t n = ::send(s.fd.get(), text.data(), text.size(), MSG_NOSIGNAL | MSG_DONTWAIT);
}

void Crowd::read(std::size_t i)
{
    Slot& s = slots_[i];
    char buffer[2048];
    const ssize_t n = ::recv(s.fd.get(), buffer, sizeof buffer, MSG_DONTWAIT);
    if (n > 0) {
        const bool first = s.seen.empty();
        s.seen.append(buffer, static_cast<std::size_t>(n));
        if (first) (s.seen.rfind("HELLO", 0) == 0 ? counts.greeted : counts.refused)++;
        for (std::size_t at = 0; (at = s.seen.find("ERR 403", at)) != std::string::npos; at += 7)
            ++counts.wrong_token_replies;
        s.seen = s.seen.substr(0, 8);  // the first reply's kind is all that is kept
        return;
    }
    if (n == 0 || (errno != EAGAIN && errno != EWOULDBLOCK)) {
        if (s.seen.rfind("HELLO", 0) == 0) ++counts.closed_by_server;
        s.fd.reset();
        s.next_action = Clock::now() + 100ms;  // then it comes back
    }
}

void Crowd::run(Clock::time_point end)
{
    for (std::size_t i = 0; i < slots_.size(); ++i) open(i);
    std::vector<pollfd> fds(slots_.size());
    while (Clock::now() < end) {
        const auto now = Clock::now();
        for (std::size_t i = 0; i < slots_.size(); ++i) {
            if (!slots_[i].fd && now >= slots_[i].next_action)
                open(i);
            else if (slots_[i].fd && now >= slots_[i].next_action)
                act(i, now);
            fds[i] = {slots_[i].fd ? slots_[i].fd.get() : -1, POLLIN, 0};
        }
        ::poll(fds.data(), fds.size(), 10);
        for (std::size_t i = 0; i < slots_.size(); ++i)
            if (fds[i].revents) read(i);
    }
}

// A connection of the token holder, from 127.0.0.1, authenticated.
class TokenHolder {
public:
    explicit TokenHolder(std::uint16_t port)
        : fd_(net::connect_to("127.0.0.1", port, net::Transport::Tcp, Clock::now() + 5s))
    {
        const auto greeting = reader_.read_line(fd_.get(), Clock::now() + 5s);
        if (!greeting || greeting->rfind("HELLO", 0) != 0)
            throw std::runtime_error("not greeted: " + greeting.value_or("<timeout>"));
        if (request(std::string("AUTH ") + kToken) != "OK") throw std::runtime_error("the token holder was refused");
    }
    std::string request(const std::string& line)
    {
        const std::string text = line + "\n";
        net::send_all(fd_.get(), std::span<const char>(text.data(), text.size()), Clock::now() + 5s);
        return reader_.read_line(fd_.get(), Clock::now() + 5s).value_or("<timeout>");
    }

private:
    net::Fd fd_;
    net::LineReader reader_{1024};
};

// How long a new token holder takes from connecting to its first state (ms), one every
// 200 ms until `end`; and how many were not served.
std::vector<double> new_holders(std::uint16_t port, Clock::time_point end, int& failed)
{
    std::vector<double> ms;
    while (Clock::now() + 200ms < end) {
        const auto start = Clock::now();
        try {
            TokenHolder holder(port);
            if (holder.request("STATUS").rfind("OK STATE", 0) != 0) throw std::runtime_error("no state");
            ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - start).count());
        } catch (const std::exception& e) {
            std::fprintf(stderr, "new token holder not served: %s\n", e.what());
            ++failed;
        }
        std::this_thread::sleep_until(start + 200ms);
    }
    return ms;
}

// The token holder's STATUS round trips (ms), one every 5 ms for `duration`.
std::vector<double> measure(std::uint16_t port, std::chrono::milliseconds duration)
{
    TokenHolder holder(port);
    auto request = [&](const std::string& line) { return holder.request(line); };
    std::vector<double> ms;
    for (const auto end = Clock::now() + duration; Clock::now() < end;) {
        const auto start = Clock::now();
        const std::string reply = request("STATUS");
        if (reply.rfind("OK STATE", 0) != 0) throw std::runtime_error("STATUS answered " + reply);
        ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - start).count());
        std::this_thread::sleep_until(start + 5ms);
    }
    return ms;
}

void print_round_trips(const char* what, std::vector<double> ms)
{
    if (ms.empty()) {
        std::printf("%-28s none\n", what);
        return;
    }
    std::sort(ms.begin(), ms.end());
    auto at = [&](double q) { return ms[std::min(ms.size() - 1, static_cast<std::size_t>(q * ms.size()))]; };
    std::printf("%-28s %6zu round trips  p50 %7.3f ms  p99 %7.3f ms  max %7.3f ms\n", what, ms.size(), at(0.5),
                at(0.99), ms.back());
}

}  // namespace

int main(int argc, char** argv)
{
    try {
        const Options o = parse_options(argc, argv);
        raise_descriptor_limit(o.connections + 64);
        ::signal(SIGPIPE, SIG_IGN);
        const Headsim head = start_headsim(o.headsim);
        print_round_trips("alone:", measure(head.port, 1000ms));
        Crowd crowd(head.port, o.connections);
        const auto end =
            Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(o.seconds));
        std::thread attack([&] { crowd.run(end); });
        std::this_thread::sleep_for(500ms);  // the crowd in place
        int not_served = 0;
        std::vector<double> logins;
        std::thread newcomers([&] { logins = new_holders(head.port, end, not_served); });
        const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(end - Clock::now()) - 200ms;
        std::vector<double> under;
        try {
            under = measure(head.port, left);
        } catch (const std::exception& e) {
            std::printf("the token holder's connection failed under the crowd: %s\n", e.what());
        }
        newcomers.join();
        attack.join();
        char label[64];
        std::snprintf(label, sizeof label, "with %d hostile:", o.connections);
        print_round_trips(label, under);
        print_round_trips("new holder, connect to state:", logins);
        std::printf("new token holders not served: %d\n", not_served);
        const CrowdCounts& c = crowd.counts;
        std::printf("crowd: %ld connections, %ld greeted, %ld refused (503), %ld dropped by the server, "
                    "%ld wrong-token replies\n",
                    c.connects.load(), c.greeted.load(), c.refused.load(), c.closed_by_server.load(),
                    c.wrong_token_replies.load());
        std::fflush(stdout);
        stop_headsim(head);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "headsim_flood: %s\n", e.what());
        return 1;
    }
    return 0;
}
