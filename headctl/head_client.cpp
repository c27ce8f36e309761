#include "headctl/head_client.hpp"
#include "headctl/command_merge.hpp"

#include "common/enum_names.hpp"

#include <cmath>

namespace gc::headctl {

using SteadyClock = std::chrono::steady_clock;

namespace {

constexpr EnumNames<ConnectionState, 4> kConnectionStates{{
    {ConnectionState::Connecting, "connecting"},
    {ConnectionState::Connected, "connected"},
    {ConnectionState::Disconnected, "disconnected"},
    {ConnectionState::Stopped, "stopped"},
}};

}  // namespace

std::string_view to_string(ConnectionState s) { return name_in(kConnectionStates, s, "?"); }

HeadClient::HeadClient(HeadClientConfig config)
    : config_(std::move(config)), history_(config_.history_capacity < 2 ? 2 : config_.history_capacity)
{
    using std::chrono::milliseconds;
    auto positive = [](milliseconds d, const char* name) {
        if (d <= milliseconds{0}) throw std::invalid_argument(std::string("head client: ") + name + " must be > 0");
    };
    positive(config_.connect_timeout, "connect timeout");
    positive(config_.request_timeout, "request timeout");
    positive(config_.backoff_initial, "initial backoff");
    positive(config_.status_interval, "status interval");
    positive(config_.backoff_reset_after, "backoff reset time");
    if (config_.backoff_max < config_.backoff_initial)
        throw std::invalid_argument("head client: maximum backoff must be >= the initial backoff");
    if (config_.min_command_interval < milliseconds{0} || config_.max_extrapolation < milliseconds{0})
        throw std::invalid_argument("head client: intervals must be >= 0");
    if (config_.history_capacity < 2) throw std::invalid_argument("head client: history capacity must be >= 2");
    if (!config_.backend_factory) {
        const HeadUri uri = parse_head_uri(config_.uri);
        const auto backend = make_backend(uri, config_.token);  // reports bad parameters now, not on the thread
        config_.backend_factory = [uri, token = config_.token] { return make_backend(uri, token); };
        // A GCHP head names its axes in its greeting; other backends know theirs up front.
        if (uri.scheme != HeadScheme::Gchp) axes_ = backend->axes();
    }
    if (!config_.clock) config_.clock = [] { return SteadyClock::now().time_since_epoch(); };
    thread_ = std::thread([this] { run(); });
}

HeadClient::~HeadClient()
{
    {
        std::lock_guard lock(mutex_);
        stopping_ = true;
    }
    cancel_ = true;  // cuts a blocking exchange with the head short
    wake_.notify_all();
    thread_.join();
}

void HeadClient::submit(const HeadCommand& command)
{
    for (Axis a : kAllAxes) {
        if (!command.values.has(a)) continue;
        if (!std::isfinite(command.values.get(a)))
            throw std::invalid_argument("head command: " + std::string(axis_name(a)) + " value is not finite");
        if (!axes_[static_cast<std::size_t>(a)])
            throw std::invalid_argument("head command: this head has no " + std::string(axis_name(a)) + " axis");
    }
    const bool is_move = command.kind == CommandKind::Absolute || command.kind == CommandKind::Relative ||
                         command.kind == CommandKind::Velocity;
    if (is_move && command.values.empty()) throw std::invalid_argument("head command: a move names no axis");
    if (is_preset(command.kind) && (command.preset < 0 || command.preset > kMaxPreset))
        throw std::invalid_argument("head command: preset " + std::to_string(command.preset) + " is not in 0.." +
                                    std::to_string(kMaxPreset));
    {
        std::lock_guard lock(mutex_);
        ++stats_.commands_submitted;
        stats_.commands_superseded += std::uint64_t(queue_command(waiting_, command, kMaxWaitingCommands));
    }
    wake_.notify_all();
}

ConnectionState HeadClient::state() const
{
    std::lock_guard lock(mutex_);
    return state_;
}

std::string HeadClient::last_error() const
{
    std::lock_guard lock(mutex_);
    return last_error_;
}

HeadClientStats HeadClient::stats() const
{
    std::lock_guard lock(mutex_);
    return stats_;
}

std::optional<HeadLimits> HeadClient::limits() const
{
    std::lock_guard lock(mutex_);
    return limits_;
}

std::optional<StateSample> HeadClient::latest() const
{
    std::lock_guard lock(mutex_);
    return history_.newest();
}

std::optional<HeadPose> HeadClient::pose_at(Timestamp t) const
{
    std::lock_guard lock(mutex_);
    return history_.pose_at(t, config_.max_extrapolation);
}

Timestamp HeadClient::now() const { return config_.clock(); }

void HeadClient::set_state(ConnectionState s, const std::string& error)
{
    bool changed = false;
    {
        std::lock_guard lock(mutex_);
        changed = s != state_;
        state_ = s;
        if (!error.empty()) last_error_ = error;
    }
    if (changed && config_.on_state_change) config_.on_state_change(s, error);
}

void HeadClient::wait_for(SteadyClock::duration d)
{
    std::unique_lock lock(mutex_);
    wake_.wait_for(lock, d, [this] { return stopping_; });
}

void HeadClient::run()
{
    const net::CancelScope cancel_scope(cancel_);
    auto backoff = config_.backoff_initial;
    for (;;) {
        {
            std::lock_guard lock(mutex_);
            if (stopping_) break;
            ++stats_.connect_attempts;
        }
        set_state(ConnectionState::Connecting, {});
        std::unique_ptr<HeadBackend> backend;
        std::string error;
        std::optional<SteadyClock::time_point> connected_at;
        try {
            backend = config_.backend_factory();
            backend->open(SteadyClock::now() + config_.connect_timeout);
            connected_at = SteadyClock::now();
            {
                std::lock_guard lock(mutex_);
                ++stats_.connections;
            }
            serve(*backend);  // reports Connected once the head has answered a first STATUS
        } catch (const std::exception& e) {
            error = e.what();
        }
        if (backend) backend->close();
        {
            std::lock_guard lock(mutex_);
            if (stopping_) break;
        }
        set_state(ConnectionState::Disconnected, error);
        if (connected_at && SteadyClock::now() - *connected_at >= config_.backoff_reset_after)
            backoff = config_.backoff_initial;
        wait_for(backoff);
        backoff = std::min(backoff * 2, config_.backoff_max);
    }
    set_state(ConnectionState::Stopped, {});
}

void HeadClient::serve(HeadBackend& backend)
{
    auto deadline = [this] { return SteadyClock::now() + config_.request_timeout; };
    if (auto limits = backend.query_limits(deadline())) {
        std::lock_guard lock(mutex_);
        limits_ = limits;
    }
    auto next_status = SteadyClock::now();
    auto next_command = SteadyClock::now();
    for (;;) {
        std::optional<HeadCommand> command;
        {
            std::unique_lock lock(mutex_);
            const auto wake_at = waiting_.empty() ? next_status : std::min(next_status, next_command);
            wake_.wait_until(lock, wake_at,
                             [&] { return stopping_ || (!waiting_.empty() && SteadyClock::now() >= next_command); });
            if (stopping_) return;
            if (!waiting_.empty() && SteadyClock::now() >= next_command) {
                command = std::move(waiting_.front());
                waiting_.pop_front();
            }
        }
        if (command) {
            next_command = SteadyClock::now() + config_.min_command_interval;
            try {
                backend.send(*command, deadline());
                std::lock_guard lock(mutex_);
                ++stats_.commands_sent;
            } catch (const HeadRejected& e) {
                std::lock_guard lock(mutex_);
                ++stats_.commands_sent;
                ++stats_.commands_rejected;
                last_error_ = e.what();
            }
        }
        if (SteadyClock::now() >= next_status) {
            // The sample is stamped halfway through the exchange: the head's reading is
            // closest to that instant when the link is symmetric.
            const Timestamp before = config_.clock();
            const HeadState s = backend.query_state(deadline());
            const Timestamp after = config_.clock();
            {
                std::lock_guard lock(mutex_);
                history_.push(StateSample{before + (after - before) / 2, s});
                ++stats_.state_samples;
            }
            next_status = SteadyClock::now() + config_.status_interval;
            // Only a head that answers counts as connected: one that greets and hangs up
            // makes one outage, not a "connected" and a "disconnected" per attempt.
            set_state(ConnectionState::Connected, {});
        }
    }
}

}  // namespace gc::headctl
