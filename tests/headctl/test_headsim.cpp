// The simulated head server: many clients, misbehaving clients, authentication, and the
// headsim executable's clean shutdown on SIGTERM.
#include "test_support.hpp"

#include "headctl/head_backend.hpp"
#include "headctl/protocol.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <vector>

namespace gc::headctl::testing {
namespace {

bool starts_with(const std::string& s, std::string_view prefix) { return s.rfind(prefix, 0) == 0; }

TEST(HeadSim, GreetsAndAnswersRequestsWithTheirIds)
{
    RunningServer server;
    LineClient c(server.port());
    EXPECT_EQ(c.line().value_or(""), "HELLO GCHP/1 axes=pan,tilt,verge_l,verge_r,zoom caps=abs,rel,vel,preset");
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

TEST(HeadSim, RequiresTheTokenBeforeAnythingElse)
{
    HeadServerConfig config;
    config.token = "letmein";
    config.max_auth_failures = 2;
    RunningServer server(config);
    LineClient c(server.port());
    EXPECT_EQ(c.line().value_or(""), "HELLO GCHP/1 axes=pan,tilt,verge_l,verge_r,zoom caps=abs,rel,vel,preset,auth");
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

TEST(HeadSim, OverLongLinesAreReportedAndSkipped)
{
    RunningServer server;
    LineClient c(server.port());
    c.line();
    c.send(std::string(3 * kMaxLineLength, 'A'));  // in pieces: the server sees it grow
    c.send(std::string(5000, 'B') + "\n#9 STATUS\n");
    EXPECT_TRUE(starts_with(c.line().value_or(""), "ERR 413 "));
    EXPECT_TRUE(starts_with(c.line().value_or(""), "OK #9 STATE "));
}

TEST(HeadSim, RefusesClientsBeyondTheCap)
{
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
TEST(HeadSim, MisbehavingClientsDoNotDisturbAGoodOne)
{
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
        case 0:
            c.send("\x01\x02garbage\xff\xfe\n\n\n");
            break;  // garbage
        case 1:
            c.send("#1 MOVE ABS pan=1");
            break;  // half a line, never finished
        case 2: {   // slow reader: never reads
            const int small = 4096;
            ::setsockopt(c.fd(), SOL_SOCKET, SO_RCVBUF, &small, sizeof small);
            ::fcntl(c.fd(), F_SETFL, ::fcntl(c.fd(), F_GETFL) | O_NONBLOCK);
            for (int k = 0; k < 50; ++k) {
                const ssize_t n = ::send(c.fd(), flood.data(), flood.size(), MSG_NOSIGNAL);
                if (n <= 0) break;
            }
            break;
        }
        case 3:
            c.close();
            break;  // abrupt close
        }
    }

    LineClient good(server.port());
    EXPECT_TRUE(starts_with(good.line().value_or(""), "HELLO"));
    double worst_ms = 0.0;
    for (int i = 0; i < 100; ++i) {
        const auto start = std::chrono::steady_clock::now();
        const std::string reply = good.request(std::string("#") + std::to_string(i) + " STATUS");
        worst_ms = std::max(
            worst_ms, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
        ASSERT_TRUE(starts_with(reply, "OK #" + std::to_string(i) + " STATE ")) << reply;
    }
    EXPECT_LT(worst_ms, 500.0);
    // Misbehaving clients that stayed connected still get their own answers.
    EXPECT_TRUE(starts_with(bad[0]->line().value_or(""), "HELLO"));
    EXPECT_TRUE(starts_with(bad[0]->line().value_or(""), "ERR 400 "));  // the garbage line
    EXPECT_TRUE(starts_with(bad[0]->request("#77 STATUS"), "OK #77 STATE "));
}

TEST(HeadSim, ThirtyTwoConcurrentClientsAllGetAnswers)
{
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

std::string headsim_path()
{
    const char* root = std::getenv("GESTURECAM_BUILD_ROOT");
    return std::string(root ? root : ".") + "/gst-plugin/tools/headsim";
}

// The headsim executable run with `args` (and `env` added to the environment); its stdout
// and stderr are read through pipes. Whatever fails, the child does not outlive the test.
class HeadsimProcess {
public:
    explicit HeadsimProcess(std::vector<std::string> args, const std::vector<std::string>& env = {})
    {
        Spawned s = spawn(headsim_path(), std::move(args), env, true);
        pid_ = s.pid;
        out_ = std::move(s.out);
        err_ = std::move(s.err);
    }
    ~HeadsimProcess()
    {
        if (reaped_) return;
        ::kill(pid_, SIGKILL);
        ::waitpid(pid_, nullptr, 0);
    }
    pid_t pid() const { return pid_; }
    // The next line on stdout, or nullopt after 5 s or at its end.
    std::optional<std::string> out_line()
    {
        try {
            return out_reader_.read_line(out_.get(), net::Clock::now() + 5s);
        } catch (const net::NetError&) {
            return std::nullopt;
        }
    }
    // The port of the "listening ADDR:PORT" line, or 0 when it does not come.
    std::uint16_t listening_port()
    {
        const auto first = out_line();
        EXPECT_TRUE(first && starts_with(*first, "listening 127.0.0.1:")) << first.value_or("<nothing>");
        if (!first || first->rfind(':') == std::string::npos) return 0;
        return static_cast<std::uint16_t>(std::stoi(first->substr(first->rfind(':') + 1)));
    }
    // The exit status, or -1 when it runs on after `limit`.
    int exit_status(std::chrono::milliseconds limit = 5000ms)
    {
        int status = 0;
        pid_t done = 0;
        for (auto end = net::Clock::now() + limit; done == 0 && net::Clock::now() < end;) {
            done = ::waitpid(pid_, &status, WNOHANG);
            if (done == 0) std::this_thread::sleep_for(10ms);
        }
        if (done == 0) return -1;
        reaped_ = true;
        return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    }
    // What it wrote on stderr so far.
    std::string err_text()
    {
        std::string text;
        char chunk[1024];
        for (ssize_t n; (n = ::read(err_.get(), chunk, sizeof chunk)) > 0;)
            text.append(chunk, static_cast<std::size_t>(n));
        return text;
    }
    // Its command line as other users of the machine read it.
    std::string command_line() const
    {
        std::ifstream in("/proc/" + std::to_string(pid_) + "/cmdline");
        std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        std::replace(text.begin(), text.end(), '\0', ' ');
        return text;
    }

private:
    pid_t pid_ = 0;
    bool reaped_ = false;
    net::Fd out_, err_;
    net::LineReader out_reader_{256};
};

TEST(HeadSim, ExecutableShutsDownCleanlyOnSigterm)
{
    HeadsimProcess headsim({"--listen", "127.0.0.1:0", "--token", "t0k"});
    const std::uint16_t port = headsim.listening_port();
    ASSERT_NE(port, 0);
    {
        LineClient c(port);
        EXPECT_TRUE(starts_with(c.line().value_or(""), "HELLO GCHP/1"));
        EXPECT_EQ(c.request("AUTH t0k"), "OK");
        EXPECT_EQ(c.request("MOVE VEL pan=10"), "OK");
        ASSERT_EQ(::kill(headsim.pid(), SIGTERM), 0);
        EXPECT_THROW(
            {
                for (int i = 0; i < 100; ++i) c.line(100ms);
            },
            net::NetError);  // the server closes its connections as it exits
    }
    const int status = headsim.exit_status();
    ASSERT_NE(status, -1) << "headsim did not exit within 5 s of SIGTERM";
    EXPECT_EQ(status, 0);
}

// A file holding `text`, removed at the end of the scope.
struct TempFile {
    explicit TempFile(const std::string& text)
    {
        char name[] = "/tmp/gesturecam-token-XXXXXX";
        const int fd = ::mkstemp(name);
        path = name;
        [[maybe_unused]] const ssize_t n = ::write(fd, text.data(), text.size());
        ::close(fd);
    }
    ~TempFile() { ::unlink(path.c_str()); }
    std::string path;
};

// The token holder is served, a wrong token is not.
void expect_token(std::uint16_t port, const std::string& token)
{
    LineClient c(port);
    EXPECT_TRUE(starts_with(c.line().value_or(""),
                            "HELLO GCHP/1 axes=pan,tilt,verge_l,verge_r,zoom caps=abs,rel,vel,preset,auth"));
    EXPECT_TRUE(starts_with(c.request("#1 STATUS"), "ERR #1 401 "));
    EXPECT_EQ(c.request("#2 AUTH " + token), "OK #2");
    LineClient other(port);
    other.line();
    EXPECT_TRUE(starts_with(other.request("#3 AUTH not-" + token), "ERR #3 403 "));
}

TEST(HeadSim, TakesItsTokenFromAFileOrTheEnvironmentOffItsCommandLine)
{
    const TempFile file("from-a-file\n");
    HeadsimProcess from_file({"--listen", "127.0.0.1:0", "--token-file", file.path});
    expect_token(from_file.listening_port(), "from-a-file");
    EXPECT_EQ(from_file.command_line().find("from-a-file"), std::string::npos);

    HeadsimProcess from_env({"--listen", "127.0.0.1:0"}, {"GESTURECAM_HEAD_TOKEN=from-the-env"});
    expect_token(from_env.listening_port(), "from-the-env");

    // A token given on the command line still works, and is blanked there once read.
    HeadsimProcess inline_token({"--listen", "127.0.0.1:0", "--token", "typed-in-clear"});
    expect_token(inline_token.listening_port(), "typed-in-clear");
    EXPECT_EQ(inline_token.command_line().find("typed-in-clear"), std::string::npos) << inline_token.command_line();
}

TEST(HeadSim, AnUnusableTokenFileStopsTheStartAndIsNamed)
{
    const TempFile empty("\n");
    for (const std::string& path : {std::string("/nonexistent/token"), empty.path}) {
        HeadsimProcess headsim({"--listen", "127.0.0.1:0", "--token-file", path});
        EXPECT_EQ(headsim.exit_status(), 2) << path;
        EXPECT_NE(headsim.err_text().find(path), std::string::npos) << path;
    }
}

TEST(HeadSim, ExecutableRefusesToListenBeyondLoopbackWithoutAToken)
{
    HeadsimProcess headsim({"--listen", "0.0.0.0:0"});
    const int status = headsim.exit_status();
    EXPECT_EQ(status, 2) << "headsim listens on every interface without a token";
    EXPECT_NE(headsim.err_text().find("--allow-remote"), std::string::npos);
}

// --onvif serves the same head over ONVIF; its token is the ONVIF password.
TEST(HeadSim, ServesOnvifOnTheSameHeadWithItsTokenAsPassword)
{
    const TempFile file("onvif-pass\n");
    HeadsimProcess headsim(
        {"--listen", "127.0.0.1:0", "--onvif", "127.0.0.1:0", "--onvif-user", "op", "--token-file", file.path});
    const std::uint16_t gchp = headsim.listening_port();
    const auto line = headsim.out_line();
    ASSERT_TRUE(line && starts_with(*line, "onvif listening 127.0.0.1:")) << line.value_or("<nothing>");
    const std::string uri = "onvif://127.0.0.1:" + line->substr(line->rfind(':') + 1) + "?user=op";

    auto onvif = make_backend(parse_head_uri(uri), "onvif-pass");
    onvif->open(net::Clock::now() + 2s);
    HeadCommand move{CommandKind::Absolute, {}};
    move.values.set(Axis::Pan, 12);
    onvif->send(move, net::Clock::now() + 1s);
    LineClient c(gchp);
    c.line();
    EXPECT_EQ(c.request("AUTH onvif-pass"), "OK");
    EXPECT_TRUE(
        loopback::eventually([&] { return c.request("STATUS").find(" pan=12 ") != std::string::npos; }, 3000ms))
        << c.request("STATUS");

    auto wrong = make_backend(parse_head_uri(uri), "onvif-guess");
    EXPECT_THROW(wrong->open(net::Clock::now() + 2s), net::NetError);
}

// --visca serves the same head over VISCA over IP, which has no authentication: beyond
// loopback only with --allow-remote, even when GCHP has a token.
TEST(HeadSim, ServesViscaOnTheSameHeadOnLoopbackOnly)
{
    HeadsimProcess headsim({"--listen", "127.0.0.1:0", "--onvif", "127.0.0.1:0", "--visca", "127.0.0.1:0"});
    const std::uint16_t gchp = headsim.listening_port();
    const auto onvif_line = headsim.out_line();
    const auto line = headsim.out_line();
    ASSERT_TRUE(onvif_line && starts_with(*onvif_line, "onvif listening 127.0.0.1:"));
    ASSERT_TRUE(line && starts_with(*line, "visca listening 127.0.0.1:")) << line.value_or("<nothing>");
    auto visca = make_backend(parse_head_uri("visca-udp://127.0.0.1:" + line->substr(line->rfind(':') + 1)));
    visca->open(net::Clock::now() + 2s);
    HeadCommand move{CommandKind::Absolute, {}};
    move.values.set(Axis::Pan, -12);
    visca->send(move, net::Clock::now() + 1s);
    LineClient c(gchp);
    c.line();
    EXPECT_TRUE(
        loopback::eventually([&] { return c.request("STATUS").find(" pan=-12 ") != std::string::npos; }, 3000ms))
        << c.request("STATUS");

    const TempFile file("gchp-token\n");
    HeadsimProcess remote({"--listen", "127.0.0.1:0", "--token-file", file.path, "--visca", "0.0.0.0:0"});
    EXPECT_EQ(remote.exit_status(), 2) << "headsim serves VISCA on every interface without --allow-remote";
    EXPECT_NE(remote.err_text().find("VISCA has no authentication"), std::string::npos) << remote.err_text();
}

}  // namespace
}  // namespace gc::headctl::testing
