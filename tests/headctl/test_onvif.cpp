// The ONVIF PTZ backend against the simulated head's ONVIF responder on loopback: each
// operation, the UsernameToken digest, faults, and cameras that say nothing or garbage
// (test_backend_session.cpp runs the same session over every protocol).
#include "session_support.hpp"
#include "test_support.hpp"

#include "headctl/onvif_backend.hpp"
#include "headctl/onvif_soap.hpp"

#include <cmath>

namespace gc::headctl::testing {
namespace {

constexpr const char* kPassword = "pa55-Word";

using OnvifHead = RunningSimHead;

OnvifResponderConfig with_password()
{
    OnvifResponderConfig c;
    c.user = "operator";
    c.password = kPassword;
    return c;
}

std::unique_ptr<HeadBackend> open_backend(const std::string& uri, const std::string& password = {})
{
    auto backend = make_backend(parse_head_uri(uri), password);
    backend->open(net::Clock::now() + 2s);
    return backend;
}

std::string net_error_of(const std::function<void()>& f)
{
    try {
        f();
    } catch (const net::NetError& e) {
        return e.what();
    }
    return "<no NetError>";
}

TEST(Onvif, EveryOperationReachesTheHead)
{
    OnvifHead head;
    auto onvif = open_backend(head.onvif_uri());
    EXPECT_EQ(onvif->axes(), (std::array<bool, kAxisCount>{true, true, false, false, true}));
    expect_pose(onvif->query_state(net::Clock::now() + 1s).pose, 0, 0, 1);

    onvif->send(absolute(10, 5, 2), net::Clock::now() + 1s);
    expect_pose(settled(*onvif).pose, 10, 5, 2);
    onvif->send(preset_command(CommandKind::SavePreset, 3), net::Clock::now() + 1s);
    const auto presets = dynamic_cast<OnvifBackend&>(*onvif).presets(net::Clock::now() + 1s);
    ASSERT_EQ(presets.size(), 1u);
    EXPECT_EQ(presets.front().token, "3");

    onvif->send(HeadCommand{CommandKind::Home, {}}, net::Clock::now() + 1s);
    expect_pose(settled(*onvif).pose, 0, 0, 1);
    onvif->send(preset_command(CommandKind::RecallPreset, 3), net::Clock::now() + 1s);
    expect_pose(settled(*onvif).pose, 10, 5, 2);

    HeadCommand relative{CommandKind::Relative, {}};
    relative.values.set(Axis::Tilt, -15);
    onvif->send(relative, net::Clock::now() + 1s);
    expect_pose(settled(*onvif).pose, 10, -10, 2);

    HeadCommand velocity{CommandKind::Velocity, {}};
    velocity.values.set(Axis::Pan, 30);
    onvif->send(velocity, net::Clock::now() + 1s);
    std::this_thread::sleep_for(200ms);
    const HeadState driving = onvif->query_state(net::Clock::now() + 1s);
    EXPECT_TRUE(driving.moving_axis(Axis::Pan));
    EXPECT_FALSE(driving.moving_axis(Axis::Tilt));  // one MoveStatus for both: the positions tell
    EXPECT_GT(driving.pose.pan_deg, 10.5);
    onvif->send(HeadCommand{CommandKind::Stop, {}}, net::Clock::now() + 1s);
    const double stopped_at = settled(*onvif).pose.pan_deg;
    std::this_thread::sleep_for(100ms);
    EXPECT_NEAR(onvif->query_state(net::Clock::now() + 1s).pose.pan_deg, stopped_at, 1e-6);
}

TEST(Onvif, RefusalsAreClearAndKeepTheConnection)
{
    OnvifHead head;
    auto onvif = open_backend(head.onvif_uri());
    try {
        onvif->send(preset_command(CommandKind::RecallPreset, 9), net::Clock::now() + 1s);
        ADD_FAILURE() << "recalling a preset never saved was accepted";
    } catch (const HeadRejected& e) {
        EXPECT_NE(std::string(e.what()).find("GotoPreset refused (NoToken)"), std::string::npos) << e.what();
    }
    // Outside the range the URI assumes: refused before anything is sent.
    EXPECT_THROW(onvif->send(absolute(200, 0, 1), net::Clock::now() + 1s), HeadRejected);
    expect_pose(onvif->query_state(net::Clock::now() + 1s).pose, 0, 0, 1);
}

TEST(Onvif, TheResponderFaultsUnknownOperationsAndMalformedRequests)
{
    OnvifHead head;
    onvif::PtzRequest unknown;
    unknown.operation = "RelativeFocus";
    const auto [status, text] = head.responder().answer(onvif::request_envelope(unknown, std::nullopt), "127.0.0.1");
    EXPECT_EQ(status, 500u);
    const auto fault = onvif::fault(onvif::parse_envelope(text));
    ASSERT_TRUE(fault);
    EXPECT_EQ(fault->code, "Receiver");
    EXPECT_EQ(fault->subcode, "ActionNotSupported");

    const auto [garbage_status, garbage] = head.responder().answer("<not-soap/>", "127.0.0.1");
    EXPECT_EQ(garbage_status, 400u);
    EXPECT_EQ(onvif::fault(onvif::parse_envelope(garbage))->subcode, "WellFormed");
}

TEST(Onvif, TheDigestIsBase64OfSha1OfNonceCreatedAndPassword)
{
    // SHA-1 of the bytes "abc" + "2026-01-01T00:00:00Z" + "pw", computed independently.
    EXPECT_EQ(onvif::password_digest("YWJj", "2026-01-01T00:00:00Z", "pw"), "ZWMgpsf8HXK3Tg3pmzuIdhh1Db4=");
    EXPECT_THROW(onvif::password_digest("not base64!", "x", "pw"), onvif::SoapError);
}

TEST(Onvif, TheRightPasswordIsServedAndAWrongOneRefusedByName)
{
    OnvifHead head(with_password());
    auto ok = open_backend(head.onvif_uri("?user=operator"), kPassword);
    ok->send(absolute(-20, 10, 1), net::Clock::now() + 1s);
    expect_pose(settled(*ok).pose, -20, 10, 1);

    const std::string wrong = net_error_of([&] { open_backend(head.onvif_uri("?user=operator"), "guess"); });
    EXPECT_NE(wrong.find("refused the credentials of user operator"), std::string::npos) << wrong;
    EXPECT_EQ(wrong.find("guess"), std::string::npos) << "the password appears in: " << wrong;
    const std::string none = net_error_of([&] { open_backend(head.onvif_uri()); });
    EXPECT_NE(none.find("refused the credentials (none given"), std::string::npos) << none;
}

TEST(Onvif, ASilentCameraTimesOutByItsDeadline)
{
    HttpScriptedServer silent("");
    const std::string error = net_error_of([&] { open_backend(silent.uri("?timeout_ms=300")); });
    EXPECT_NE(error.find("did not answer in time"), std::string::npos) << error;
}

TEST(Onvif, GarbageIsAnErrorNamingWhatCame)
{
    HttpScriptedServer garbage("HTTP/1.1 200 OK\r\nContent-Length: 11\r\n\r\nhello world");
    const std::string error = net_error_of([&] { open_backend(garbage.uri()); });
    EXPECT_NE(error.find("HTTP 200 without a SOAP reply (not well-formed XML)"), std::string::npos) << error;

    const std::string soap = onvif::empty_response("Stop");
    HttpScriptedServer other("HTTP/1.1 200 OK\r\nContent-Length: " + std::to_string(soap.size()) + "\r\n\r\n" + soap);
    const std::string wrong = net_error_of([&] { open_backend(other.uri()); });
    EXPECT_NE(wrong.find("expected GetStatusResponse, got StopResponse"), std::string::npos) << wrong;

    HttpScriptedServer endless("HTTP/1.1 200 OK\r\nContent-Length: 100000000\r\n\r\n" + std::string(200000, '<'));
    const std::string big = net_error_of([&] { open_backend(endless.uri()); });
    EXPECT_NE(big.find("a reply longer than 65536 bytes"), std::string::npos) << big;
}

// A reply just under the limit is read whole, whatever size its last chunk has.
TEST(Onvif, AReplyJustUnderTheLimitIsTaken)
{
    std::string soap = onvif::status_response({});
    soap.resize(onvif::kMaxMessageBytes - 1500, ' ');  // white space after the envelope
    HttpScriptedServer near_limit("HTTP/1.1 200 OK\r\nContent-Length: " + std::to_string(soap.size()) + "\r\n\r\n" +
                                  soap);
    EXPECT_EQ(net_error_of([&] { open_backend(near_limit.uri()); }), "<no NetError>");
}

TEST(Onvif, SilentAndOversizedRequestsDoNotHoldOthersUp)
{
    OnvifHead head;
    std::vector<std::unique_ptr<LineClient>> idle;
    for (int i = 0; i < 20; ++i) idle.push_back(std::make_unique<LineClient>(head.onvif_port()));
    idle.front()->send("POST /onvif/ptz_service HTTP/1.1\r\nHost: x\r\n");  // headers never finished
    LineClient oversized(head.onvif_port());
    oversized.send("POST /onvif/ptz_service HTTP/1.1\r\nHost: x\r\nContent-Length: 100000000\r\n\r\n");
    EXPECT_THROW(oversized.line(2000ms), net::NetError);  // closed without reading the body

    auto onvif = open_backend(head.onvif_uri());
    onvif->send(absolute(5, 0, 1), net::Clock::now() + 1s);
    expect_pose(settled(*onvif).pose, 5, 0, 1);
}

}  // namespace
}  // namespace gc::headctl::testing
