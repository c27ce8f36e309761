// Pelco-D: exact bytes and checksums, report parsing, and the backend on a pseudo-terminal
// against a camera that answers position queries, keeps presets, or stays silent.
#include "headctl/head_backend.hpp"
#include "headctl/pelco_d.hpp"
#include "pty_peer.hpp"
#include "serial_camera.hpp"

#include <gtest/gtest.h>

#include <map>
#include <thread>

namespace gc::headctl {
namespace {

using namespace std::chrono_literals;
using pelco::Message;
using testing::step_deadline;

TEST(PelcoBytes, MessagesCarryAddressCommandDataAndChecksum)
{
    EXPECT_EQ(pelco::stop(1), (Message{0xFF, 0x01, 0x00, 0x00, 0x00, 0x00, 0x01}));
    pelco::Drive right_up{1, 1, 0, 0x20, 0x10};
    EXPECT_EQ(pelco::drive(1, right_up), (Message{0xFF, 0x01, 0x00, 0x0A, 0x20, 0x10, 0x3B}));
    pelco::Drive left_down_wide{-1, -1, -1, 0x50, 0x3F};
    EXPECT_EQ(pelco::drive(2, left_down_wide), (Message{0xFF, 0x02, 0x00, 0x54, 0x3F, 0x3F, 0xD4}));
    EXPECT_EQ(pelco::preset(1, pelco::PresetAction::Set, 3), (Message{0xFF, 0x01, 0x00, 0x03, 0x00, 0x03, 0x07}));
    EXPECT_EQ(pelco::preset(1, pelco::PresetAction::GoTo, 3), (Message{0xFF, 0x01, 0x00, 0x07, 0x00, 0x03, 0x0B}));
    EXPECT_EQ(pelco::set_pan(1, 9000), (Message{0xFF, 0x01, 0x00, 0x4B, 0x23, 0x28, 0x97}));
    EXPECT_EQ(pelco::query_pan(1), (Message{0xFF, 0x01, 0x00, 0x51, 0x00, 0x00, 0x52}));
    EXPECT_THROW(pelco::stop(0), pelco::PelcoError);
    EXPECT_THROW(pelco::preset(1, pelco::PresetAction::Set, 0), pelco::PelcoError);
    EXPECT_THROW(pelco::set_pan(1, 36000), pelco::PelcoError);
    const Message report{0xFF, 0x01, 0x00, 0x59, 0x8C, 0x9F, 0x85};
    const auto r = pelco::parse_report(report);
    ASSERT_TRUE(r);
    EXPECT_EQ(r->reading, pelco::Reading::Pan);
    EXPECT_EQ(r->value, 35999);
    Message bad = report;
    bad[6] ^= 1;
    EXPECT_THROW(pelco::parse_report(bad), pelco::PelcoError);
    EXPECT_FALSE(pelco::parse_report(pelco::stop(1)));
}

// A Pelco-D dome on the far end of a pty: answers position queries, moves on set-position
// and preset messages at once; or stays silent.
class PelcoCamera {
public:
    explicit PelcoCamera(bool silent = false)
        : silent_(silent), pty_([this](std::span<const std::uint8_t> bytes) { return respond(bytes); })
    {
    }
    const std::string& path() const { return pty_.path(); }
    std::vector<Message> received() const { return received_.items(); }

private:
    std::vector<std::uint8_t> respond(std::span<const std::uint8_t> bytes)
    {
        std::vector<std::uint8_t> out;
        stream_.insert(stream_.end(), bytes.begin(), bytes.end());
        while (stream_.size() >= 7) {
            Message m{};
            std::copy_n(stream_.begin(), 7, m.begin());
            stream_.erase(stream_.begin(), stream_.begin() + 7);
            received_.add(m);
            if (silent_) continue;
            const int value = (m[4] << 8) | m[5];
            auto reply = [&](std::uint8_t kind, int v) {
                Message r{0xFF, m[1], 0x00, kind, static_cast<std::uint8_t>(v >> 8), static_cast<std::uint8_t>(v), 0};
                r[6] = static_cast<std::uint8_t>(r[1] + r[2] + r[3] + r[4] + r[5]);
                out.insert(out.end(), {0x00, 0x13});  // line noise before the report: skipped
                out.insert(out.end(), r.begin(), r.end());
            };
            switch (m[3]) {
            case 0x4B:
                pan_ = value;
                break;
            case 0x4D:
                tilt_ = value;
                break;
            case 0x03:
                presets_[value] = {pan_, tilt_};
                break;
            case 0x07:
                std::tie(pan_, tilt_) = presets_[value];
                break;
            case 0x51:
                reply(0x59, pan_);
                break;
            case 0x53:
                reply(0x5B, tilt_);
                break;
            default:
                break;
            }
        }
        return out;
    }

