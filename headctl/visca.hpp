// VISCA pan-tilt and zoom messages and VISCA-over-IP framing: pure encoding and decoding, no I/O.
#pragma once

#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace gc::headctl::visca {

using Bytes = std::vector<std::uint8_t>;

// Fastest speed codes of the pan-tilt drive (Sony's VISCA command set).
inline constexpr int kMaxPanSpeed = 0x18;
inline constexpr int kMaxTiltSpeed = 0x14;
inline constexpr int kMaxZoomSpeed = 7;

// VISCA-over-IP payload types (the first two bytes of the 8-byte header).
inline constexpr std::uint16_t kIpCommand = 0x0100;
inline constexpr std::uint16_t kIpInquiry = 0x0110;
inline constexpr std::uint16_t kIpReply = 0x0111;
inline constexpr std::uint16_t kIpControl = 0x0200;
inline constexpr std::uint16_t kIpControlReply = 0x0201;
inline constexpr std::size_t kIpHeaderSize = 8;
inline constexpr std::size_t kMaxMessageSize = 16;  // a VISCA message is at most 16 bytes

class ViscaError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// Drive direction of one axis: pan -1 = left, +1 = right; tilt -1 = down, +1 = up.
enum class Direction { Negative = -1, Stop = 0, Positive = 1 };

// Commands to camera `address` (1..7). Speeds are clamped to 1..max; positions are the
// camera's signed 16-bit units. Throw ViscaError for an address or position out of range.
Bytes pan_tilt_drive(int address, int pan_speed, int tilt_speed, Direction pan, Direction tilt);
Bytes pan_tilt_absolute(int address, int pan_speed, int tilt_speed, int pan_units, int tilt_units);
Bytes pan_tilt_relative(int address, int pan_speed, int tilt_speed, int pan_units, int tilt_units);
Bytes pan_tilt_home(int address);
Bytes pan_tilt_stop(int address);
Bytes pan_tilt_position_inquiry(int address);

// CAM_Zoom: direct to a lens position (0 = widest, unsigned 16-bit), variable-speed drive
// (speed clamped to 0..7; Positive = tele, Negative = wide, Stop) and the position inquiry.
Bytes zoom_direct(int address, int zoom_units);
Bytes zoom_drive(int address, int speed, Direction direction);
Bytes zoom_position_inquiry(int address);

// CAM_Memory: store the head's position and zoom under a number (0..127), recall or clear it.
enum class MemoryAction { Reset = 0, Set = 1, Recall = 2 };
Bytes memory(int address, MemoryAction action, int number);

enum class ReplyKind { Ack, Completion, Error, Position, ZoomPosition };

struct Reply {
    ReplyKind kind = ReplyKind::Ack;
    int address = 1;  // the replying camera
    int socket = 0;   // Ack, Completion, Error
    int error =
        0;  // Error: 0x01 length, 0x02 syntax, 0x03 buffer full, 0x04 cancelled, 0x05 no socket, 0x41 not executable
    int pan_units = 0;   // Position
    int tilt_units = 0;  // Position
    int zoom_units = 0;  // ZoomPosition
};

// Parses one reply message (ending in 0xFF). A 3-byte "y0 5z FF" is a Completion; the
// 11-byte "y0 50 0p 0p 0p 0p 0t 0t 0t 0t FF" answers the position inquiry, the 7-byte
// "y0 50 0z 0z 0z 0z FF" the zoom position inquiry.
Reply parse_reply(std::span<const std::uint8_t> message);
std::string describe_error(int error);

// Replies from camera `address` (1..7): "y0 4s FF", "y0 5s FF", "y0 6s EE FF" and the answers
// to the position inquiries, y = 8 + address.
Bytes ack(int address, int socket);
Bytes completion(int address, int socket);
Bytes error_reply(int address, int socket, int error);
Bytes position_reply(int address, int pan_units, int tilt_units);
Bytes zoom_position_reply(int address, int zoom_units);

// The lens position as VISCA carries it, linear from the widest view (0 units) to the longest
// (tele_units): one mapping for the client backend and the simulated camera. Not clamped.
double zoom_from_units(double units, double widest, double longest, int tele_units);
double zoom_to_units(double zoom, double widest, double longest, int tele_units);

// The commands and inquiries above as a camera receives them.
enum class MessageKind { Drive, Absolute, Relative, Home, PositionInquiry, ZoomDirect, ZoomDrive, ZoomInquiry, Memory };

struct Message {
    MessageKind kind = MessageKind::Drive;
    int address = 1;
    int pan_speed = 1;                               // Drive, Absolute, Relative: 1..kMaxPanSpeed
    int tilt_speed = 1;                              // 1..kMaxTiltSpeed
    Direction pan = Direction::Stop;                 // Drive
    Direction tilt = Direction::Stop;                // Drive
    int pan_units = 0;                               // Absolute, Relative
    int tilt_units = 0;                              // Absolute, Relative
    int zoom_units = 0;                              // ZoomDirect
    int zoom_speed = 0;                              // ZoomDrive: 0..kMaxZoomSpeed
    Direction zoom = Direction::Stop;                // ZoomDrive
    MemoryAction memory_action = MemoryAction::Set;  // Memory
    int memory_number = 0;                           // Memory: 0..127
};

// Parses one message (ending in 0xFF) of the kinds above, exactly as their encoders lay it
// out; throws ViscaError for anything else (a camera's syntax error). encode() gives the bytes back.
Message parse_message(std::span<const std::uint8_t> message);
Bytes encode(const Message& message);

// VISCA over IP: 2-byte payload type, 2-byte payload length, 4-byte sequence number, all
// big-endian, then the payload.
Bytes wrap_ip(std::uint16_t payload_type, std::uint32_t sequence, std::span<const std::uint8_t> payload);

struct IpMessage {
    std::uint16_t payload_type = 0;
    std::uint32_t sequence = 0;
    Bytes payload;
};
IpMessage unwrap_ip(std::span<const std::uint8_t> datagram);

// The control message that resets the camera's expected sequence number.
Bytes ip_reset_sequence(std::uint32_t sequence);

}  // namespace gc::headctl::visca
