// Watching a JSON-lines output while the program that writes it runs: what a reader following
// the file sees, and what is left after the program is terminated part-way. Shared by the
// gesturecam-track and handtracker tests.
#pragma once

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

extern char** environ;

namespace gc::test {

struct LineWatch {
    bool started = false;
    int looks = 0;              // times the file was seen non-empty while the program ran
    std::string partial;        // the first content seen ending inside a line that stayed so; empty if none
    bool terminated = false;    // the program ended by the SIGTERM
    std::string final_content;  // the file after the program ended
};

inline std::string file_text(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

// Runs `argv` (output and errors to /dev/null), reads `path` every millisecond while it runs,
// and sends SIGTERM once the file holds `lines_before_term` whole lines (or after `timeout`).
inline LineWatch watch_lines(const std::vector<std::string>& argv, const std::string& path,
                             std::size_t lines_before_term, std::chrono::seconds timeout)
{
    LineWatch w;
    std::vector<char*> args;
    for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
    pid_t pid = -1;
    w.started = ::posix_spawnp(&pid, args[0], &actions, nullptr, args.data(), environ) == 0;
    posix_spawn_file_actions_destroy(&actions);
    if (!w.started) return w;
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    bool sent = false;
    int status = 0;
    while (::waitpid(pid, &status, WNOHANG) == 0) {
        const std::string seen = file_text(path);
        if (!seen.empty()) {
            ++w.looks;
            if (seen.back() != '\n' && w.partial.empty()) {
                // A reader can catch one write(2) of a long line half copied, for microseconds;
                // a line held back in a buffer stays cut until the next flush, a frame later.
                std::this_thread::sleep_for(std::chrono::milliseconds(5));
                const std::string later = file_text(path);
                if (later.find('\n', seen.size()) == std::string::npos) w.partial = seen;
            }
        }
        const auto lines = static_cast<std::size_t>(std::count(seen.begin(), seen.end(), '\n'));
        if (!sent && (lines >= lines_before_term || std::chrono::steady_clock::now() > deadline)) {
            ::kill(pid, SIGTERM);
            sent = true;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    w.terminated = WIFSIGNALED(status) && WTERMSIG(status) == SIGTERM;
    w.final_content = file_text(path);
    return w;
}

}  // namespace gc::test
