// The asynchronous head client: one thread owns the connection; callers only hand over the
// latest command and read the latest state, never waiting on the network.
#pragma once

#include "headctl/head_backend.hpp"
#include "headctl/pose_history.hpp"

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

namespace gc::headctl {

// Commands held back by the rate limit; only commands a later one can neither merge with nor
// undo stay apart, so more than a few is a caller far ahead of the head.
inline constexpr std::size_t kMaxWaitingCommands = 4;

// Connected: the head has answered a STATUS on the current connection.
enum class ConnectionState { Connecting, Connected, Disconnected, Stopped };
std::string_view to_string(ConnectionState s);

struct HeadClientConfig {
    std::string uri = "tcp://127.0.0.1:5050";
    std::string token;
    std::chrono::milliseconds connect_timeout{1000};
    std::chrono::milliseconds request_timeout{500};
    std::chrono::milliseconds backoff_initial{100};  // doubles after each failed attempt...
    std::chrono::milliseconds backoff_max{5000};     // ...up to this
    // A connection that lasted this long sets the backoff back to its start; a shorter one
    // counts as a failed attempt, so a head that accepts and then fails is not called
    // every backoff_initial.
    std::chrono::milliseconds backoff_reset_after{2000};
    std::chrono::milliseconds min_command_interval{20};  // rate limit of commands sent
    std::chrono::milliseconds status_interval{20};       // how often the state is sampled
    std::size_t history_capacity = 256;
    std::chrono::milliseconds max_extrapolation{100};
    // The clock samples are stamped with; steady_clock when empty.
    std::function<Timestamp()> clock;
    // Called on the client's thread after each state change; must not block.
    std::function<void(ConnectionState, const std::string& error)> on_state_change;
    // Makes the backend; from uri and token when empty (tests inject their own).
    std::function<std::unique_ptr<HeadBackend>()> backend_factory;
};

struct HeadClientStats {
    std::uint64_t connect_attempts = 0;
    std::uint64_t connections = 0;
    std::uint64_t commands_submitted = 0;
    std::uint64_t commands_sent = 0;
    std::uint64_t commands_superseded = 0;  // merged into or undone by a later one before being sent
    std::uint64_t commands_rejected = 0;    // refused by the head
    std::uint64_t state_samples = 0;
};

class HeadClient {
public:
    // Validates the configuration (std::invalid_argument naming the field) and starts the thread.
    explicit HeadClient(HeadClientConfig config);
    ~HeadClient();
    HeadClient(const HeadClient&) = delete;
    HeadClient& operator=(const HeadClient&) = delete;

    // Latest command wins: it takes the place of the commands not yet sent where the head ends
    // the same (queue_command); a command it cannot replace, such as a stop of the axes it
    // does not name, still goes out first. Throws std::invalid_argument for a value that is
    // not finite or an axis the head does not have.
    void submit(const HeadCommand& command);

    ConnectionState state() const;
    std::string last_error() const;
    HeadClientStats stats() const;
    std::optional<HeadLimits> limits() const;
    std::optional<StateSample> latest() const;
    // Whether commands may name the axis (a backend without it refuses them in submit).
    bool has_axis(Axis a) const { return axes_[static_cast<std::size_t>(a)]; }
    // The head's pose at a capture time on the configured clock (see PoseHistory::pose_at).
    std::optional<HeadPose> pose_at(Timestamp capture_time) const;
    Timestamp now() const;

private:
    void run();
    void serve(HeadBackend& backend);
    void set_state(ConnectionState s, const std::string& error);
    void wait_for(std::chrono::steady_clock::duration d);

    HeadClientConfig config_;
    std::array<bool, kAxisCount> axes_{true, true, true, true, true};

    mutable std::mutex mutex_;
    std::condition_variable wake_;
    bool stopping_ = false;
    std::atomic<bool> cancel_{false};  // stopping_, readable by the network waits without the mutex
    std::deque<HeadCommand> waiting_;  // not yet sent, oldest first (queue_command)
    ConnectionState state_ = ConnectionState::Connecting;
    std::string last_error_;
    HeadClientStats stats_;
    std::optional<HeadLimits> limits_;
    PoseHistory history_;

    std::thread thread_;
};

}  // namespace gc::headctl
