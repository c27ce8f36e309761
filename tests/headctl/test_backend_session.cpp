// One scripted session through the backend interface leaves the same head state over
// headsim's GCHP, ONVIF and VISCA (over IP and over TCP) responders; the VISCA responder's own answers; and
// silent or garbage cameras of every protocol, which must fail a request by its timeout and
// never make the client's callers wait.
#include "session_support.hpp"
#include "test_support.hpp"

#include "headctl/head_client.hpp"
#include "headctl/visca.hpp"

#include <cstdio>
#include <functional>

namespace gc::headctl::testing {
namespace {

using visca::Bytes;

// A UDP peer on 127.0.0.1 in place of a VISCA-over-IP camera: acknowledges the sequence reset
// when told to, and answers every other datagram with what `answer` gives for its sequence
// number (nothing: a silent camera).
class HostileViscaPeer {
public:
    using Answer = std::function<std::vector<Bytes>(std::uint32_t sequence)>;
    HostileViscaPeer(bool acknowledge_reset, Answer answer)
        : acknowledge_reset_(acknowledge_reset), answer_(std::move(answer))
    {
        sockaddr_storage addr{};
        const socklen_t len = numeric_address("127.0.0.1", 0, addr);
        fd_ = net::Fd(::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0));
        if (!fd_ || ::bind(fd_.get(), reinterpret_cast<sockaddr*>(&addr), len) != 0)
            throw net::NetError("cannot bind a UDP peer");
        port_ = bound_port(fd_.get());
        thread_ = std::thread([this] { run(); });
    }
    ~HostileViscaPeer()
    {
        stop_ = true;
        thread_.join();
    }
    std::string uri(const std::string& query = "") const
    {
        return "visca-udp://127.0.0.1:" + std::to_string(port_) + query;
    }

private:
    void run()
    {
        while (!stop_) {
            pollfd p{fd_.get(), POLLIN, 0};
            if (::poll(&p, 1, 20) <= 0) continue;
            std::array<std::uint8_t, 64> in{};
            sockaddr_storage from{};
            socklen_t from_len = sizeof from;
            const ssize_t n =
                ::recvfrom(fd_.get(), in.data(), in.size(), 0, reinterpret_cast<sockaddr*>(&from), &from_len);
            if (n < static_cast<ssize_t>(visca::kIpHeaderSize)) continue;
            const auto m = visca::unwrap_ip(std::span<const std::uint8_t>(in.data(), static_cast<std::size_t>(n)));
            std::vector<Bytes> out;
            if (m.payload_type == visca::kIpControl) {
                if (acknowledge_reset_) out.push_back(visca::wrap_ip(visca::kIpControlReply, m.sequence, m.payload));
            } else {
                out = answer_(m.sequence);
            }
            for (const Bytes& d : out)
                ::sendto(fd_.get(), d.data(), d.size(), 0, reinterpret_cast<sockaddr*>(&from), from_len);
        }
    }

