// A serial line (RS-232/RS-485 adapter, or a pseudo-terminal in tests) opened raw, 8N1,
// without flow control, non-blocking: the byte layer of serial VISCA and Pelco-D.
#pragma once

#include "headctl/net.hpp"

#include <string>

namespace gc::headctl {

// The rates the serial heads use; anything else is refused.
bool is_supported_baud(int baud);

// Opens `path` at `baud` bits per second and discards whatever was waiting on the line.
// Throws net::NetError naming the path when it cannot be opened or configured, and
// std::invalid_argument for an unsupported rate.
net::Fd open_serial_port(const std::string& path, int baud);

}  // namespace gc::headctl
