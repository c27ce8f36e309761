// VISCA: exact bytes of every command, VISCA-over-IP framing and sequence numbers, reply
// parsing, and the backend against a loopback responder (UDP and TCP).
#include "headctl/visca.hpp"
#include "headctl/visca_backend.hpp"

#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <netinet/udp.h>
#include <poll.h>
#include <pthread.h>
#include <sched.h>
#include <sys/socket.h>
#include <sys/uio.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cstdio>
#include <mutex>
#include <thread>

namespace gc::headctl {
namespace {

using namespace std::chrono_literals;
using visca::Bytes;

TEST(ViscaBytes, CommandsHaveTheExactLayout)
{
    EXPECT_EQ(visca::pan_tilt_drive(1, 0x10, 0x08, visca::Direction::Negative, visca::Direction::Positive),
              (Bytes{0x81, 0x01, 0x06, 0x01, 0x10, 0x08, 0x01, 0x01, 0xFF}));
    EXPECT_EQ(visca::pan_tilt_drive(1, 0x10, 0x08, visca::Direction::Positive, visca::Direction::Negative),
              (Bytes{0x81, 0x01, 0x06, 0x01, 0x10, 0x08, 0x02, 0x02, 0xFF}));
    EXPECT_EQ(visca::pan_tilt_stop(2), (Bytes{0x82, 0x01, 0x06, 0x01, 0x18, 0x14, 0x03, 0x03, 0xFF}));
    EXPECT_EQ(visca::pan_tilt_absolute(1, 0x18, 0x14, 0x1234, -2),
              (Bytes{0x81, 0x01, 0x06, 0x02, 0x18, 0x14, 0x01, 0x02, 0x03, 0x04, 0x0F, 0x0F, 0x0F, 0x0E, 0xFF}));
    EXPECT_EQ(visca::pan_tilt_relative(7, 0x30, 0x00, -0x8000, 0x7FFF),
              (Bytes{0x87, 0x01, 0x06, 0x03, 0x18, 0x01, 0x08, 0x00, 0x00, 0x00, 0x07, 0x0F, 0x0F, 0x0F, 0xFF}));
    EXPECT_EQ(visca::pan_tilt_home(1), (Bytes{0x81, 0x01, 0x06, 0x04, 0xFF}));
    EXPECT_EQ(visca::pan_tilt_position_inquiry(1), (Bytes{0x81, 0x09, 0x06, 0x12, 0xFF}));
    EXPECT_THROW(visca::pan_tilt_home(0), visca::ViscaError);
    EXPECT_THROW(visca::pan_tilt_home(8), visca::ViscaError);
    EXPECT_THROW(visca::pan_tilt_absolute(1, 1, 1, 0x8000, 0), visca::ViscaError);
}

TEST(ViscaBytes, MemoryCommandsHaveTheExactLayout)
{
    EXPECT_EQ(visca::memory(1, visca::MemoryAction::Set, 5), (Bytes{0x81, 0x01, 0x04, 0x3F, 0x01, 0x05, 0xFF}));
    EXPECT_EQ(visca::memory(3, visca::MemoryAction::Recall, 0x7F), (Bytes{0x83, 0x01, 0x04, 0x3F, 0x02, 0x7F, 0xFF}));
    EXPECT_EQ(visca::memory(1, visca::MemoryAction::Reset, 0), (Bytes{0x81, 0x01, 0x04, 0x3F, 0x00, 0x00, 0xFF}));
    EXPECT_THROW(visca::memory(1, visca::MemoryAction::Set, 128), visca::ViscaError);
    EXPECT_THROW(visca::memory(1, visca::MemoryAction::Set, -1), visca::ViscaError);
}

TEST(ViscaBytes, ZoomCommandsAndInquiryHaveTheExactLayout)
{
    EXPECT_EQ(visca::zoom_direct(1, 0x4000), (Bytes{0x81, 0x01, 0x04, 0x47, 0x04, 0x00, 0x00, 0x00, 0xFF}));
    EXPECT_EQ(visca::zoom_direct(2, 0x1234), (Bytes{0x82, 0x01, 0x04, 0x47, 0x01, 0x02, 0x03, 0x04, 0xFF}));
    EXPECT_EQ(visca::zoom_drive(1, 5, visca::Direction::Positive), (Bytes{0x81, 0x01, 0x04, 0x07, 0x25, 0xFF}));
    EXPECT_EQ(visca::zoom_drive(1, 9, visca::Direction::Negative), (Bytes{0x81, 0x01, 0x04, 0x07, 0x37, 0xFF}));
    EXPECT_EQ(visca::zoom_drive(1, 3, visca::Direction::Stop), (Bytes{0x81, 0x01, 0x04, 0x07, 0x00, 0xFF}));
    EXPECT_EQ(visca::zoom_position_inquiry(1), (Bytes{0x81, 0x09, 0x04, 0x47, 0xFF}));
    EXPECT_THROW(visca::zoom_direct(1, -1), visca::ViscaError);
    EXPECT_THROW(visca::zoom_direct(1, 0x10000), visca::ViscaError);
    const auto z = visca::parse_reply(Bytes{0x90, 0x50, 0x0A, 0x0B, 0x0C, 0x0D, 0xFF});
    EXPECT_EQ(z.kind, visca::ReplyKind::ZoomPosition);
    EXPECT_EQ(z.zoom_units, 0xABCD);
    EXPECT_THROW(visca::parse_reply(Bytes{0x90, 0x50, 0x1A, 0x0B, 0x0C, 0x0D, 0xFF}), visca::ViscaError);
}

TEST(ViscaBytes, IpHeaderCarriesTypeLengthAndSequence)
{
    const Bytes payload = visca::pan_tilt_home(1);
    EXPECT_EQ(visca::wrap_ip(visca::kIpCommand, 0x01020304, payload),
              (Bytes{0x01, 0x00, 0x00, 0x05, 0x01, 0x02, 0x03, 0x04, 0x81, 0x01, 0x06, 0x04, 0xFF}));
    EXPECT_EQ(visca::ip_reset_sequence(7), (Bytes{0x02, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00, 0x07, 0x01}));
    const auto m = visca::unwrap_ip(visca::wrap_ip(visca::kIpInquiry, 0xFFFFFFFF, payload));
    EXPECT_EQ(m.payload_type, visca::kIpInquiry);
    EXPECT_EQ(m.sequence, 0xFFFFFFFFu);
    EXPECT_EQ(m.payload, payload);
    EXPECT_THROW(visca::unwrap_ip(Bytes{0x01, 0x11, 0x00}), visca::ViscaError);
    EXPECT_THROW(visca::unwrap_ip(Bytes{0x01, 0x11, 0x00, 0x04, 0, 0, 0, 1, 0x90, 0x41, 0xFF}), visca::ViscaError);
    EXPECT_THROW(visca::unwrap_ip(Bytes{0x01, 0x11, 0x00, 0x00, 0, 0, 0, 1}), visca::ViscaError);
}

TEST(ViscaBytes, ParsesAckCompletionErrorAndPosition)
{
    auto ack = visca::parse_reply(Bytes{0x90, 0x41, 0xFF});
    EXPECT_EQ(ack.kind, visca::ReplyKind::Ack);
    EXPECT_EQ(ack.socket, 1);
    EXPECT_EQ(ack.address, 1);
    EXPECT_EQ(visca::parse_reply(Bytes{0xA0, 0x52, 0xFF}).kind, visca::ReplyKind::Completion);
    EXPECT_EQ(visca::parse_reply(Bytes{0xA0, 0x52, 0xFF}).address, 2);
    auto err = visca::parse_reply(Bytes{0x90, 0x61, 0x41, 0xFF});
    EXPECT_EQ(err.kind, visca::ReplyKind::Error);
    EXPECT_EQ(err.error, 0x41);
    EXPECT_EQ(visca::describe_error(0x41), "command not executable");
    EXPECT_EQ(visca::describe_error(0x77), "error 0x77");
    auto pos = visca::parse_reply(Bytes{0x90, 0x50, 0x0F, 0x0F, 0x0F, 0x0E, 0x00, 0x01, 0x00, 0x00, 0xFF});
    EXPECT_EQ(pos.kind, visca::ReplyKind::Position);
    EXPECT_EQ(pos.pan_units, -2);
    EXPECT_EQ(pos.tilt_units, 0x0100);
}

// The camera's side: replies laid out as parse_reply reads them, commands read back.
TEST(ViscaBytes, EncodesRepliesAndParsesCommands)
{
    EXPECT_EQ(visca::ack(1, 1), (Bytes{0x90, 0x41, 0xFF}));
    EXPECT_EQ(visca::completion(2, 1), (Bytes{0xA0, 0x51, 0xFF}));
    EXPECT_EQ(visca::error_reply(1, 0, 0x02), (Bytes{0x90, 0x60, 0x02, 0xFF}));
    EXPECT_EQ(visca::position_reply(1, -2, 0x0100),
              (Bytes{0x90, 0x50, 0x0F, 0x0F, 0x0F, 0x0E, 0x00, 0x01, 0x00, 0x00, 0xFF}));
    EXPECT_EQ(visca::zoom_position_reply(1, 0x4000), (Bytes{0x90, 0x50, 0x04, 0x00, 0x00, 0x00, 0xFF}));

    const auto drive = visca::parse_message(Bytes{0x83, 0x01, 0x06, 0x01, 0x0C, 0x0A, 0x01, 0x02, 0xFF});
    EXPECT_EQ(drive.kind, visca::MessageKind::Drive);
    EXPECT_EQ(drive.address, 3);
    EXPECT_EQ(drive.pan_speed, 0x0C);
    EXPECT_EQ(drive.tilt_speed, 0x0A);
    EXPECT_EQ(drive.pan, visca::Direction::Negative);   // 01: left
    EXPECT_EQ(drive.tilt, visca::Direction::Negative);  // 02: down
    const auto move = visca::parse_message(visca::pan_tilt_relative(1, 0x18, 0x14, -24, 8));
    EXPECT_EQ(move.kind, visca::MessageKind::Relative);
    EXPECT_EQ(move.pan_units, -24);
    EXPECT_EQ(move.tilt_units, 8);
    EXPECT_EQ(visca::parse_message(visca::zoom_direct(1, 0x0333)).zoom_units, 0x0333);
    const auto recall = visca::parse_message(visca::memory(1, visca::MemoryAction::Recall, 0x7F));
    EXPECT_EQ(recall.memory_action, visca::MemoryAction::Recall);
    EXPECT_EQ(recall.memory_number, 0x7F);
    for (const Bytes& bad : {Bytes{0x81, 0x01, 0x06, 0x01, 0x00, 0x0A, 0x01, 0x02, 0xFF},  // speed 0
                             Bytes{0x81, 0x01, 0x06, 0x01, 0x0C, 0x0A, 0x04, 0x02, 0xFF},  // direction 04
                             Bytes{0x88, 0x01, 0x06, 0x04, 0xFF},                          // broadcast
                             Bytes{0x81, 0x01, 0x04, 0x3F, 0x03, 0x01, 0xFF},              // memory action 3
                             Bytes{0x81, 0x01, 0x04, 0x07, 0x28, 0xFF},                    // zoom speed 8
                             Bytes{0x81, 0x09, 0x06, 0x12, 0x00, 0xFF}})
        EXPECT_THROW(visca::parse_message(bad), visca::ViscaError);
}

TEST(ViscaBytes, RejectsMalformedReplies)
{
    for (const Bytes& bad : {
             Bytes{},
             Bytes{0x90, 0xFF},
             Bytes{0x90, 0x41, 0x00},
             Bytes{0x91, 0x41, 0xFF},
             Bytes{0x80, 0x41, 0xFF},
             Bytes{0x10, 0x41, 0xFF},
             Bytes{0x90, 0x41, 0x00, 0xFF},
             Bytes{0x90, 0x61, 0xFF},
             Bytes{0x90, 0x71, 0xFF},
             Bytes{0x90, 0xFF, 0x41, 0xFF},
             Bytes{0x90, 0x50, 0x00, 0xFF},
             Bytes{0x90, 0x50, 0x1F, 0x0F, 0x0F, 0x0E, 0x00, 0x01, 0x00, 0x00, 0xFF},
             Bytes(17, 0x00),
         }) {
        EXPECT_THROW(visca::parse_reply(bad), visca::ViscaError) << bad.size();
    }
}

// A camera on loopback: answers VISCA over IP (UDP) or raw VISCA (TCP), keeps a position.
class ViscaResponder {
public:
    explicit ViscaResponder(bool tcp) : tcp_(tcp)
    {
        fd_ = ::socket(AF_INET, (tcp ? SOCK_STREAM : SOCK_DGRAM) | SOCK_CLOEXEC, 0);
        sockaddr_in a{};
        a.sin_family = AF_INET;
        a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
        EXPECT_EQ(::bind(fd_, reinterpret_cast<sockaddr*>(&a), sizeof a), 0);
        if (tcp) ::listen(fd_, 1);
        socklen_t len = sizeof a;
        ::getsockname(fd_, reinterpret_cast<sockaddr*>(&a), &len);
        port_ = ntohs(a.sin_port);
        thread_ = std::thread([this] { tcp_ ? serve_tcp() : serve_udp(); });
    }
    ~ViscaResponder()
    {
        stop_ = true;
        thread_.join();
        ::close(fd_);
    }
    std::uint16_t port() const { return port_; }
    std::vector<Bytes> received()
    {
        std::lock_guard lock(mutex_);
        return received_;
    }
    void refuse_next() { refuse_next_ = true; }
    // From now on a message is answered only by a flood of datagrams that are not its reply
    // (UDP only).
    void flood_instead_of_answering() { flood_ = true; }
    void set_zoom(int units)
    {
        std::lock_guard lock(mutex_);
        zoom_ = units;
    }
    void set_position(int pan, int tilt)
    {
        std::lock_guard lock(mutex_);
        pan_ = pan;
        tilt_ = tilt;
    }

private:
    // The replies to one VISCA message.
    std::vector<Bytes> answer(const Bytes& m)
    {
        std::lock_guard lock(mutex_);
        received_.push_back(m);
        if (m == visca::pan_tilt_position_inquiry(1)) {
            Bytes r{0x90, 0x50};
            for (int v : {pan_, tilt_})
                for (int shift = 12; shift >= 0; shift -= 4)
                    r.push_back(static_cast<std::uint8_t>((static_cast<std::uint16_t>(v) >> shift) & 0x0F));
            r.push_back(0xFF);
            return {r};
        }
        if (m == visca::zoom_position_inquiry(1)) {
            Bytes r{0x90, 0x50};
            for (int shift = 12; shift >= 0; shift -= 4)
                r.push_back(static_cast<std::uint8_t>((zoom_ >> shift) & 0x0F));
            r.push_back(0xFF);
            return {r};
        }
        if (refuse_next_.exchange(false)) return {Bytes{0x90, 0x61, 0x41, 0xFF}};
        if (m.size() == 9 && m[1] == 0x01 && m[2] == 0x04 && m[3] == 0x47)
            zoom_ = (m[4] << 12) | (m[5] << 8) | (m[6] << 4) | m[7];
        auto nibbles = [&](std::size_t at) {
            return static_cast<std::int16_t>((m[at] << 12) | (m[at + 1] << 8) | (m[at + 2] << 4) | m[at + 3]);
        };
        if (m.size() == 15 && m[3] == 0x02) {
            pan_ = nibbles(6);
            tilt_ = nibbles(10);
        } else if (m.size() == 15 && m[3] == 0x03) {
            pan_ += nibbles(6);
            tilt_ += nibbles(10);
        } else if (m == visca::pan_tilt_home(1)) {
            pan_ = tilt_ = 0;
        }
        return {Bytes{0x90, 0x41, 0xFF}, Bytes{0x90, 0x51, 0xFF}};
    }

