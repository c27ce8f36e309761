// The simulated head server: many clients, misbehaving clients, authentication, and the
// headsim executable's clean shutdown on SIGTERM.
#include "test_support.hpp"

#include "headctl/protocol.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <vector>

extern char** environ;

namespace gc::headctl::testing {
namespace {

bool starts_with(const std::string& s, std::string_view prefix) { return s.rfind(prefix, 0) == 0; }

TEST(HeadSim, GreetsAndAnswersRequestsWithTheirIds) {
    RunningServer server;
    LineClient c(server.port());
    EXPECT_EQ(c.line().value_or(""), "HELLO GCHP/1 axes=pan,tilt,verge_l,verge_r caps=abs,rel,vel");
    EXPECT_EQ(c.request("#1 MOVE ABS pan=2"), "OK #1");
    const Reply r = parse_reply(c.request("#2 STATUS"));
    EXPECT_EQ(r.id, 2u);
    EXPECT_EQ(r.body, ReplyBody::State);
    EXPECT_TRUE(starts_with(c.request("#3 LIMITS"), "OK #3 LIMITS pan=-170:170:120:400 "));
    EXPECT_EQ(c.request("#4 MOVE ABS pan=400"), "ERR #4 416 pan target 400 deg is outside [-170, 170]");
    EXPECT_TRUE(starts_with(c.request("#5 MOVE ABS pan=nan"), "ERR #5 422 "));
    EXPECT_TRUE(starts_with(c.request("#6 DANCE"), "ERR #6 404 "));
    EXPECT_TRUE(starts_with(c.request("garbage \x01"), "ERR 400 "));
    EXPECT_EQ(c.request("QUIT"), "OK");
    EXPECT_THROW(c.line(), net::NetError);  // closed after QUIT
}

TEST(HeadSim, RequiresTheTokenBeforeAnythingElse) {
    HeadServerConfig config;
    config.token = "letmein";
    config.max_auth_failures = 2;
    RunningServer server(config);
    LineClient c(server.port());
    EXPECT_EQ(c.line().value_or(""), "HELLO GCHP/1 axes=pan,tilt,verge_l,verge_r caps=abs,rel,vel,auth");
    EXPECT_TRUE(starts_with(c.request("#1 STATUS"), "ERR #1 401 "));
    EXPECT_TRUE(starts_with(c.request("#2 AUTH wrong"), "ERR #2 403 "));
    EXPECT_EQ(c.request("#3 AUTH letmein"), "OK #3");
    EXPECT_TRUE(starts_with(c.request("#4 STATUS"), "OK #4 STATE "));

    LineClient guesser(server.port());
    guesser.line();
    EXPECT_TRUE(starts_with(guesser.request("AUTH a"), "ERR 403"));
    EXPECT_TRUE(starts_with(guesser.request("AUTH b"), "ERR 403"));
    EXPECT_THROW(guesser.line(), net::NetError);  // too many failures: closed
}

TEST(HeadSim, OverLongLinesAreReportedAndSkipped) {
    RunningServer server;
    LineClient c(server.port());
    c.line();
    c.send(std::string(3 * kMaxLineLength, 'A'));  // in pieces: the server sees it grow
    c.send(std::string(5000, 'B') + "\n#9 STATUS\n");
    EXPECT_TRUE(starts_with(c.line().value_or(""), "ERR 413 "));
    EXPECT_TRUE(starts_with(c.line().value_or(""), "OK #9 STATE "));
}

TEST(HeadSim, RefusesClientsBeyondTheCap) {
    HeadServerConfig config;
    config.max_clients = 2;
    RunningServer server(config);
    LineClient a(server.port());
    LineClient b(server.port());
    EXPECT_TRUE(starts_with(a.line().value_or(""), "HELLO"));
    EXPECT_TRUE(starts_with(b.line().value_or(""), "HELLO"));
    LineClient c(server.port());
    EXPECT_TRUE(starts_with(c.line().value_or(""), "ERR 503 "));
    a.close();
    // The freed slot is served again (the server notices the close on its next wake-up).
    bool served = false;
    for (int attempt = 0; attempt < 50 && !served; ++attempt) {
        LineClient d(server.port());
        served = starts_with(d.line().value_or(""), "HELLO");
        if (!served) std::this_thread::sleep_for(20ms);
    }
    EXPECT_TRUE(served);
}

// A good client keeps getting prompt answers while 32 others misbehave in every way.
TEST(HeadSim, MisbehavingClientsDoNotDisturbAGoodOne) {
    HeadServerConfig config;
    config.max_clients = 64;
    config.max_pending_output = 16 * 1024;
    RunningServer server(config);

    std::vector<std::unique_ptr<LineClient>> bad;
    for (int i = 0; i < 32; ++i) bad.push_back(std::make_unique<LineClient>(server.port()));
    const std::string flood_request = "#1 STATUS\n";
    std::string flood;
    for (int i = 0; i < 400; ++i) flood += flood_request;
    for (int i = 0; i < 32; ++i) {
        LineClient& c = *bad[static_cast<std::size_t>(i)];
        switch (i % 4) {
            case 0: c.send("\x01\x02garbage\xff\xfe\n\n\n"); break;  // garbage
            case 1: c.send("#1 MOVE ABS pan=1"); break;                 // half a line, never finished
            case 2: {                                                   // slow reader: never reads
                const int small = 4096;
                ::setsockopt(c.fd(), SOL_SOCKET, SO_RCVBUF, &small, sizeof small);
                ::fcntl(c.fd(), F_SETFL, ::fcntl(c.fd(), F_GETFL) | O_NONBLOCK);
                for (int k = 0; k < 50; ++k) {
                    const ssize_t n = ::send(c.fd(), flood.data(), flood.size(), MSG_NOSIGNAL);
                    if (n <= 0) break;
                }
                break;
            }
            case 3: c.close(); break;  // abrupt close
        }
    }

    LineClient good(server.port());
    EXPECT_TRUE(starts_with(good.line().value_or(""), "HELLO"));
    double worst_ms = 0.0;
    for (int i = 0; i < 100; ++i) {
        const auto start = std::chrono::steady_clock::now();
        const std::string reply = good.request("#" + std::to_string(i) + " STATUS");
        worst_ms = std::max(worst_ms, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
        ASSERT_TRUE(starts_with(reply, "OK #" + std::to_string(i) + " STATE ")) << reply;
    }
    EXPECT_LT(worst_ms, 500.0);
    // Misbehaving clients that stayed connected still get their own answers.
    EXPECT_TRUE(starts_with(bad[0]->line().value_or(""), "HELLO"));
    EXPECT_TRUE(starts_with(bad[0]->line().value_or(""), "ERR 400 "));  // the garbage line
    EXPECT_TRUE(starts_with(bad[0]->request("#77 STATUS"), "OK #77 STATE "));
}

TEST(HeadSim, ThirtyTwoConcurrentClientsAllGetAnswers) {
    HeadServerConfig config;
    config.max_clients = 40;
    RunningServer server(config);
    std::vector<std::thread> threads;
    std::atomic<int> answered{0};
    for (int t = 0; t < 32; ++t) {
        threads.emplace_back([&, t] {
            try {
                LineClient c(server.port());
                c.line();
                for (int i = 0; i < 20; ++i) {
                    // Appended, not concatenated: GCC 12 warns (-Wrestrict) on "#" + string.
                    std::string id = "#";
                    id += std::to_string(t * 100 + i);
                    std::string request = id;
                    request += i % 2 ? " STATUS" : " MOVE VEL pan=1";
                    const std::string r = c.request(request);
                    if (starts_with(r, "OK " + id)) ++answered;
                }
            } catch (const std::exception&) {
            }
        });
    }
    for (auto& th : threads) th.join();
    EXPECT_EQ(answered.load(), 32 * 20);
}

std::string headsim_path() {
    const char* root = std::getenv("GESTURECAM_BUILD_ROOT");
    return std::string(root ? root : ".") + "/headctl/headsim";
}

TEST(HeadSim, ExecutableShutsDownCleanlyOnSigterm) {
    int out[2];
    ASSERT_EQ(::pipe(out), 0);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, out[1], STDOUT_FILENO);
    posix_spawn_file_actions_addclose(&actions, out[0]);
    const std::string path = headsim_path();
    std::vector<std::string> args{path, "--listen", "127.0.0.1:0", "--token", "t0k"};
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    pid_t pid = 0;
    ASSERT_EQ(::posix_spawn(&pid, path.c_str(), &actions, nullptr, argv.data(), environ), 0) << path;
    posix_spawn_file_actions_destroy(&actions);
    ::close(out[1]);
    // Whatever fails below, the child does not outlive the test.
    struct Reaper {
        pid_t pid;
        bool reaped = false;
        ~Reaper() {
            if (reaped) return;
            ::kill(pid, SIGKILL);
            ::waitpid(pid, nullptr, 0);
        }
    } reaper{pid};

    net::set_nonblocking(out[0]);  // the deadline below must hold
    net::LineReader reader(256);
    const auto first = reader.read_line(out[0], net::Clock::now() + 5s);
    ::close(out[0]);
    ASSERT_TRUE(first.has_value());
    ASSERT_TRUE(starts_with(*first, "listening 127.0.0.1:")) << *first;
    const int port = std::stoi(first->substr(first->rfind(':') + 1));
    {
        LineClient c(static_cast<std::uint16_t>(port));
        EXPECT_TRUE(starts_with(c.line().value_or(""), "HELLO GCHP/1"));
        EXPECT_EQ(c.request("AUTH t0k"), "OK");
        EXPECT_EQ(c.request("MOVE VEL pan=10"), "OK");
        ASSERT_EQ(::kill(pid, SIGTERM), 0);
        EXPECT_THROW(
            {
                for (int i = 0; i < 100; ++i) c.line(100ms);
            },
            net::NetError);  // the server closes its connections as it exits
    }
    int status = 0;
    pid_t done = 0;
    for (int i = 0; i < 500 && done == 0; ++i) {
        done = ::waitpid(pid, &status, WNOHANG);
        if (done == 0) std::this_thread::sleep_for(10ms);
    }
    ASSERT_NE(done, 0) << "headsim did not exit within 5 s of SIGTERM";
    reaper.reaped = true;
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 0);
}

}  // namespace
}  // namespace gc::headctl::testing
