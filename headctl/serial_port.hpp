// A serial line (RS-232/RS-485 adapter, or a pseudo-terminal in tests) opened raw, 8N1,
// without flow control, non-blocking: the byte layer of serial VISCA and Pelco-D.
#pragma once

#include "headctl/net.hpp"
#include "headctl/uri.hpp"

#include <chrono>
#include <string>

namespace gc::headctl {

// The rates the serial heads use; anything else is refused.
bool is_supported_baud(int baud);

// Opens `path` at `baud` bits per second and discards whatever was waiting on the line.
// Throws net::NetError naming the path when it cannot be opened or configured, and
// std::invalid_argument for an unsupported rate.
net::Fd open_serial_port(const std::string& path, int baud);

// The URI parameters the serial protocols' heads share (VISCA's over IP too); each throws
// std::invalid_argument for a value out of range. "address": the head's address on the line,
// an integer in 1..max_address.
int address_param(const HeadUri& uri, int max_address);
// "baud": a rate is_supported_baud accepts.
int baud_param(const HeadUri& uri, int fallback);
// "timeout_ms": how long to wait for a reply, 1 ms to 1 minute.
std::chrono::milliseconds reply_timeout_param(const HeadUri& uri, std::chrono::milliseconds fallback);

}  // namespace gc::headctl
