// A scripted session through the one backend interface, and what the tests read from a head
// once it has come to rest.
#pragma once

#include "headctl/head_backend.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <memory>
#include <string>
#include <thread>

namespace gc::headctl::testing {

inline HeadCommand absolute(double pan, double tilt, double zoom)
{
    HeadCommand c{CommandKind::Absolute, {}};
    c.values.set(Axis::Pan, pan);
    c.values.set(Axis::Tilt, tilt);
    c.values.set(Axis::Zoom, zoom);
    return c;
}

// The state once no axis moves (or after 5 s).
inline HeadState settled(HeadBackend& head)
{
    using namespace std::chrono_literals;
    HeadState s = head.query_state(net::Clock::now() + 1s);
    for (int i = 0; i < 250; ++i) {
        std::this_thread::sleep_for(20ms);
        s = head.query_state(net::Clock::now() + 1s);
        if (std::none_of(s.moving.begin(), s.moving.end(), [](bool m) { return m; })) break;
    }
    return s;
}

inline void expect_pose(const HeadPose& pose, double pan, double tilt, double zoom, double tolerance = 1e-3)
{
    EXPECT_NEAR(pose.pan_deg, pan, tolerance);
    EXPECT_NEAR(pose.tilt_deg, tilt, tolerance);
    EXPECT_NEAR(pose.zoom, zoom, tolerance);
}

// Home, a move, a zoom, preset 5 saved, a move elsewhere, preset 5 recalled, stop: the state
// the head comes to rest in.
inline HeadState run_session(const std::string& uri)
{
    using namespace std::chrono_literals;
    auto head = make_backend(parse_head_uri(uri));
    const auto soon = [] { return net::Clock::now() + 1s; };
    head->open(soon());
    head->send(HeadCommand{CommandKind::Home, {}}, soon());
    head->send(absolute(30, -10, 1), soon());
    settled(*head);
    HeadCommand zoom{CommandKind::Absolute, {}};
    zoom.values.set(Axis::Zoom, 4);
    head->send(zoom, soon());
    settled(*head);
    head->send(preset_command(CommandKind::SavePreset, 5), soon());
    head->send(absolute(-40, 20, 2), soon());
    settled(*head);
    head->send(preset_command(CommandKind::RecallPreset, 5), soon());
    settled(*head);
    head->send(HeadCommand{CommandKind::Stop, {}}, soon());
    return settled(*head);
}

}  // namespace gc::headctl::testing
