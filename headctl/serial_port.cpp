#include "headctl/serial_port.hpp"

#include <fcntl.h>
#include <termios.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <stdexcept>

namespace gc::headctl {

namespace {

struct Rate {
    int baud;
    speed_t code;
};
constexpr std::array<Rate, 7> kRates{{
    {2400, B2400},
    {4800, B4800},
    {9600, B9600},
    {19200, B19200},
    {38400, B38400},
    {57600, B57600},
    {115200, B115200},
}};

[[noreturn]] void fail(const std::string& path, const char* what)
{
    throw net::NetError("serial port " + path + ": " + what + " (" + std::strerror(errno) + ")");
}

}  // namespace

bool is_supported_baud(int baud)
{
    for (const Rate& r : kRates)
        if (r.baud == baud) return true;
    return false;
}

net::Fd open_serial_port(const std::string& path, int baud)
{
    speed_t code = 0;
    for (const Rate& r : kRates)
        if (r.baud == baud) code = r.code;
    if (code == 0) throw std::invalid_argument("serial port: " + std::to_string(baud) + " baud is not supported");
    net::Fd fd(::open(path.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC));
    if (!fd) fail(path, "cannot open");
    termios t{};
    if (::tcgetattr(fd.get(), &t) != 0) fail(path, "is not a terminal");
    // Raw bytes: no echo, no line editing, no translation of CR/LF or of the 0xFF that ends
    // every VISCA message; the receiver is on and modem lines are ignored.
    ::cfmakeraw(&t);
    t.c_cflag &= ~static_cast<tcflag_t>(CSTOPB | PARENB | CRTSCTS | CSIZE);
    t.c_cflag |= CS8 | CLOCAL | CREAD;
    t.c_iflag &= ~static_cast<tcflag_t>(IXON | IXOFF | IXANY);
    // One byte satisfies a read; with O_NONBLOCK an empty line then reads as EAGAIN, not as
    // the end of the stream that VMIN = 0 would make it look like.
    t.c_cc[VMIN] = 1;
    t.c_cc[VTIME] = 0;
    if (::cfsetispeed(&t, code) != 0 || ::cfsetospeed(&t, code) != 0) fail(path, "cannot set the rate");
    if (::tcsetattr(fd.get(), TCSANOW, &t) != 0) fail(path, "cannot configure");
    ::tcflush(fd.get(), TCIOFLUSH);
    return fd;
}

int address_param(const HeadUri& uri, int max_address)
{
    const double address = uri.number_param("address", 1, 1, max_address);
    if (address != std::floor(address))
        throw std::invalid_argument("head URI: parameter address must be an integer in 1.." +
                                    std::to_string(max_address));
    return static_cast<int>(address);
}

int baud_param(const HeadUri& uri, int fallback)
{
    const int baud = static_cast<int>(uri.number_param("baud", fallback, 1, 1e7));
    if (!is_supported_baud(baud))
        throw std::invalid_argument("head URI: baud must be 2400, 4800, 9600, 19200, 38400, 57600 or 115200");
    return baud;
}

std::chrono::milliseconds reply_timeout_param(const HeadUri& uri, std::chrono::milliseconds fallback)
{
    return std::chrono::milliseconds(
        static_cast<long>(uri.number_param("timeout_ms", static_cast<double>(fallback.count()), 1, 60'000)));
}

}  // namespace gc::headctl
