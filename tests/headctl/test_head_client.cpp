// The asynchronous client against a loopback simulated head: connection, sampling, the
// single command slot, the rate limit, reconnection with backoff, and a caller that never waits.
#include "shared_log.hpp"
#include "test_support.hpp"

#include "headctl/command_merge.hpp"
#include "headctl/gchp_backend.hpp"
#include "headctl/head_client.hpp"

#include <netinet/in.h>
#include <sys/socket.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <deque>
#include <cstdio>
#include <functional>
#include <vector>

namespace gc::headctl::testing {
namespace {

// Polls cond every 5 ms for at most `limit`.
template <typename Cond>
bool eventually(Cond cond, std::chrono::milliseconds limit = 5000ms)
{
    const auto end = std::chrono::steady_clock::now() + limit;
    while (std::chrono::steady_clock::now() < end) {
        if (cond()) return true;
        std::this_thread::sleep_for(5ms);
    }
    return cond();
}

HeadCommand absolute_pan(double deg)
{
    HeadCommand c{CommandKind::Absolute, {}};
    c.values.set(Axis::Pan, deg);
    return c;
}

// A client that samples every 10 ms and retries after 20 ms, doubling up to 160 ms.
HeadClientConfig config_for(const std::string& uri)
{
    HeadClientConfig c;
    c.uri = uri;
    c.status_interval = 10ms;
    c.backoff_initial = 20ms;
    c.backoff_max = 160ms;
    return c;
}

HeadClientConfig config_for(const RunningServer& server) { return config_for(server.uri()); }

// The same, sending commands no closer together than `min_command_interval`.
HeadClientConfig config_for(const RunningServer& server, std::chrono::milliseconds min_command_interval)
{
    HeadClientConfig c = config_for(server);
    c.min_command_interval = min_command_interval;
    return c;
}

// The state changes a client reports, as its callback records them.
class StateLog : public SharedLog<ConnectionState> {
public:
    std::function<void(ConnectionState, const std::string&)> recorder()
    {
        return [this](ConnectionState s, const std::string&) { add(s); };
    }
    std::vector<ConnectionState> seen() const { return items(); }
};

TEST(HeadClient, ConnectsSamplesAndInterpolates)
{
    RunningServer server;
    HeadClient client(config_for(server));
    ASSERT_TRUE(eventually([&] { return client.stats().state_samples >= 5; }));
    EXPECT_EQ(client.state(), ConnectionState::Connected);
    ASSERT_TRUE(client.limits());
    EXPECT_EQ(*client.limits(), default_simulated_limits());
    client.submit(absolute_pan(20.0));
    ASSERT_TRUE(eventually([&] {
        const auto s = client.latest();
        return s && std::abs(s->state.pose.pan_deg - 20.0) < 1e-9 && !s->state.moving[0];
    }));
    const auto pose = client.pose_at(client.now());
    ASSERT_TRUE(pose);
    EXPECT_NEAR(pose->pan_deg, 20.0, 1e-9);
}

TEST(HeadClient, StampsSamplesWithTheCallersClock)
{
    RunningServer server;
    HeadClientConfig config = config_for(server);
    const auto offset = std::chrono::hours(1000);
    config.clock = [offset] { return std::chrono::steady_clock::now().time_since_epoch() + offset; };
    HeadClient client(config);
    ASSERT_TRUE(eventually([&] { return client.latest().has_value(); }));
    const auto age = client.now() - client.latest()->time;
    EXPECT_GE(age, 0ms);
    EXPECT_LT(age, 2000ms);
}

TEST(HeadClient, LatestCommandWins)
{
    RunningServer server;
    HeadClient client(config_for(server, 300ms));
    ASSERT_TRUE(eventually([&] { return client.state() == ConnectionState::Connected; }));
    for (int i = 1; i <= 50; ++i) client.submit(absolute_pan(i));
    ASSERT_TRUE(eventually([&] {
        const auto s = client.latest();
        return s && std::abs(s->state.pose.pan_deg - 50.0) < 1e-9 && !s->state.moving[0];
    }));
    const HeadClientStats stats = client.stats();
    EXPECT_EQ(stats.commands_submitted, 50u);
    EXPECT_LE(stats.commands_sent, 2u);  // the first, perhaps, then the last
    EXPECT_EQ(stats.commands_sent + stats.commands_superseded, 50u);
}

HeadCommand velocity(std::initializer_list<std::pair<Axis, double>> values)
{
    HeadCommand c{CommandKind::Velocity, {}};
    for (const auto& [axis, v] : values) c.values.set(axis, v);
    return c;
}

HeadCommand of_kind(CommandKind kind, std::initializer_list<std::pair<Axis, double>> values)
{
    HeadCommand c{kind, {}};
    for (const auto& [axis, v] : values) c.values.set(axis, v);
    return c;
}

// What waits to be sent after `commands` are submitted in turn, and how many went.
std::pair<std::deque<HeadCommand>, int> queued(std::initializer_list<HeadCommand> commands)
{
    std::deque<HeadCommand> waiting;
    int gone = 0;
    for (const HeadCommand& c : commands) gone += queue_command(waiting, c, kMaxWaitingCommands);
    return {waiting, gone};
}

TEST(QueueCommand, ALaterCommandTakesAnEarliersPlaceOnlyWhereTheHeadEndsTheSame)
{
    // The vergence stopped, then a command for pan and tilt only: one command, the stop kept.
    const HeadCommand stop_verge =
        velocity({{Axis::Pan, 10.7}, {Axis::Tilt, -6.3}, {Axis::VergeLeft, 0.0}, {Axis::VergeRight, 0.0}});
    auto [waiting, gone] = queued({stop_verge, velocity({{Axis::Pan, 10.5}, {Axis::Tilt, -6.4}})});
    EXPECT_EQ(waiting, (std::deque<HeadCommand>{velocity(
                           {{Axis::Pan, 10.5}, {Axis::Tilt, -6.4}, {Axis::VergeLeft, 0.0}, {Axis::VergeRight, 0.0}})}));
    EXPECT_EQ(gone, 1);
    // Absolute after absolute merges the same way.
    const HeadCommand pan_to = of_kind(CommandKind::Absolute, {{Axis::Pan, 5.0}});
    const HeadCommand tilt_to = of_kind(CommandKind::Absolute, {{Axis::Tilt, -3.0}});
    EXPECT_EQ(queued({pan_to, tilt_to}).first,
              (std::deque<HeadCommand>{of_kind(CommandKind::Absolute, {{Axis::Pan, 5.0}, {Axis::Tilt, -3.0}})}));
    // A look naming fewer axes than the vergence stop before it: both go, in turn.
    EXPECT_EQ(queued({stop_verge, pan_to}).first, (std::deque<HeadCommand>{stop_verge, pan_to}));
    // A move naming every axis of the earlier one replaces it, of whatever kind.
    const HeadCommand look =
        of_kind(CommandKind::Absolute,
                {{Axis::Pan, 20.0}, {Axis::Tilt, 4.0}, {Axis::VergeLeft, 2.0}, {Axis::VergeRight, -2.0}});
    EXPECT_EQ(queued({stop_verge, look}).first, (std::deque<HeadCommand>{look}));
    // A velocity after a stop does not undo it: the stop goes first.
    const HeadCommand stop{CommandKind::Stop, {}};
    const HeadCommand pan_velocity = velocity({{Axis::Pan, 4.0}});
    EXPECT_EQ(queued({stop, pan_velocity}).first, (std::deque<HeadCommand>{stop, pan_velocity}));
    // Relative moves are not added up (the sum may pass a limit the first alone would not).
    const HeadCommand nudge = of_kind(CommandKind::Relative, {{Axis::Pan, 2.0}});
    EXPECT_EQ(queued({nudge, nudge}).first, (std::deque<HeadCommand>{nudge, nudge}));
    // A stop, home or recall undoes every motion before it, never a saved preset.
    const HeadCommand save = preset_command(CommandKind::SavePreset, 3);
    const HeadCommand recall = preset_command(CommandKind::RecallPreset, 3);
    EXPECT_EQ(queued({stop_verge, save, nudge, pan_to, recall}).first, (std::deque<HeadCommand>{save, recall}));
    EXPECT_EQ(queued({save, stop}).first, (std::deque<HeadCommand>{save, stop}));
    // A caller far ahead of the head: the oldest goes beyond four.
    const auto [many, dropped] = queued({save, nudge, nudge, nudge, nudge});
    EXPECT_EQ(many.size(), kMaxWaitingCommands);
    EXPECT_EQ(many.front(), nudge);
    EXPECT_EQ(dropped, 1);
}

// The head link's sequence after a stall: the eyes verge (sent), their stop waits behind the
// rate limit, and a pan/tilt command arrives before it goes out. The vergence must stop.
TEST(HeadClient, AVergenceStopIsNotLostToTheNextCommand)
{
    RunningServer server;
    // 600 ms between commands: the two submits land well within it, and the vergence would
    // still turn when looked at, short of headsim's 1 s velocity timeout.
    HeadClient client(config_for(server, 600ms));
    ASSERT_TRUE(eventually([&] { return client.state() == ConnectionState::Connected; }));
    client.submit(velocity({{Axis::Pan, 2.0}, {Axis::VergeLeft, 10.0}, {Axis::VergeRight, -10.0}}));
    ASSERT_TRUE(eventually([&] { return client.stats().commands_sent == 1; }));
    client.submit(velocity({{Axis::Pan, 2.0}, {Axis::VergeLeft, 0.0}, {Axis::VergeRight, 0.0}}));
    client.submit(velocity({{Axis::Pan, 1.0}}));
    ASSERT_TRUE(eventually([&] { return client.stats().commands_sent == 2; }));
    EXPECT_EQ(client.stats().commands_superseded, 1u);
    // Once that command is in, the vergence rests (it moved for the 600 ms between the two).
    std::this_thread::sleep_for(150ms);
    const auto s = client.latest();
    ASSERT_TRUE(s);
    EXPECT_FALSE(s->state.moving[static_cast<std::size_t>(Axis::VergeLeft)]);
    EXPECT_FALSE(s->state.moving[static_cast<std::size_t>(Axis::VergeRight)]);
    EXPECT_LT(s->state.pose.verge_left_deg, 8.0);  // 10 deg/s for 0.6 s
    EXPECT_TRUE(s->state.moving[static_cast<std::size_t>(Axis::Pan)]);
}

TEST(HeadClient, RateLimitsCommands)
{
    RunningServer server;
    HeadClient client(config_for(server, 50ms));
    ASSERT_TRUE(eventually([&] { return client.state() == ConnectionState::Connected; }));
    const auto start = std::chrono::steady_clock::now();
    int submitted = 0;
    while (std::chrono::steady_clock::now() - start < 500ms) {
        HeadCommand c{CommandKind::Velocity, {}};
        c.values.set(Axis::Pan, 1.0 + submitted % 10);
        client.submit(c);
        ++submitted;
        std::this_thread::sleep_for(2ms);
    }
    const double elapsed_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    std::this_thread::sleep_for(100ms);
    const HeadClientStats stats = client.stats();
    EXPECT_GT(submitted, 50);
    EXPECT_LE(stats.commands_sent, static_cast<std::uint64_t>(elapsed_ms / 50.0) + 3);
    EXPECT_GE(stats.commands_sent, 5u);
}

TEST(HeadClient, ReportsRefusedCommandsAndStaysConnected)
{
    RunningServer server;
    HeadClient client(config_for(server));
    ASSERT_TRUE(eventually([&] { return client.state() == ConnectionState::Connected; }));
    client.submit(absolute_pan(400.0));
    ASSERT_TRUE(eventually([&] { return client.stats().commands_rejected == 1; }));
    EXPECT_NE(client.last_error().find("out-of-range"), std::string::npos) << client.last_error();
    EXPECT_EQ(client.state(), ConnectionState::Connected);
}

TEST(HeadClient, ReconnectsWithExponentialBackoff)
{
    std::uint16_t port = 0;
    {
        RunningServer probe;  // a port that was free a moment ago
        port = probe.port();
    }
    StateLog log;
    HeadClientConfig config = config_for("tcp://127.0.0.1:" + std::to_string(port));
    config.on_state_change = log.recorder();
    HeadClient client(config);
    std::this_thread::sleep_for(1000ms);
    // Waits of 20, 40, 80, then 160 ms: about 8 attempts in the first second, not 50.
    const auto attempts = client.stats().connect_attempts;
    EXPECT_GE(attempts, 4u);
    EXPECT_LE(attempts, 12u);
    EXPECT_EQ(client.state(), ConnectionState::Disconnected);
    EXPECT_NE(client.last_error().find("cannot connect"), std::string::npos) << client.last_error();

    HeadServerConfig server_config;
    server_config.port = port;
    auto server = std::make_unique<RunningServer>(server_config);
    ASSERT_TRUE(eventually([&] { return client.state() == ConnectionState::Connected; }, 3000ms));
    ASSERT_TRUE(eventually([&] { return client.stats().state_samples > 0; }));
    server.reset();  // the head goes away: the client notices and retries
    ASSERT_TRUE(eventually([&] { return client.state() != ConnectionState::Connected; }, 3000ms));
    server = std::make_unique<RunningServer>(server_config);
    ASSERT_TRUE(eventually([&] { return client.state() == ConnectionState::Connected; }, 3000ms));
    EXPECT_EQ(client.stats().connections, 2u);
    const std::vector<ConnectionState> seen = log.seen();
    EXPECT_NE(std::find(seen.begin(), seen.end(), ConnectionState::Disconnected), seen.end());
    EXPECT_EQ(seen.back(), ConnectionState::Connected);
}

// A head that greets and then hangs up, every time: each connection "succeeds", so a client
// that forgets its backoff on connecting would call again every initial backoff.
TEST(HeadClient, BackoffGrowsAcrossConnectThenFailCycles)
{
    ScriptedServer flaky("HELLO GCHP/1 axes=pan,tilt,verge_l,verge_r caps=abs,rel,vel\n");
    HeadClient client(config_for(flaky.uri()));
    std::this_thread::sleep_for(1000ms);
    // Waits of 20, 40, 80, then 160 ms, as for a head that refuses outright: not one per 20 ms.
    const HeadClientStats stats = client.stats();
    std::printf("a head that connects and fails: %llu attempts in 1 s\n",
                static_cast<unsigned long long>(stats.connect_attempts));
    EXPECT_GE(stats.connections, 3u);
    EXPECT_LE(stats.connect_attempts, 12u);
}

TEST(HeadClient, AuthenticatesWithItsToken)
{
    HeadServerConfig server_config;
    server_config.token = "opensesame";
    RunningServer server(server_config);
    HeadClientConfig config = config_for(server);
    config.token = "wrong";
    {
        HeadClient client(config);
        ASSERT_TRUE(eventually([&] { return client.state() == ConnectionState::Disconnected; }));
        EXPECT_NE(client.last_error().find("refused the token"), std::string::npos) << client.last_error();
    }
    config.token = "opensesame";
    HeadClient client(config);
    EXPECT_TRUE(eventually([&] { return client.stats().state_samples > 0; }));
}

TEST(HeadClient, CallerNeverWaitsOnAStuckHead)
{
    const StuckListener stuck;
    HeadClientConfig config;
    config.uri = stuck.uri();
    config.connect_timeout = 2000ms;
    HeadClient client(config);
    std::this_thread::sleep_for(50ms);
    const double worst_us = longest_call_us(200, [&](int i) {
        client.submit(absolute_pan(i % 10));
        client.pose_at(client.now());
        client.state();
    });
    EXPECT_LT(worst_us, 100000.0);  // scheduling noise only: far below the 2 s connect timeout
    EXPECT_EQ(client.state(), ConnectionState::Connecting);
    EXPECT_FALSE(client.pose_at(client.now()));
}

// A head that greets and hangs up before it reports a state never counts as connected, so
// whoever reports connection changes (the element's warnings) sees one outage, not one per
// attempt.
TEST(HeadClient, AHeadThatHangsUpBeforeItsFirstStateIsNeverReportedConnected)
{
    ScriptedServer flaky("HELLO GCHP/1 axes=pan,tilt,verge_l,verge_r caps=abs,rel,vel\n");
    StateLog log;
    HeadClientConfig config = config_for(flaky.uri());
    config.on_state_change = log.recorder();
    HeadClient client(config);
    // The count of connections grows as an attempt connects, before its hang-up is reported:
    // wait for the reports themselves.
    const auto disconnects = [&] {
        const std::vector<ConnectionState> seen = log.seen();
        return std::count(seen.begin(), seen.end(), ConnectionState::Disconnected);
    };
    ASSERT_TRUE(eventually([&] { return client.stats().connections >= 3 && disconnects() >= 3; }));
    const std::vector<ConnectionState> seen = log.seen();
    EXPECT_EQ(std::count(seen.begin(), seen.end(), ConnectionState::Connected), 0);
    EXPECT_GE(std::count(seen.begin(), seen.end(), ConnectionState::Disconnected), 3);
}

// A GCHP line may hold 512 bytes before its '\n' (and a '\r' that does not count); a head
// sending a longer one is refused, and the message names the limit.
TEST(GchpBackend, TakesLinesOfUpTo512BytesAndNamesTheLimitBeyond)
{
    const std::string greeting = "HELLO GCHP/1 axes=pan,tilt,verge_l,verge_r caps=abs,rel,vel,";
    const std::string longest = greeting + std::string(kMaxLineLength - greeting.size(), 'x');
    ASSERT_EQ(longest.size(), 512u);
    for (const std::string& ending : {std::string("\n"), std::string("\r\n")}) {
        ScriptedServer fits(longest + ending);
        GchpBackend head("127.0.0.1", fits.port(), "");
        EXPECT_NO_THROW(head.open(net::Clock::now() + 2s));
    }
    for (const std::size_t extra : {1u, 400u, 4000u}) {
        ScriptedServer too_long(longest + std::string(extra, 'y') + "\n");
        GchpBackend head("127.0.0.1", too_long.port(), "");
        try {
            head.open(net::Clock::now() + 2s);
            ADD_FAILURE() << "a line of " << 512 + extra << " bytes was taken";
        } catch (const net::NetError& e) {
            EXPECT_NE(std::string(e.what()).find("longer than 512 bytes"), std::string::npos) << e.what();
        }
    }
}

TEST(HeadClient, RejectsBadConfigurationAndCommands)
{
    HeadClientConfig config;
    config.uri = "ftp://head";
    EXPECT_THROW(HeadClient{config}, std::invalid_argument);
    config.uri = "tcp://127.0.0.1:9";
    config.backoff_max = 1ms;
    EXPECT_THROW(HeadClient{config}, std::invalid_argument);
    config = {};
    config.uri = "visca-udp://127.0.0.1:9";
    HeadClient visca_client(config);
    HeadCommand verge{CommandKind::Absolute, {}};
    verge.values.set(Axis::VergeLeft, 1.0);
    EXPECT_THROW(visca_client.submit(verge), std::invalid_argument);
    EXPECT_THROW(visca_client.submit(absolute_pan(std::nan(""))), std::invalid_argument);
    EXPECT_THROW(visca_client.submit(HeadCommand{CommandKind::Velocity, {}}), std::invalid_argument);
}

}  // namespace
}  // namespace gc::headctl::testing
