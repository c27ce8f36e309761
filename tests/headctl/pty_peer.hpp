// The far end of a pseudo-terminal pair, for testing serial heads: the backend opens path()
// as it would /dev/ttyUSB0; every chunk of bytes it writes goes to `respond`, whose result is
// written back. Serves on its own thread for the object's lifetime.
#pragma once

#include <gtest/gtest.h>

#include <fcntl.h>
#include <poll.h>
#include <stdlib.h>
#include <unistd.h>

#include <atomic>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <thread>
#include <vector>

namespace gc::headctl::testing {

class PtyPeer {
public:
    using Respond = std::function<std::vector<std::uint8_t>(std::span<const std::uint8_t>)>;

    explicit PtyPeer(Respond respond) : respond_(std::move(respond))
    {
        master_ = ::posix_openpt(O_RDWR | O_NOCTTY | O_CLOEXEC);
        EXPECT_GE(master_, 0);
        EXPECT_EQ(::grantpt(master_), 0);
        EXPECT_EQ(::unlockpt(master_), 0);
        path_ = ::ptsname(master_);
        thread_ = std::thread([this] { serve(); });
    }
    ~PtyPeer()
    {
        stop_ = true;
        thread_.join();
        ::close(master_);
    }
    PtyPeer(const PtyPeer&) = delete;
    PtyPeer& operator=(const PtyPeer&) = delete;
    const std::string& path() const { return path_; }

private:
    void serve()
    {
        while (!stop_) {
            pollfd p{master_, POLLIN, 0};
            if (::poll(&p, 1, 20) <= 0 || !(p.revents & POLLIN)) continue;
            std::uint8_t buf[256];
            const ssize_t n = ::read(master_, buf, sizeof buf);
            if (n <= 0) continue;
            const auto out = respond_(std::span<const std::uint8_t>(buf, static_cast<std::size_t>(n)));
            if (!out.empty()) [[maybe_unused]]
                auto w = ::write(master_, out.data(), out.size());
        }
    }

    Respond respond_;
    int master_ = -1;
    std::string path_;
    std::atomic<bool> stop_{false};
    std::thread thread_;
};

}  // namespace gc::headctl::testing
