// Reading a small configuration file that may be anything the user names: only a regular
// file of bounded size is read, and nothing blocks (a FIFO or a device is refused at once).
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>

namespace gc {

// Why a file was not read; the message says what the path is or what failed, without the
// path, so that the caller can prefix its own context (e.g. "calibration file 'x': ").
class SmallFileError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// The whole content of the regular file at `path`, at most `max_bytes` long. Opens without
// blocking, refuses directories, FIFOs, devices and sockets, and reads at most max_bytes + 1
// bytes, so that a file that grows while it is read cannot exceed the cap either.
std::string read_small_file(const std::string& path, std::size_t max_bytes);

}  // namespace gc