    bool wait_readable(int fd)
    {
        pollfd p{fd, POLLIN, 0};
        return ::poll(&p, 1, 20) > 0;
    }

    void serve_udp()
    {
        while (!stop_) {
            if (!wait_readable(fd_)) continue;
            std::uint8_t buf[256];
            sockaddr_storage from{};
            socklen_t len = sizeof from;
            const ssize_t n = ::recvfrom(fd_, buf, sizeof buf, 0, reinterpret_cast<sockaddr*>(&from), &len);
            if (n <= 0) continue;
            const auto msg = visca::unwrap_ip(std::span<const std::uint8_t>(buf, static_cast<std::size_t>(n)));
            {
                std::lock_guard lock(mutex_);
                sequences_.push_back(msg.sequence);
            }
            std::vector<Bytes> out;
            std::uint16_t type = visca::kIpReply;
            if (msg.payload_type == visca::kIpControl) {
                type = visca::kIpControlReply;
                out.push_back(Bytes{0x01});
            } else if (flood_) {
                flood(msg.sequence, from, len);
            } else {
                // A stale reply with another sequence number first: the client must skip it.
                const Bytes stale = visca::wrap_ip(visca::kIpReply, msg.sequence + 1000, Bytes{0x90, 0x51, 0xFF});
                ::sendto(fd_, stale.data(), stale.size(), 0, reinterpret_cast<sockaddr*>(&from), len);
                out = answer(msg.payload);
            }
            for (const Bytes& r : out) {
                const Bytes d = visca::wrap_ip(type, msg.sequence, r);
                ::sendto(fd_, d.data(), d.size(), 0, reinterpret_cast<sockaddr*>(&from), len);
            }
        }
    }

