// The simulated head against clients that do not know its token: idle and trickling
// connections, many connections from one address, reconnecting token guessers, and a
// listening address beyond loopback without a token. Each comes from its own 127.x.y.z
// address, as a remote attacker would.
#include "test_support.hpp"

#include "headctl/sim/auth_throttle.hpp"

#include <cstdio>
#include <memory>
#include <vector>

namespace gc::headctl::testing {
namespace {

bool starts_with(const std::string& s, std::string_view prefix) { return s.rfind(prefix, 0) == 0; }

constexpr const char* kToken = "s3cret-Token";

HeadServerConfig with_token()
{
    HeadServerConfig config;
    config.port = 0;
    config.token = kToken;
    return config;
}

// Whether the server closes the connection within `limit`: reads (and drops) whatever
// it says until then; the last line read goes to *last.
bool closed_within(LineClient& c, std::chrono::milliseconds limit, std::string* last = nullptr)
{
    const auto end = net::Clock::now() + limit;
    try {
        while (net::Clock::now() < end) {
            const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(end - net::Clock::now());
            if (auto l = c.line(std::max(left, 1ms)); l && last) *last = *l;
        }
    } catch (const net::NetError&) {
        return true;
    }
    return false;
}

// The token holder on 127.0.0.1: greeted, authenticated, answered.
void expect_served(std::uint16_t port)
{
    LineClient good(port);
    EXPECT_TRUE(starts_with(good.line().value_or("<timeout>"), "HELLO GCHP/1"));
    EXPECT_EQ(good.request(std::string("#1 AUTH ") + kToken), "OK #1");
    EXPECT_TRUE(starts_with(good.request("#2 STATUS"), "OK #2 STATE ")) << "the token holder is not served";
}

TEST(HeadSimHostile, IdleConnectionsWithoutTheTokenDoNotLockOutItsHolder)
{
    RunningServer server(with_token());
    // 40 addresses, 4 idle connections each: ten times the default client cap, and more than
    // the server keeps waiting to authenticate.
    std::vector<std::unique_ptr<LineClient>> idle;
    for (int a = 0; a < 40; ++a) {
        const std::string source = "127.0.1." + std::to_string(a + 2);
        for (int k = 0; k < 4; ++k) idle.push_back(std::make_unique<LineClient>(server.port(), source.c_str()));
    }
    expect_served(server.port());
}

TEST(HeadSimHostile, AClientThatDoesNotAuthenticateInTimeIsDropped)
{
    RunningServer server(with_token());
    LineClient authenticated(server.port());
    authenticated.line();
    ASSERT_EQ(authenticated.request(std::string("AUTH ") + kToken), "OK");
    LineClient idle(server.port(), "127.0.2.2");
    LineClient asking(server.port(), "127.0.2.3");     // requests without a token: refused each time
    LineClient trickling(server.port(), "127.0.2.4");  // one byte of a request now and then
    std::atomic<bool> stop{false};
    std::thread drip([&] {
        const std::string request = "#1 STATUS\n";
        for (std::size_t i = 0; !stop; ++i) {
            try {
                asking.send("#2 STATUS\n");
                trickling.send(std::string(1, request[i % request.size()]));
            } catch (const net::NetError&) {
                return;
            }
            std::this_thread::sleep_for(200ms);
        }
    });
    std::string said;
    EXPECT_TRUE(closed_within(idle, 10s, &said)) << "an idle unauthenticated client stays connected";
    EXPECT_TRUE(starts_with(said, "ERR 401 ")) << said;
    EXPECT_TRUE(closed_within(trickling, 10s)) << "a trickling unauthenticated client stays connected";
    EXPECT_TRUE(closed_within(asking, 10s)) << "an unauthenticated client sending requests stays connected";
    stop = true;
    drip.join();
    // The one that did authenticate, and has been idle as long, is still served.
    EXPECT_TRUE(starts_with(authenticated.request("#3 STATUS"), "OK #3 STATE "));
}

TEST(HeadSimHostile, UnauthenticatedConnectionsPerAddressAreLimited)
{
    RunningServer server(with_token());
    std::vector<std::unique_ptr<LineClient>> crowd;
    int greeted = 0, refused = 0;
    for (int k = 0; k < 12; ++k) {
        crowd.push_back(std::make_unique<LineClient>(server.port(), "127.0.3.2"));
        const std::string first = crowd.back()->line().value_or("<timeout>");
        greeted += starts_with(first, "HELLO ");
        refused += starts_with(first, "ERR 503 ");
    }
    EXPECT_GE(greeted, 1);
    EXPECT_LE(greeted, 8) << "one address holds every connection it opens";
    EXPECT_EQ(greeted + refused, 12);
    // Another address is greeted as usual.
    LineClient other(server.port(), "127.0.3.3");
    EXPECT_TRUE(starts_with(other.line().value_or("<timeout>"), "HELLO "));
}

// Wrong tokens cost the guessing address a wait that doubles with every failure, however
// it reconnects; other addresses are not held up.
TEST(HeadSimHostile, WrongTokensAreDelayedPerAddressAcrossReconnections)
{
    RunningServer server(with_token());
    int refusals = 0;
    const auto end = net::Clock::now() + 2s;
    std::vector<std::thread> guessers;
    std::mutex mutex;
    for (int g = 0; g < 3; ++g) {
        guessers.emplace_back([&, g] {
            for (int attempt = 0; net::Clock::now() < end; ++attempt) {
                try {
                    LineClient guesser(server.port(), "127.0.4.2");
                    guesser.line();
                    guesser.send("AUTH guess" + std::to_string(g) + "x" + std::to_string(attempt) + "\n");
                    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(end - net::Clock::now());
                    const auto reply = guesser.line(std::max(left, 1ms));
                    if (reply && starts_with(*reply, "ERR 403 ")) {
                        std::lock_guard lock(mutex);
                        ++refusals;
                    }
                } catch (const net::NetError&) {
                    std::this_thread::sleep_for(5ms);
                }
            }
        });
    }
    std::this_thread::sleep_for(500ms);
    expect_served(server.port());  // from 127.0.0.1, meanwhile
    for (auto& t : guessers) t.join();
    std::printf("%d wrong tokens answered in 2 s\n", refusals);
    EXPECT_GE(refusals, 2);
    EXPECT_LE(refusals, 8) << "wrong tokens are answered as fast as they come";
    // The right token from the guessing address is still taken, after the wait.
    LineClient late(server.port(), "127.0.4.2");
    EXPECT_TRUE(starts_with(late.line().value_or("<timeout>"), "HELLO "));
    late.send(std::string("#5 AUTH ") + kToken + "\n");
    EXPECT_EQ(late.line(10s).value_or("<timeout>"), "OK #5");
}

TEST(HeadSimHostile, RefusesToListenBeyondLoopbackWithoutAToken)
{
    for (const char* host : {"0.0.0.0", "::", "192.0.2.1"}) {
        HeadServerConfig config;
        config.host = host;
        config.port = 0;
        try {
            HeadServer server(config);
            ADD_FAILURE() << host << " was accepted without a token";
        } catch (const std::invalid_argument& e) {
            EXPECT_NE(std::string(e.what()).find("allow-remote"), std::string::npos) << e.what();
        } catch (const std::exception& e) {
            ADD_FAILURE() << host << ": " << e.what();
        }
    }
    for (const char* host : {"127.0.0.1", "127.9.8.7", "::1"}) {
        HeadServerConfig config;
        config.host = host;
        config.port = 0;
        EXPECT_NO_THROW(HeadServer server(config)) << host;
    }
}

TEST(AuthThrottle, WaitsDoubleUpToTheMaximumAndASuccessClearsThem)
{
    AuthThrottle throttle(100ms, 1s, 3);
    const auto t0 = AuthThrottle::Clock::now();
    EXPECT_LE(throttle.next_check("10.0.0.1"), t0);
    std::vector<std::chrono::milliseconds> waits;
    auto t = t0;
    for (int i = 0; i < 6; ++i) {
        throttle.failed("10.0.0.1", t);
        waits.push_back(std::chrono::duration_cast<std::chrono::milliseconds>(throttle.next_check("10.0.0.1") - t));
        t = throttle.next_check("10.0.0.1");
    }
    EXPECT_EQ(waits, (std::vector<std::chrono::milliseconds>{100ms, 200ms, 400ms, 800ms, 1000ms, 1000ms}));
    EXPECT_LE(throttle.next_check("10.0.0.2"), t0);  // another address waits for nothing
    throttle.succeeded("10.0.0.1");
    EXPECT_LE(throttle.next_check("10.0.0.1"), t);
    for (int a = 0; a < 10; ++a) throttle.failed("10.0.1." + std::to_string(a), t);
    EXPECT_LE(throttle.size(), 3u);  // bounded memory, however many addresses fail
}

TEST(AuthThrottle, CountsAnIpv6HostByItsNetwork)
{
    auto key = [](const char* text) {
        sockaddr_storage s{};
        if (::inet_pton(AF_INET, text, &reinterpret_cast<sockaddr_in&>(s).sin_addr) == 1) {
            s.ss_family = AF_INET;
        } else {
            ::inet_pton(AF_INET6, text, &reinterpret_cast<sockaddr_in6&>(s).sin6_addr);
            s.ss_family = AF_INET6;
        }
        return address_key(s);
    };
    EXPECT_EQ(key("192.0.2.7"), "192.0.2.7");
    EXPECT_EQ(key("::ffff:192.0.2.7"), "192.0.2.7");
    EXPECT_EQ(key("2001:db8:1:2:aaaa::1"), key("2001:db8:1:2:bbbb::9"));
    EXPECT_NE(key("2001:db8:1:2::1"), key("2001:db8:1:3::1"));
}

}  // namespace
}  // namespace gc::headctl::testing
