// What an element needs to use a head client from GStreamer: the head's state samples and
// the buffers' capture times on one time line (the pipeline clock), and connection changes
// reported on the bus.
#pragma once

#include "headctl/head_backend.hpp"
#include "headctl/head_client.hpp"
#include "headctl/steering/head_link.hpp"

#include <gst/gst.h>

#include <functional>
#include <string>

namespace gc::gst {

// The element's pipeline clock as a head client clock. Without a clock (not yet playing)
// it reads steady_clock, which is also what GStreamer's default system clock reads.
std::function<headctl::Timestamp()> element_clock(GstElement* element);

// When the frame at `running_time` was captured, on element_clock: base time + running
// time; the clock's now when the running time or the base time is unknown.
headctl::Timestamp capture_time(GstElement* element, GstClockTime running_time);

// A connection-change callback for the head client (called on its thread) that posts on
// the element's bus: a `head-connection` element message (uri, state, error) for every
// change between connected and not, a warning when the head is lost or cannot be reached
// (once per outage, not once per retry) and an info message when it is back. The URI is
// shown with its token hidden. Every change, each retry's failure included, is also logged in
// the gesturecam-head debug category (INFO).
std::function<void(headctl::ConnectionState, const std::string&)> connection_reporter(GstElement* element,
                                                                                      const std::string& uri);

// A steering-event callback for the head link: logs each event (INFO in the gesturecam-head
// debug category) and posts a `head-steering` element message (event, detail), so an
// application sees the head look at a target, come back, and pause after someone else
// moved it.
std::function<void(headctl::SteeringEvent, const std::string&)> steering_reporter(GstElement* element);

// A command callback for the head link that logs each command sent to the head (DEBUG in
// the gesturecam-head debug category, with the element as the object).
std::function<void(const headctl::HeadCommand&)> command_logger(GstElement* element);

}  // namespace gc::gst
