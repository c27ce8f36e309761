// Serial VISCA through a pseudo-terminal pair: the backend opens the terminal side with
// termios as it would /dev/ttyUSB0, a camera answers on the other side. A camera that stays
// silent or sends garbage costs the caller no more than its deadline.
#include "headctl/head_backend.hpp"
#include "headctl/serial_port.hpp"
#include "headctl/visca.hpp"

#include "pty_peer.hpp"
#include "serial_camera.hpp"

#include <gtest/gtest.h>

#include <algorithm>

namespace gc::headctl {
namespace {

using namespace std::chrono_literals;
using testing::step_deadline;
using visca::Bytes;

// A VISCA camera on the far end of a pty pair; silent or babbling on request.
class SerialCamera {
public:
    enum class Mode { Answer, Silent, Garbage };

    explicit SerialCamera(Mode mode = Mode::Answer)
        : mode_(mode), pty_([this](std::span<const std::uint8_t> bytes) { return respond(bytes); })
    {
    }
    const std::string& path() const { return pty_.path(); }
    std::vector<Bytes> received() const { return received_.items(); }

private:
    Bytes respond(std::span<const std::uint8_t> bytes)
    {
        if (mode_ == Mode::Silent) return {};
        if (mode_ == Mode::Garbage) return Bytes(64, 0x5A);  // never an FF: no message ever ends
        Bytes out;
        stream_.insert(stream_.end(), bytes.begin(), bytes.end());
        for (auto end = std::find(stream_.begin(), stream_.end(), 0xFF); end != stream_.end();
             end = std::find(stream_.begin(), stream_.end(), 0xFF)) {
            const Bytes m(stream_.begin(), end + 1);
            stream_.erase(stream_.begin(), end + 1);
            for (const Bytes& r : answer(m)) out.insert(out.end(), r.begin(), r.end());
        }
        return out;
    }

    std::vector<Bytes> answer(const Bytes& m)
    {
        received_.add(m);
        if (m == visca::pan_tilt_position_inquiry(1)) {
            Bytes r{0x90, 0x50};
            for (int v : {pan_, 0})
                for (int shift = 12; shift >= 0; shift -= 4)
                    r.push_back(static_cast<std::uint8_t>((static_cast<std::uint16_t>(v) >> shift) & 0x0F));
            r.push_back(0xFF);
            return {r};
        }
        if (m.size() == 15 && m[3] == 0x02)
            pan_ = static_cast<std::int16_t>((m[6] << 12) | (m[7] << 8) | (m[8] << 4) | m[9]);
        return {Bytes{0x90, 0x41, 0xFF}, Bytes{0x90, 0x51, 0xFF}};
    }

    Mode mode_;
    testing::SharedLog<Bytes> received_;
    Bytes stream_;
    int pan_ = 0;
    testing::PtyPeer pty_;  // last: its thread starts once the rest is built
};

HeadCommand pan_to(double deg)
{
    HeadCommand c{CommandKind::Absolute, {}};
    c.values.set(Axis::Pan, deg);
    return c;
}

TEST(SerialVisca, DrivesACameraOnASerialLine)
{
    SerialCamera camera;
    auto head = testing::opened_backend("visca-serial://" + camera.path() + "?baud=9600");
    EXPECT_DOUBLE_EQ(head->query_state(step_deadline()).pose.pan_deg, 0.0);
    head->send(pan_to(10.0), step_deadline());
    EXPECT_DOUBLE_EQ(head->query_state(step_deadline()).pose.pan_deg, 10.0);
    head->send(preset_command(CommandKind::SavePreset, 2), step_deadline());
    const auto got = camera.received();
    ASSERT_EQ(got.size(), 4u);
    EXPECT_EQ(got[1], visca::pan_tilt_absolute(1, 0x18, 0x14, 160, 0));
    EXPECT_EQ(got[3], visca::memory(1, visca::MemoryAction::Set, 2));
    EXPECT_EQ(head->name(), "visca-serial://" + camera.path());
}

TEST(SerialVisca, ASilentOrBabblingCameraCostsNoMoreThanTheDeadline)
{
    for (const auto mode : {SerialCamera::Mode::Silent, SerialCamera::Mode::Garbage}) {
        SerialCamera camera(mode);
        auto head = make_backend(parse_head_uri("visca-serial://" + camera.path() + "?timeout_ms=200"));
        head->open(net::Clock::now() + 1s);
        const auto start = net::Clock::now();
        // Silent: the reply timeout ends the wait; garbage: no message end within 16 bytes.
        const char* expected = mode == SerialCamera::Mode::Silent ? "did not answer in time" : "unterminated message";
        EXPECT_NE(testing::net_error_of([&] { head->query_state(net::Clock::now() + 1s); }).find(expected),
                  std::string::npos);
        if (mode == SerialCamera::Mode::Garbage) head->open(net::Clock::now() + 1s);  // as the client would
        EXPECT_NE(testing::net_error_of([&] { head->send(pan_to(5.0), net::Clock::now() + 1s); }).find(expected),
                  std::string::npos);
        // Bounded by the reply timeout (200 ms each), not a hang: the suite's timeout would
        // catch a hang, this catches a deadline ignored.
        EXPECT_LT(net::Clock::now() - start, 1900ms);
    }
}

TEST(SerialVisca, UnusablePortsAndRatesAreRefused)
{
    EXPECT_THROW(open_serial_port("/nonexistent/ttyUSB9", 9600), net::NetError);
    EXPECT_THROW(open_serial_port("/dev/null", 9600), net::NetError);  // not a terminal
    EXPECT_THROW(open_serial_port("/dev/null", 1234), std::invalid_argument);
    EXPECT_THROW(parse_head_uri("visca-serial://dev/ttyUSB0"), std::invalid_argument);  // not an absolute path
    EXPECT_THROW(make_backend(parse_head_uri("visca-serial:///dev/ttyUSB0?baud=1234")), std::invalid_argument);
    const HeadUri u = parse_head_uri("visca-serial:///dev/ttyUSB0?baud=38400&address=2");
    EXPECT_EQ(u.path, "/dev/ttyUSB0");
    EXPECT_EQ(to_string(u), "visca-serial:///dev/ttyUSB0?baud=38400&address=2");
}

}  // namespace
}  // namespace gc::headctl
