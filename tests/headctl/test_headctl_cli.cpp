// The headctl command-line client against a loopback simulated head: output and exit codes.
#include "test_support.hpp"
#include "tools/tool_version.hpp"

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <vector>

namespace gc::headctl::testing {
namespace {

struct Outcome {
    int exit_code = -1;
    std::string out;
    std::string err;
};

// Runs build/gst-plugin/tools/`program` with args (and `env` added to the environment); bounded to 10 s.
Outcome run_program(const std::string& program, std::vector<std::string> args, const std::vector<std::string>& env = {})
{
    const char* root = std::getenv("GESTURECAM_BUILD_ROOT");
    const std::string path = std::string(root ? root : ".") + "/gst-plugin/tools/" + program;
    Outcome o;
    Spawned child;
    try {
        child = spawn(path, std::move(args), env, true);
    } catch (const std::exception&) {
        ADD_FAILURE() << "cannot run " << path;
        return o;
    }
    const pid_t pid = child.pid;
    const auto end = net::Clock::now() + 10s;
    std::array<std::uint8_t, 4096> buf{};
    try {
        while (net::Clock::now() < end) {
            const auto n = net::receive_some(child.out.get(), buf, end);
            if (!n) break;
            o.out.append(reinterpret_cast<const char*>(buf.data()), *n);
        }
    } catch (const net::NetError&) {
        // end of output
    }
    child.out.reset();
    int status = 0;
    pid_t done = 0;
    for (int i = 0; i < 500 && done == 0; ++i) {
        done = ::waitpid(pid, &status, WNOHANG);
        if (done == 0) std::this_thread::sleep_for(10ms);
    }
    if (done == 0) {
        ::kill(pid, SIGKILL);
        ::waitpid(pid, &status, 0);
        ADD_FAILURE() << "headctl did not finish within 5 s of closing its output";
        return o;
    }
    o.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    // What it wrote on stderr (a few lines at most: the pipe's buffer holds them all).
    char chunk[4096];
    for (ssize_t n; (n = ::read(child.err.get(), chunk, sizeof chunk)) > 0;)
        o.err.append(chunk, static_cast<std::size_t>(n));
    return o;
}

Outcome run_headctl(std::vector<std::string> args, const std::vector<std::string>& env = {})
{
    return run_program("headctl", std::move(args), env);
}

TEST(HeadctlCli, StatusMoveAndLimits)
{
    RunningServer server;
    const Outcome status = run_headctl({"--uri", server.uri(), "status"});
    EXPECT_EQ(status.exit_code, 0);
    EXPECT_NE(status.out.find("pan=0.000 tilt=0.000"), std::string::npos) << status.out;
    const Outcome move = run_headctl({"--uri", server.uri(), "move", "rel", "pan=-5", "tilt=2"});
    EXPECT_EQ(move.exit_code, 0);
    EXPECT_EQ(move.out, "ok move rel pan=-5 tilt=2\n");
    const Outcome limits = run_headctl({"--uri", server.uri(), "limits"});
    EXPECT_EQ(limits.exit_code, 0);
    EXPECT_NE(limits.out.find("pan      min=-170.000 max=170.000"), std::string::npos) << limits.out;
    const Outcome watch = run_headctl({"--uri", server.uri(), "watch", "10", "3"});
    EXPECT_EQ(watch.exit_code, 0);
    EXPECT_EQ(std::count(watch.out.begin(), watch.out.end(), '\n'), 3);
}

TEST(HeadctlCli, ZoomIsAMagnification)
{
    RunningServer server;
    EXPECT_NE(run_headctl({"--uri", server.uri(), "status"}).out.find(" zoom=1.000 "), std::string::npos);
    const Outcome move = run_headctl({"--uri", server.uri(), "move", "zoom=2"});
    EXPECT_EQ(move.exit_code, 0);
    EXPECT_EQ(move.out, "ok move abs zoom=2\n");
    std::string seen;
    for (int i = 0; i < 100 && seen.find(" zoom=2.000 ") == std::string::npos; ++i) {
        std::this_thread::sleep_for(20ms);
        seen = run_headctl({"--uri", server.uri(), "status"}).out;
    }
    EXPECT_NE(seen.find(" zoom=2.000 "), std::string::npos) << seen;
    EXPECT_EQ(run_headctl({"--uri", server.uri(), "move", "zoom=0.5"}).exit_code, 4);  // below the widest view
    const Outcome limits = run_headctl({"--uri", server.uri(), "limits"});
    EXPECT_NE(limits.out.find("zoom     min=1.000 max=20.000"), std::string::npos) << limits.out;
}

// Whether `headctl --uri URI status` shows `text` within about 3 s.
bool headctl_status_shows(const std::string& uri, const std::string& text)
{
    std::string seen;
    for (int i = 0; i < 150 && seen.find(text) == std::string::npos; ++i) {
        std::this_thread::sleep_for(20ms);
        seen = run_headctl({"--uri", uri, "status"}).out;
    }
    return seen.find(text) != std::string::npos;
}

TEST(HeadctlCli, PresetsAreSavedAndRecalledOnTheHead)
{
    RunningServer server;
    const auto status_shows = [&](const std::string& text) { return headctl_status_shows(server.uri(), text); };
    EXPECT_EQ(run_headctl({"--uri", server.uri(), "preset", "recall", "2"}).exit_code, 4);  // never saved
    EXPECT_EQ(run_headctl({"--uri", server.uri(), "move", "pan=12", "zoom=3"}).exit_code, 0);
    ASSERT_TRUE(status_shows("pan=12.000 "));
    ASSERT_TRUE(status_shows(" zoom=3.000 "));
    const Outcome save = run_headctl({"--uri", server.uri(), "preset", "save", "2"});
    EXPECT_EQ(save.exit_code, 0);
    EXPECT_EQ(save.out, "ok preset save 2\n");
    EXPECT_EQ(run_headctl({"--uri", server.uri(), "home"}).exit_code, 0);
    ASSERT_TRUE(status_shows("pan=0.000 "));
    EXPECT_EQ(run_headctl({"--uri", server.uri(), "preset", "recall", "2"}).exit_code, 0);
    EXPECT_TRUE(status_shows("pan=12.000 "));
    EXPECT_TRUE(status_shows(" zoom=3.000 "));
    EXPECT_EQ(run_headctl({"--uri", server.uri(), "preset", "save"}).exit_code, 2);
    EXPECT_EQ(run_headctl({"--uri", server.uri(), "preset", "save", "128"}).exit_code, 2);
    EXPECT_EQ(run_headctl({"--uri", server.uri(), "preset", "keep", "1"}).exit_code, 2);
}

// The same commands over ONVIF, to the head headsim --onvif serves.
TEST(HeadctlCli, SpeaksOnvifToTheSimulatedHead)
{
    RunningSimHead head;
    const std::string uri = head.onvif_uri();
    const Outcome move = run_headctl({"--uri", uri, "move", "pan=10", "tilt=5", "zoom=2"});
    EXPECT_EQ(move.exit_code, 0) << move.err;
    EXPECT_EQ(move.out, "ok move abs pan=10 tilt=5 zoom=2\n");
    ASSERT_TRUE(headctl_status_shows(uri, "pan=10.000 tilt=5.000 verge_l=0.000 verge_r=0.000 zoom=2.000 "));
    EXPECT_EQ(run_headctl({"--uri", uri, "preset", "save", "3"}).out, "ok preset save 3\n");
    EXPECT_EQ(run_headctl({"--uri", uri, "home"}).out, "ok home\n");
    ASSERT_TRUE(headctl_status_shows(uri, "pan=0.000 tilt=0.000 "));
    EXPECT_EQ(run_headctl({"--uri", uri, "preset", "recall", "3"}).out, "ok preset recall 3\n");
    EXPECT_TRUE(headctl_status_shows(uri, "pan=10.000 tilt=5.000 "));
    EXPECT_EQ(run_headctl({"--uri", uri, "stop"}).out, "ok stop\n");
    EXPECT_TRUE(headctl_status_shows(head.gchp_uri(), "pan=10.000 tilt=5.000 "));  // one head behind both
    const Outcome unsaved = run_headctl({"--uri", uri, "preset", "recall", "9"});
    EXPECT_EQ(unsaved.exit_code, 4);
    EXPECT_NE(unsaved.err.find("GotoPreset refused (NoToken)"), std::string::npos) << unsaved.err;
}

TEST(HeadctlCli, ExitCodesTellUsageConnectionAndRefusal)
{
    HeadServerConfig config;
    config.token = "k3y";
    RunningServer server(config);
    EXPECT_EQ(run_headctl({"--uri", server.uri(), "--token", "k3y", "move", "pan=400"}).exit_code, 4);
    EXPECT_EQ(run_headctl({"--uri", server.uri(), "--token", "k3y", "home"}).exit_code, 0);
    EXPECT_EQ(run_headctl({"--uri", server.uri(), "status"}).exit_code, 3);  // no token
    EXPECT_EQ(run_headctl({"--uri", server.uri(), "--token", "nope", "status"}).exit_code, 3);
    EXPECT_EQ(run_headctl({"--uri", server.uri(), "dance"}).exit_code, 2);
    EXPECT_EQ(run_headctl({"--uri", server.uri(), "move", "pan=abc"}).exit_code, 2);
    EXPECT_EQ(run_headctl({"--uri", server.uri(), "move", "roll=1"}).exit_code, 2);
    EXPECT_EQ(run_headctl({"--uri", "ftp://x", "status"}).exit_code, 2);
    EXPECT_EQ(run_headctl({}).exit_code, 2);
    server.stop();
    EXPECT_EQ(run_headctl({"--uri", server.uri(), "--timeout", "500", "status"}).exit_code, 3);
}

TEST(HeadctlCli, TakesTheTokenFromAFileOrTheEnvironment)
{
    HeadServerConfig config;
    config.token = "k3y-in-a-file";
    RunningServer server(config);
    char name[] = "/tmp/gesturecam-token-XXXXXX";
    const int fd = ::mkstemp(name);
    ASSERT_GE(fd, 0);
    const std::string text = "k3y-in-a-file\n";
    ASSERT_EQ(::write(fd, text.data(), text.size()), static_cast<ssize_t>(text.size()));
    ::close(fd);
    EXPECT_EQ(run_headctl({"--uri", server.uri(), "--token-file", name, "status"}).exit_code, 0);
    EXPECT_EQ(run_headctl({"--uri", server.uri(), "status"}, {"GESTURECAM_HEAD_TOKEN=k3y-in-a-file"}).exit_code, 0);
    EXPECT_EQ(run_headctl({"--uri", server.uri(), "status"}, {"GESTURECAM_HEAD_TOKEN=wrong"}).exit_code, 3);
    // One source at a time; a file that cannot be read is a usage error.
    EXPECT_EQ(run_headctl({"--uri", server.uri(), "--token-file", name, "--token", "x", "status"}).exit_code, 2);
    EXPECT_EQ(run_headctl({"--uri", server.uri(), "--token-file", "/nonexistent/token", "status"}).exit_code, 2);
    ::unlink(name);
}

}  // namespace
TEST(HeadctlCli, JsonRepliesOneObjectPerLine)
{
    RunningServer server;
    const Outcome status = run_headctl({"--uri", server.uri(), "--json", "status"});
    EXPECT_EQ(status.exit_code, 0);
    EXPECT_NE(status.out.find("\"pan\":0,\"tilt\":0,\"verge_l\":0,\"verge_r\":0,\"zoom\":1,\"pan_moving\":false"),
              std::string::npos)
        << status.out;
    EXPECT_EQ(status.out.front(), '{');
    EXPECT_EQ(std::count(status.out.begin(), status.out.end(), '\n'), 1);
    const Outcome move = run_headctl({"--uri", server.uri(), "--json", "move", "rel", "pan=-5"});
    EXPECT_EQ(move.exit_code, 0);
    EXPECT_EQ(move.out, "{\"ok\":true,\"command\":\"move rel pan=-5\"}\n");
    const Outcome limits = run_headctl({"--uri", server.uri(), "--json", "limits"});
    EXPECT_EQ(limits.exit_code, 0);
    EXPECT_NE(limits.out.find("{\"axis\":\"pan\",\"min\":-170,\"max\":170,"), std::string::npos) << limits.out;
    EXPECT_EQ(std::count(limits.out.begin(), limits.out.end(), '\n'), 5);  // pan, tilt, verge_l, verge_r, zoom
}

TEST(HeadctlCli, VersionHelpAndAOneLineHint)
{
    for (const std::string program : {"headctl", "headsim"}) {
        const Outcome version = run_program(program, {"--version"});
        EXPECT_EQ(version.exit_code, 0);
        EXPECT_EQ(version.out, program + " " + GC_TOOL_VERSION + "\n");
        const Outcome help = run_program(program, {"-h"});
        EXPECT_EQ(help.exit_code, 0);
        EXPECT_NE(help.out.find("usage: " + program), std::string::npos) << help.out;
        const Outcome bad = run_program(program, {"--frobnicate", "status"});
        EXPECT_EQ(bad.exit_code, 2);
        EXPECT_NE(bad.err.find("--frobnicate"), std::string::npos) << bad.err;
        EXPECT_NE(bad.err.find("--help"), std::string::npos) << bad.err;
        EXPECT_EQ(std::count(bad.err.begin(), bad.err.end(), '\n'), 1) << bad.err;
    }
}

}  // namespace gc::headctl::testing
