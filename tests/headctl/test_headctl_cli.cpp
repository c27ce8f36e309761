// The headctl command-line client against a loopback simulated head: output and exit codes.
#include "test_support.hpp"

#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <vector>

extern char** environ;

namespace gc::headctl::testing {
namespace {

struct Outcome {
    int exit_code = -1;
    std::string out;
};

// Runs the headctl executable with args; bounded to 10 s.
Outcome run_headctl(std::vector<std::string> args) {
    const char* root = std::getenv("GESTURECAM_BUILD_ROOT");
    const std::string path = std::string(root ? root : ".") + "/headctl/headctl";
    args.insert(args.begin(), path);
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    int pipe_fds[2];
    if (::pipe(pipe_fds) != 0) return {};
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, pipe_fds[1], STDOUT_FILENO);
    posix_spawn_file_actions_addclose(&actions, pipe_fds[0]);
    pid_t pid = 0;
    const int rc = ::posix_spawn(&pid, path.c_str(), &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    ::close(pipe_fds[1]);
    Outcome o;
    if (rc != 0) {
        ::close(pipe_fds[0]);
        ADD_FAILURE() << "cannot run " << path;
        return o;
    }
    net::set_nonblocking(pipe_fds[0]);
    const auto end = net::Clock::now() + 10s;
    std::array<std::uint8_t, 4096> buf{};
    try {
        while (net::Clock::now() < end) {
            const auto n = net::receive_some(pipe_fds[0], buf, end);
            if (!n) break;
            o.out.append(reinterpret_cast<const char*>(buf.data()), *n);
        }
    } catch (const net::NetError&) {
        // end of output
    }
    ::close(pipe_fds[0]);
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
    return o;
}

TEST(HeadctlCli, StatusMoveAndLimits) {
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

TEST(HeadctlCli, ExitCodesTellUsageConnectionAndRefusal) {
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

}  // namespace
}  // namespace gc::headctl::testing