    bool acknowledge_reset_;
    Answer answer_;
    net::Fd fd_;
    std::uint16_t port_ = 0;
    std::atomic<bool> stop_{false};
    std::thread thread_;
};

HostileViscaPeer::Answer say_nothing()
{
    return [](std::uint32_t) { return std::vector<Bytes>{}; };
}

std::unique_ptr<HeadBackend> opened(const std::string& uri)
{
    auto head = make_backend(parse_head_uri(uri));
    head->open(net::Clock::now() + 2s);
    return head;
}

// The NetError a state inquiry with a 30 s deadline throws, and how long it took.
std::pair<std::string, double> inquiry_failure(HeadBackend& head)
{
    const auto start = net::Clock::now();
    std::string error = "<no NetError>";
    try {
        head.query_state(net::Clock::now() + 30s);
    } catch (const net::NetError& e) {
        error = e.what();
    }
    return {error, std::chrono::duration<double, std::milli>(net::Clock::now() - start).count()};
}

TEST(BackendSession, TheSameSessionLeavesTheSameStateOverGchpOnvifAndVisca)
{
    RunningSimHead for_gchp, for_onvif, for_visca, for_visca_tcp;
    const HeadState gchp = run_session(for_gchp.gchp_uri());
    const HeadState onvif = run_session(for_onvif.onvif_uri());
    const HeadState visca = run_session(for_visca.visca_uri());
    const HeadState visca_tcp = run_session(for_visca_tcp.visca_uri("visca-tcp"));
    for (const auto& [name, s] :
         {std::pair{"gchp", gchp}, {"onvif", onvif}, {"visca-udp", visca}, {"visca-tcp", visca_tcp}})
        std::printf("%-9s pan %.4f tilt %.4f zoom %.5f\n", name, s.pose.pan_deg, s.pose.tilt_deg, s.pose.zoom);
    expect_pose(gchp.pose, 30, -10, 4);
    for (const HeadState& other : {onvif, visca, visca_tcp}) {
        expect_pose(other.pose, gchp.pose.pan_deg, gchp.pose.tilt_deg, gchp.pose.zoom);
        EXPECT_EQ(other.moving, gchp.moving);
    }
    // The VISCA session moved the head itself: its GCHP side sees the same pose.
    expect_pose(settled(*opened(for_visca.gchp_uri())).pose, 30, -10, 4);
}

TEST(ViscaResponder, DrivesRelativeMovesAndStopsTheHead)
{
    RunningSimHead sim;
    auto head = opened(sim.visca_uri());
    auto gchp = opened(sim.gchp_uri());
    head->send(absolute(10, 5, 1), net::Clock::now() + 1s);
    HeadCommand relative{CommandKind::Relative, {}};
    relative.values.set(Axis::Pan, 5);
    relative.values.set(Axis::Tilt, -7.5);
    head->send(relative, net::Clock::now() + 1s);
    expect_pose(settled(*gchp).pose, 15, -2.5, 1);

    HeadCommand drive{CommandKind::Velocity, {}};
    drive.values.set(Axis::Pan, -60);  // right to left
    drive.values.set(Axis::Tilt, 30);  // upwards
    drive.values.set(Axis::Zoom, 4);   // towards tele
    head->send(drive, net::Clock::now() + 1s);
    std::this_thread::sleep_for(300ms);
    const HeadState driving = gchp->query_state(net::Clock::now() + 1s);
    EXPECT_LT(driving.pose.pan_deg, 14.0);
    EXPECT_GT(driving.pose.tilt_deg, -1.5);
    EXPECT_GT(driving.pose.zoom, 1.2);
    EXPECT_TRUE(driving.moving_axis(Axis::Pan));
    head->send(HeadCommand{CommandKind::Stop, {}}, net::Clock::now() + 1s);
    const HeadState stopped = settled(*gchp);
    EXPECT_FALSE(stopped.moving_axis(Axis::Pan) || stopped.moving_axis(Axis::Tilt) || stopped.moving_axis(Axis::Zoom));
    std::this_thread::sleep_for(100ms);
    expect_pose(gchp->query_state(net::Clock::now() + 1s).pose, stopped.pose.pan_deg, stopped.pose.tilt_deg,
                stopped.pose.zoom, 1e-9);
}

TEST(ViscaResponder, RefusesWhatTheHeadCannotDoAndAnswersUnknownMessagesWithASyntaxError)
{
    RunningSimHead sim;
    auto head = opened(sim.visca_uri());
    const auto refusal = [&](const HeadCommand& c) {
        try {
            head->send(c, net::Clock::now() + 1s);
        } catch (const HeadRejected& e) {
            return std::string(e.what());
        }
        return std::string("<accepted>");
    };
    EXPECT_NE(refusal(absolute(175, 0, 1)).find("refused: command not executable"), std::string::npos);
    EXPECT_NE(refusal(preset_command(CommandKind::RecallPreset, 9)).find("not executable"), std::string::npos);
    expect_pose(head->query_state(net::Clock::now() + 1s).pose, 0, 0, 1);  // nothing moved

    // What the backend never sends: raw datagrams to the responder's port.
    HeadModel model(HeadModelConfig{});
    const auto reply_to = [&](const Bytes& payload) {
        return answer_visca_datagram(model, 0.0, visca::wrap_ip(visca::kIpCommand, 7, payload), ViscaUnits{});
    };
    EXPECT_EQ(reply_to({0x81, 0x01, 0x7E, 0x01, 0xFF}),
              std::vector<Bytes>{visca::wrap_ip(visca::kIpReply, 7, Bytes{0x90, 0x60, 0x02, 0xFF})});
    EXPECT_EQ(reply_to({0x83, 0x01, 0x06, 0x02, 0x19, 0x01, 0, 0, 0, 0, 0, 0, 0, 0, 0xFF}),  // pan speed 0x19
              std::vector<Bytes>{visca::wrap_ip(visca::kIpReply, 7, Bytes{0xB0, 0x60, 0x02, 0xFF})});
    EXPECT_EQ(reply_to(visca::memory(2, visca::MemoryAction::Reset, 1)),
              std::vector<Bytes>{visca::wrap_ip(visca::kIpReply, 7, Bytes{0xA0, 0x61, 0x41, 0xFF})});
    EXPECT_EQ(reply_to(visca::pan_tilt_home(1)),
              (std::vector<Bytes>{visca::wrap_ip(visca::kIpReply, 7, visca::ack(1, 1)),
                                  visca::wrap_ip(visca::kIpReply, 7, visca::completion(1, 1))}));
    Bytes truncated = visca::wrap_ip(visca::kIpCommand, 7, visca::pan_tilt_home(1));
    truncated.pop_back();
    EXPECT_TRUE(answer_visca_datagram(model, 0.0, truncated, ViscaUnits{}).empty());
}

// Over TCP a message without its end within 16 bytes is a length error, and the stream is
// read again from the next FF on.
TEST(ViscaResponder, AnOverlongTcpMessageIsALengthErrorAndTheStreamCarriesOn)
{
    RunningSimHead sim;
    const std::uint16_t port = parse_head_uri(sim.visca_uri("visca-tcp")).port;
    net::Fd fd = connect_from("127.0.0.1", port);
    Bytes sent(20, 0x01);
    sent.push_back(0xFF);
    const Bytes inquiry = visca::pan_tilt_position_inquiry(1);
    sent.insert(sent.end(), inquiry.begin(), inquiry.end());
    net::send_all(fd.get(), std::span<const std::uint8_t>(sent), net::Clock::now() + 1s);
    Bytes got;
    const Bytes expected = [] {
        Bytes e = visca::error_reply(1, 0, 0x01);
        const Bytes position = visca::position_reply(1, 0, 0);
        e.insert(e.end(), position.begin(), position.end());
        return e;
    }();
    std::array<std::uint8_t, 64> buffer{};
    while (got.size() < expected.size()) {
        const auto n = net::receive_some(fd.get(), buffer, net::Clock::now() + 2s);
        if (!n) break;
        got.insert(got.end(), buffer.begin(), buffer.begin() + static_cast<std::ptrdiff_t>(*n));
    }
    EXPECT_EQ(got, expected);
}

TEST(ViscaResponder, ServesBeyondLoopbackOnlyWhenAllowed)
{
    HeadServerConfig gchp;
    gchp.port = 0;
    gchp.token = "a-token-for-gchp-only";
    HeadServer server(gchp);
    ViscaResponderConfig visca;
    visca.port = 0;
    visca.host = "0.0.0.0";
    try {
        ViscaResponder refused(visca, server);
        ADD_FAILURE() << "served VISCA on 0.0.0.0 without being allowed to";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("VISCA has no authentication"), std::string::npos) << e.what();
    }
    visca.allow_remote = true;
    EXPECT_NO_THROW(ViscaResponder allowed(visca, server));
}