    // Datagrams that are not the reply (other sequence numbers, garbled headers) for 5 s or
    // until destroyed. The flood must outrun the client's reads, or the client would find its
    // queue empty now and then and look at its deadline there: each send becomes 64 datagrams
    // (segmentation offload, where the kernel has it) and the sending thread runs at a
    // real-time priority (where allowed), so other load on the machine does not pause it.
    void flood(std::uint32_t sequence, sockaddr_storage& to, socklen_t to_len)
    {
        const Bytes stale = visca::wrap_ip(visca::kIpReply, sequence + 1, Bytes{0x90, 0x51, 0xFF});
        Bytes garbled = stale;
        garbled[3] = 4;  // the header claims a byte more than the datagram has
        int segment = static_cast<int>(stale.size());
        const bool offload = ::setsockopt(fd_, IPPROTO_UDP, UDP_SEGMENT, &segment, sizeof segment) == 0;
        Bytes burst;
        for (int k = 0; k < (offload ? 64 : 1); ++k) {
            const Bytes& d = k % 2 ? garbled : stale;
            burst.insert(burst.end(), d.begin(), d.end());
        }
        std::array<iovec, 16> parts{};
        std::array<mmsghdr, 16> batch{};
        for (std::size_t k = 0; k < batch.size(); ++k) {
            parts[k] = {burst.data(), burst.size()};
            batch[k].msg_hdr.msg_name = &to;
            batch[k].msg_hdr.msg_namelen = to_len;
            batch[k].msg_hdr.msg_iov = &parts[k];
            batch[k].msg_hdr.msg_iovlen = 1;
        }
        sched_param realtime{};
        realtime.sched_priority = 1;
        if (std::thread::hardware_concurrency() > 1)  // on one core it would starve the client
            ::pthread_setschedparam(::pthread_self(), SCHED_FIFO, &realtime);
        for (const auto end = net::Clock::now() + 5s; !stop_ && net::Clock::now() < end;)
            ::sendmmsg(fd_, batch.data(), batch.size(), 0);
        realtime.sched_priority = 0;
        ::pthread_setschedparam(::pthread_self(), SCHED_OTHER, &realtime);
    }