    bool silent_;
    testing::SharedLog<Message> received_;
    std::vector<std::uint8_t> stream_;
    int pan_ = 0, tilt_ = 0;
    std::map<int, std::pair<int, int>> presets_;
    testing::PtyPeer pty_;  // last: its thread starts once the rest is built
};

HeadCommand move(CommandKind kind, double pan, double tilt)
{
    HeadCommand c{kind, {}};
    c.values.set(Axis::Pan, pan);
    c.values.set(Axis::Tilt, tilt);
    return c;
}

TEST(PelcoBackend, MovesReadsBackAndKeepsPresets)
{
    PelcoCamera camera;
    auto head = testing::opened_backend("pelco-d://" + camera.path() + "?address=1&baud=2400");
    head->send(move(CommandKind::Absolute, -30.0, 10.0), step_deadline());
    HeadState s = head->query_state(step_deadline());
    EXPECT_DOUBLE_EQ(s.pose.pan_deg, -30.0);  // 330.00 deg on the camera
    EXPECT_DOUBLE_EQ(s.pose.tilt_deg, 10.0);
    head->send(preset_command(CommandKind::SavePreset, 4), step_deadline());
    head->send(HeadCommand{CommandKind::Home, {}}, step_deadline());
    EXPECT_DOUBLE_EQ(head->query_state(step_deadline()).pose.pan_deg, 0.0);
    head->send(preset_command(CommandKind::RecallPreset, 4), step_deadline());
    s = head->query_state(step_deadline());
    EXPECT_DOUBLE_EQ(s.pose.pan_deg, -30.0);
    EXPECT_DOUBLE_EQ(s.pose.tilt_deg, 10.0);
    head->send(move(CommandKind::Velocity, 50.0, -30.0), step_deadline());
    head->send(HeadCommand{CommandKind::Stop, {}}, step_deadline());

    // Nothing acknowledges the last two: wait until the camera has read them.
    for (int i = 0; i < 100 && camera.received().size() < 14; ++i) std::this_thread::sleep_for(10ms);
    const auto got = camera.received();
    ASSERT_EQ(got.size(), 14u);
    EXPECT_EQ(got[0], pelco::set_pan(1, 33000));
    EXPECT_EQ(got[4], pelco::preset(1, pelco::PresetAction::Set, 5));  // library preset 4 is Pelco's 5
    EXPECT_EQ(got[9], pelco::preset(1, pelco::PresetAction::GoTo, 5));
    EXPECT_EQ(got[got.size() - 2], pelco::drive(1, pelco::Drive{1, -1, 0, 0x20, 0x20}));
    EXPECT_EQ(got.back(), pelco::stop(1));
}

TEST(PelcoBackend, ASilentCameraCostsNoMoreThanTheDeadline)
{
    PelcoCamera camera(true);
    auto head = make_backend(parse_head_uri("pelco-d://" + camera.path() + "?timeout_ms=200"));
    head->open(net::Clock::now() + 1s);
    const auto start = net::Clock::now();
    const std::string error = testing::net_error_of([&] { head->query_state(net::Clock::now() + 1s); });
    EXPECT_NE(error.find("did not answer in time"), std::string::npos) << error;
    EXPECT_LT(net::Clock::now() - start, 900ms);
    HeadCommand verge{CommandKind::Absolute, {}};
    verge.values.set(Axis::VergeLeft, 1.0);
    EXPECT_THROW(head->send(verge, net::Clock::now() + 1s), HeadRejected);
    EXPECT_THROW(make_backend(parse_head_uri("pelco-d:///dev/ttyUSB0?address=0")), std::invalid_argument);
}

}  // namespace
}  // namespace gc::headctl