TEST(ViscaPeers, ASilentCameraFailsTheConnectionByItsDeadline)
{
    HostileViscaPeer silent(false, say_nothing());
    auto head = make_backend(parse_head_uri(silent.uri()));
    const auto start = net::Clock::now();
    EXPECT_THROW(head->open(net::Clock::now() + 300ms), net::NetError);
    std::printf("silent camera: open failed after %.0f ms (deadline 300 ms)\n",
                std::chrono::duration<double, std::milli>(net::Clock::now() - start).count());
}

// Cameras that take the connection and then answer nothing, or garbage: each request fails by
// the 200 ms reply timeout (the bound leaves room for a loaded machine), long before the
// caller's 30 s deadline, or at once when what came cannot be a reply.
TEST(ViscaPeers, SilenceOrGarbageAfterConnectingFailsARequestByTheReplyTimeout)
{
    HostileViscaPeer mute(true, say_nothing());
    HostileViscaPeer junk(true, [](std::uint32_t) { return std::vector<Bytes>{Bytes{0x01, 0x11, 0x00, 0x09, 0xFF}}; });
    HostileViscaPeer wrong(true, [](std::uint32_t sequence) {
        return std::vector<Bytes>{visca::wrap_ip(visca::kIpReply, sequence, Bytes{0x12, 0x34, 0xFF})};
    });
    ScriptedServer mute_tcp("", true);
    ScriptedServer junk_tcp(std::string(20, 'x'), true);
    const std::string tcp = "visca-tcp://127.0.0.1:";
    for (const auto& [uri, expected] : {std::pair{mute.uri(), "did not answer in time"},
                                        {junk.uri(), "did not answer in time"},
                                        {wrong.uri(), "has a bad header byte"},
                                        {tcp + std::to_string(mute_tcp.port()), "did not answer in time"},
                                        {tcp + std::to_string(junk_tcp.port()), "sent an unterminated message"}}) {
        auto head = opened(uri + "?timeout_ms=200");
        const auto [error, ms] = inquiry_failure(*head);
        std::printf("%s after %.0f ms\n", error.c_str(), ms);
        EXPECT_NE(error.find(expected), std::string::npos) << error;
        EXPECT_LT(ms, 5000.0);
    }
}

// A silent camera of any protocol: the streaming thread's calls into the client return at
// once, and the client keeps trying to connect.
TEST(ViscaPeers, TheClientsCallersNeverWaitOnASilentCameraOfAnyProtocol)
{
    ScriptedServer gchp("", true);
    HttpScriptedServer onvif("");
    HostileViscaPeer visca(false, say_nothing());
    for (const std::string& uri : {gchp.uri(), onvif.uri(), visca.uri("?zoom_max=20")}) {
        HeadClientConfig config;
        config.uri = uri;
        config.connect_timeout = 2000ms;
        HeadClient client(config);
        std::this_thread::sleep_for(50ms);
        const double worst_us = longest_call_us(200, [&](int i) {
            client.submit(absolute(i % 10, 0, 1));
            client.pose_at(client.now());
        });
        std::printf("%s: longest call %.0f us\n", uri.c_str(), worst_us);
        EXPECT_LT(worst_us, 100000.0) << uri;  // scheduling noise only: far below the 2 s connect timeout
        EXPECT_EQ(client.state(), ConnectionState::Connecting) << uri;
    }
}

}  // namespace
}  // namespace gc::headctl::testing