    void serve_tcp()
    {
        int conn = -1;
        Bytes stream;
        while (!stop_) {
            if (conn < 0) {
                if (wait_readable(fd_)) conn = ::accept(fd_, nullptr, nullptr);
                continue;
            }
            if (!wait_readable(conn)) continue;
            std::uint8_t buf[256];
            const ssize_t n = ::read(conn, buf, sizeof buf);
            if (n <= 0) {
                ::close(conn);
                conn = -1;
                continue;
            }
            stream.insert(stream.end(), buf, buf + n);
            for (auto end = std::find(stream.begin(), stream.end(), 0xFF); end != stream.end();
                 end = std::find(stream.begin(), stream.end(), 0xFF)) {
                const Bytes m(stream.begin(), end + 1);
                stream.erase(stream.begin(), end + 1);
                for (const Bytes& r : answer(m)) [[maybe_unused]] auto w = ::write(conn, r.data(), r.size());
            }
        }
        if (conn >= 0) ::close(conn);
    }

public:
    std::vector<std::uint32_t> sequences()
    {
        std::lock_guard lock(mutex_);
        return sequences_;
    }

private:
    bool tcp_;
    int fd_ = -1;
    std::uint16_t port_ = 0;
    std::atomic<bool> stop_{false};
    std::atomic<bool> refuse_next_{false};
    std::atomic<bool> flood_{false};
    std::mutex mutex_;
    std::vector<Bytes> received_;
    std::vector<std::uint32_t> sequences_;
    int pan_ = 0;
    int tilt_ = 0;
    int zoom_ = 0;
    std::thread thread_;
};

HeadCommand command(CommandKind kind, std::optional<double> pan, std::optional<double> tilt)
{
    HeadCommand c{kind, {}};
    if (pan) c.values.set(Axis::Pan, *pan);
    if (tilt) c.values.set(Axis::Tilt, *tilt);
    return c;
}

void exercise(ViscaResponder& camera, ViscaBackend& head)
{
    const auto deadline = [] { return net::Clock::now() + 2s; };
    head.open(deadline());
    camera.set_position(160, -32);  // 10 deg, -2 deg at 16 units per degree
    const HeadState s = head.query_state(deadline());
    EXPECT_DOUBLE_EQ(s.pose.pan_deg, 10.0);
    EXPECT_DOUBLE_EQ(s.pose.tilt_deg, -2.0);

    head.send(command(CommandKind::Absolute, 20.0, std::nullopt), deadline());  // tilt stays
    head.send(command(CommandKind::Relative, -1.5, 0.5), deadline());
    head.send(command(CommandKind::Velocity, -50.0, 0.0), deadline());
    head.send(command(CommandKind::Velocity, std::nullopt, 45.0), deadline());  // pan keeps driving
    head.send(HeadCommand{CommandKind::Stop, {}}, deadline());
    const auto after = head.query_state(deadline());
    EXPECT_DOUBLE_EQ(after.pose.pan_deg, 18.5);
    EXPECT_DOUBLE_EQ(after.pose.tilt_deg, -1.5);
    head.send(HeadCommand{CommandKind::Home, {}}, deadline());
    EXPECT_DOUBLE_EQ(head.query_state(deadline()).pose.pan_deg, 0.0);

    camera.refuse_next();
    EXPECT_THROW(head.send(command(CommandKind::Relative, 1.0, std::nullopt), deadline()), HeadRejected);
    HeadCommand verge{CommandKind::Absolute, {}};
    verge.values.set(Axis::VergeLeft, 1.0);
    EXPECT_THROW(head.send(verge, deadline()), HeadRejected);
    EXPECT_THROW(head.send(command(CommandKind::Absolute, 5000.0, 0.0), deadline()), HeadRejected);

    const auto got = camera.received();
    ASSERT_GE(got.size(), 9u);
    EXPECT_EQ(got[0], visca::pan_tilt_position_inquiry(1));
    EXPECT_EQ(got[1], visca::pan_tilt_absolute(1, 0x18, 0x14, 320, -32));
    EXPECT_EQ(got[2], visca::pan_tilt_relative(1, 0x18, 0x14, -24, 8));
    EXPECT_EQ(got[3], visca::pan_tilt_drive(1, 0x0C, 0x01, visca::Direction::Negative, visca::Direction::Stop));
    EXPECT_EQ(got[4], visca::pan_tilt_drive(1, 0x0C, 0x0A, visca::Direction::Negative, visca::Direction::Positive));
    EXPECT_EQ(got[5], visca::pan_tilt_stop(1));
    EXPECT_EQ(got[7], visca::pan_tilt_home(1));
}

TEST(ViscaBackend, DrivesACameraOverUdpWithSequenceNumbers)
{
    ViscaResponder camera(false);
    ViscaBackend head("127.0.0.1", camera.port(), ViscaBackend::Transport::Udp, ViscaSettings{});
    exercise(camera, head);
    const auto seq = camera.sequences();
    ASSERT_GE(seq.size(), 3u);
    // The reset first, then commands numbered from 0 upwards without gaps.
    for (std::size_t i = 1; i < seq.size(); ++i) EXPECT_EQ(seq[i], i - 1);
}

TEST(ViscaBackend, ZoomsToAMagnificationAndReadsItBack)
{
    ViscaResponder camera(false);
    ViscaSettings settings;
    settings.zoom_max = 21.0;  // position 0x4000 at 21x: 0x0333 per step of 1x (rounded)
    ViscaBackend head("127.0.0.1", camera.port(), ViscaBackend::Transport::Udp, settings);
    EXPECT_TRUE(head.axes()[static_cast<std::size_t>(Axis::Zoom)]);
    const auto deadline = [] { return net::Clock::now() + 2s; };
    head.open(deadline());
    camera.set_zoom(0x2000);
    EXPECT_DOUBLE_EQ(head.query_state(deadline()).pose.zoom, 11.0);
    HeadCommand zoom{CommandKind::Absolute, {}};
    zoom.values.set(Axis::Zoom, 2.0);
    head.send(zoom, deadline());
    EXPECT_NEAR(head.query_state(deadline()).pose.zoom, 2.0, 1e-3);
    zoom.kind = CommandKind::Velocity;
    zoom.values.set(Axis::Zoom, -4.0);  // half the default 8 per s: code 4 (of 0..7), wide
    head.send(zoom, deadline());
    head.send(HeadCommand{CommandKind::Home, {}}, deadline());
    EXPECT_DOUBLE_EQ(head.query_state(deadline()).pose.zoom, 1.0);
    zoom.kind = CommandKind::Absolute;
    zoom.values.set(Axis::Zoom, 22.0);
    EXPECT_THROW(head.send(zoom, deadline()), HeadRejected);

    const auto got = camera.received();
    // Only the lens is driven by a zoom move: no pan-tilt message between the inquiries.
    ASSERT_GE(got.size(), 10u);
    EXPECT_EQ(got[2], visca::zoom_direct(1, 0x0333));
    EXPECT_EQ(got[5], visca::zoom_drive(1, 4, visca::Direction::Negative));
    EXPECT_EQ(got[6], visca::pan_tilt_home(1));
    EXPECT_EQ(got[7], visca::zoom_direct(1, 0));

    ViscaBackend fixed("127.0.0.1", camera.port(), ViscaBackend::Transport::Udp, ViscaSettings{});
    EXPECT_FALSE(fixed.axes()[static_cast<std::size_t>(Axis::Zoom)]);
    fixed.open(deadline());
    zoom.values.set(Axis::Zoom, 2.0);
    EXPECT_THROW(fixed.send(zoom, deadline()), HeadRejected);
}

TEST(ViscaBackend, SavesAndRecallsPresetsInTheCamerasMemory)
{
    ViscaResponder camera(true);
    ViscaBackend head("127.0.0.1", camera.port(), ViscaBackend::Transport::Tcp, ViscaSettings{});
    const auto deadline = [] { return net::Clock::now() + 2s; };
    head.open(deadline());
    head.send(preset_command(CommandKind::SavePreset, 4), deadline());
    head.send(preset_command(CommandKind::RecallPreset, 4), deadline());
    const auto got = camera.received();
    ASSERT_EQ(got.size(), 2u);
    EXPECT_EQ(got[0], visca::memory(1, visca::MemoryAction::Set, 4));
    EXPECT_EQ(got[1], visca::memory(1, visca::MemoryAction::Recall, 4));
    camera.refuse_next();
    EXPECT_THROW(head.send(preset_command(CommandKind::RecallPreset, 9), deadline()), HeadRejected);
    EXPECT_THROW(head.send(preset_command(CommandKind::RecallPreset, 128), deadline()), HeadRejected);
}

TEST(ViscaBackend, DrivesACameraOverTcp)
{
    ViscaResponder camera(true);
    ViscaBackend head("127.0.0.1", camera.port(), ViscaBackend::Transport::Tcp, ViscaSettings{});
    exercise(camera, head);
}

TEST(ViscaBackend, ASilentCameraTimesOut)
{
    // A bound UDP socket that never answers.
    const int fd = ::socket(AF_INET, SOCK_DGRAM, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    ::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a);
    socklen_t len = sizeof a;
    ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len);
    ViscaBackend head("127.0.0.1", ntohs(a.sin_port), ViscaBackend::Transport::Udp, ViscaSettings{});
    const auto start = net::Clock::now();
    EXPECT_THROW(head.open(net::Clock::now() + 200ms), net::NetError);
    EXPECT_LT(net::Clock::now() - start, 2s);
    ::close(fd);
}

// However fast datagrams that are not its reply come in, the client gives up at its reply
// timeout (50 ms here; the bound leaves ten times that for a loaded machine).
TEST(ViscaBackend, AFloodOfRepliesToOtherMessagesDoesNotHoldTheClientPastItsTimeout)
{
    ViscaResponder camera(false);
    camera.flood_instead_of_answering();
    ViscaSettings settings;
    settings.reply_timeout = 50ms;
    ViscaBackend head("127.0.0.1", camera.port(), ViscaBackend::Transport::Udp, settings);
    head.open(net::Clock::now() + 2s);
    const auto start = net::Clock::now();
    EXPECT_THROW(head.query_state(net::Clock::now() + 20s), net::NetError);
    const auto waited = net::Clock::now() - start;
    std::printf("gave up after %.0f ms\n", std::chrono::duration<double, std::milli>(waited).count());
    EXPECT_LT(waited, 500ms);
}

}  // namespace
}  // namespace gc::headctl
