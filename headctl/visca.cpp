#include "headctl/visca.hpp"

#include <algorithm>
#include <cstdio>

namespace gc::headctl::visca {

namespace {

std::uint8_t header(int address)
{
    if (address < 1 || address > 7)
        throw ViscaError("VISCA camera address " + std::to_string(address) + " is not in 1..7");
    return static_cast<std::uint8_t>(0x80 | address);
}

std::uint8_t speed(int value, int max) { return static_cast<std::uint8_t>(std::clamp(value, 1, max)); }

std::uint8_t direction(Direction d, std::uint8_t negative, std::uint8_t positive)
{
    return d == Direction::Stop ? 0x03 : (d == Direction::Negative ? negative : positive);
}

// A signed 16-bit position as four bytes carrying one nibble each, most significant first.
void append_nibbles(Bytes& out, int units, const char* axis)
{
    if (units < -0x8000 || units > 0x7FFF)
        throw ViscaError(std::string("VISCA ") + axis + " position " + std::to_string(units) +
                         " does not fit in 16 bits");
    const auto u = static_cast<std::uint16_t>(static_cast<std::int16_t>(units));
    for (int shift = 12; shift >= 0; shift -= 4) out.push_back(static_cast<std::uint8_t>((u >> shift) & 0x0F));
}

std::uint16_t read_unsigned_nibbles(std::span<const std::uint8_t> bytes)
{
    std::uint16_t u = 0;
    for (std::uint8_t b : bytes) {
        if (b > 0x0F) throw ViscaError("VISCA position byte has its high nibble set");
        u = static_cast<std::uint16_t>((u << 4) | b);
    }
    return u;
}

int read_nibbles(std::span<const std::uint8_t> bytes)
{
    return static_cast<std::int16_t>(read_unsigned_nibbles(bytes));
}

Bytes move(int address, std::uint8_t kind, int pan_speed, int tilt_speed, int pan_units, int tilt_units)
{
    Bytes out{header(address), 0x01, 0x06, kind, speed(pan_speed, kMaxPanSpeed), speed(tilt_speed, kMaxTiltSpeed)};
    append_nibbles(out, pan_units, "pan");
    append_nibbles(out, tilt_units, "tilt");
    out.push_back(0xFF);
    return out;
}

std::string hex(std::span<const std::uint8_t> bytes)
{
    std::string out;
    char b[4];
    for (std::size_t i = 0; i < std::min<std::size_t>(bytes.size(), 16); ++i) {
        std::snprintf(b, sizeof b, "%02X ", bytes[i]);
        out += b;
    }
    if (!out.empty()) out.pop_back();
    return out;
}

// 3..16 bytes, one FF and that at the end.
void check_framing(std::span<const std::uint8_t> m, const std::string& what)
{
    if (m.size() < 3) throw ViscaError("VISCA " + what + " of " + std::to_string(m.size()) + " bytes is too short");
    if (m.size() > kMaxMessageSize) throw ViscaError("VISCA " + what + " longer than 16 bytes");
    if (m.back() != 0xFF) throw ViscaError("VISCA " + what + " [" + hex(m) + "] does not end in FF");
    if (std::find(m.begin(), m.end() - 1, 0xFF) != m.end() - 1)
        throw ViscaError("VISCA " + what + " [" + hex(m) + "] has FF before its end");
}

std::uint8_t reply_header(int address) { return static_cast<std::uint8_t>((header(address) & 0x0F) + 8) << 4; }

void append_unsigned_nibbles(Bytes& out, int units)
{
    for (int shift = 12; shift >= 0; shift -= 4) out.push_back(static_cast<std::uint8_t>((units >> shift) & 0x0F));
}

}  // namespace

Bytes pan_tilt_drive(int address, int pan_speed, int tilt_speed, Direction pan, Direction tilt)
{
    return {header(address),
            0x01,
            0x06,
            0x01,
            speed(pan_speed, kMaxPanSpeed),
            speed(tilt_speed, kMaxTiltSpeed),
            direction(pan, 0x01, 0x02),
            direction(tilt, 0x02, 0x01),
            0xFF};
}

Bytes pan_tilt_absolute(int address, int pan_speed, int tilt_speed, int pan_units, int tilt_units)
{
    return move(address, 0x02, pan_speed, tilt_speed, pan_units, tilt_units);
}

Bytes pan_tilt_relative(int address, int pan_speed, int tilt_speed, int pan_units, int tilt_units)
{
    return move(address, 0x03, pan_speed, tilt_speed, pan_units, tilt_units);
}

Bytes pan_tilt_home(int address) { return {header(address), 0x01, 0x06, 0x04, 0xFF}; }

Bytes pan_tilt_stop(int address)
{
    return pan_tilt_drive(address, kMaxPanSpeed, kMaxTiltSpeed, Direction::Stop, Direction::Stop);
}

Bytes pan_tilt_position_inquiry(int address) { return {header(address), 0x09, 0x06, 0x12, 0xFF}; }

Bytes zoom_direct(int address, int zoom_units)
{
    if (zoom_units < 0 || zoom_units > 0xFFFF)
        throw ViscaError("VISCA zoom position " + std::to_string(zoom_units) + " is not in 0..65535");
    Bytes out{header(address), 0x01, 0x04, 0x47};
    append_unsigned_nibbles(out, zoom_units);
    out.push_back(0xFF);
    return out;
}

Bytes zoom_drive(int address, int speed, Direction d)
{
    const auto p = static_cast<std::uint8_t>(std::clamp(speed, 0, kMaxZoomSpeed));
    const std::uint8_t code = d == Direction::Stop ? 0x00 : (d == Direction::Positive ? 0x20 | p : 0x30 | p);
    return {header(address), 0x01, 0x04, 0x07, code, 0xFF};
}

Bytes memory(int address, MemoryAction action, int number)
{
    if (number < 0 || number > 0x7F) throw ViscaError("VISCA memory " + std::to_string(number) + " is not in 0..127");
    return {
        header(address), 0x01, 0x04, 0x3F, static_cast<std::uint8_t>(action), static_cast<std::uint8_t>(number), 0xFF};
}

Bytes zoom_position_inquiry(int address) { return {header(address), 0x09, 0x04, 0x47, 0xFF}; }

Reply parse_reply(std::span<const std::uint8_t> m)
{
    check_framing(m, "reply");
    const int from = (m[0] >> 4) - 8;
    if ((m[0] & 0x0F) != 0 || from < 1 || from > 7)
        throw ViscaError("VISCA reply [" + hex(m) + "] has a bad header byte");
    Reply r;
    r.address = from;
    r.socket = m[1] & 0x0F;
    switch (m[1] >> 4) {
    case 0x4:
        if (m.size() != 3) throw ViscaError("VISCA ACK [" + hex(m) + "] must be 3 bytes");
        r.kind = ReplyKind::Ack;
        return r;
    case 0x5:
        if (m.size() == 3) {
            r.kind = ReplyKind::Completion;
            return r;
        }
        if (m.size() == 11 && r.socket == 0) {
            r.kind = ReplyKind::Position;
            r.pan_units = read_nibbles(m.subspan(2, 4));
            r.tilt_units = read_nibbles(m.subspan(6, 4));
            return r;
        }
        if (m.size() == 7 && r.socket == 0) {
            r.kind = ReplyKind::ZoomPosition;
            r.zoom_units = read_unsigned_nibbles(m.subspan(2, 4));
            return r;
        }
        throw ViscaError("VISCA completion [" + hex(m) + "] has an unexpected length");
    case 0x6:
        if (m.size() != 4) throw ViscaError("VISCA error reply [" + hex(m) + "] must be 4 bytes");
        r.kind = ReplyKind::Error;
        r.error = m[2];
        return r;
    default:
        throw ViscaError("VISCA reply [" + hex(m) + "] is not an ACK, completion or error");
    }
}

Bytes ack(int address, int socket)
{
    return {reply_header(address), static_cast<std::uint8_t>(0x40 | (socket & 0x0F)), 0xFF};
}

Bytes completion(int address, int socket)
{
    return {reply_header(address), static_cast<std::uint8_t>(0x50 | (socket & 0x0F)), 0xFF};
}

Bytes error_reply(int address, int socket, int error)
{
    return {reply_header(address), static_cast<std::uint8_t>(0x60 | (socket & 0x0F)),
            static_cast<std::uint8_t>(error & 0x7F), 0xFF};
}

Bytes position_reply(int address, int pan_units, int tilt_units)
{
    Bytes out{reply_header(address), 0x50};
    append_nibbles(out, pan_units, "pan");
    append_nibbles(out, tilt_units, "tilt");
    out.push_back(0xFF);
    return out;
}

Bytes zoom_position_reply(int address, int zoom_units)
{
    if (zoom_units < 0 || zoom_units > 0xFFFF)
        throw ViscaError("VISCA zoom position " + std::to_string(zoom_units) + " is not in 0..65535");
    Bytes out{reply_header(address), 0x50};
    append_unsigned_nibbles(out, zoom_units);
    out.push_back(0xFF);
    return out;
}

namespace {

int checked_speed(std::uint8_t code, int max, std::span<const std::uint8_t> m)
{
    if (code < 1 || code > max) throw ViscaError("VISCA command [" + hex(m) + "] has a speed out of range");
    return code;
}

// The pan-tilt drive's direction bytes: pan 01 left, 02 right; tilt 01 up, 02 down; 03 stop.
Direction drive_direction(std::uint8_t code, Direction on_01, std::span<const std::uint8_t> m)
{
    if (code == 0x03) return Direction::Stop;
    if (code == 0x01) return on_01;
    if (code == 0x02) return on_01 == Direction::Positive ? Direction::Negative : Direction::Positive;
    throw ViscaError("VISCA drive [" + hex(m) + "] has an unknown direction");
}

Message parse_pan_tilt(std::span<const std::uint8_t> m, Message r)
{
    if (m[3] == 0x04 && m.size() == 5) {
        r.kind = MessageKind::Home;
        return r;
    }
    const bool drive = m[3] == 0x01 && m.size() == 9;
    const bool move = (m[3] == 0x02 || m[3] == 0x03) && m.size() == 15;
    if (!drive && !move) throw ViscaError("VISCA pan-tilt command [" + hex(m) + "] is not one this camera knows");
    r.pan_speed = checked_speed(m[4], kMaxPanSpeed, m);
    r.tilt_speed = checked_speed(m[5], kMaxTiltSpeed, m);
    if (drive) {
        r.kind = MessageKind::Drive;
        r.pan = drive_direction(m[6], Direction::Negative, m);
        r.tilt = drive_direction(m[7], Direction::Positive, m);
        return r;
    }
    r.kind = m[3] == 0x02 ? MessageKind::Absolute : MessageKind::Relative;
    r.pan_units = read_nibbles(m.subspan(6, 4));
    r.tilt_units = read_nibbles(m.subspan(10, 4));
    return r;
}

Message parse_lens(std::span<const std::uint8_t> m, Message r)
{
    if (m[3] == 0x47 && m.size() == 9) {
        r.kind = MessageKind::ZoomDirect;
        r.zoom_units = read_unsigned_nibbles(m.subspan(4, 4));
        return r;
    }
    if (m[3] == 0x07 && m.size() == 6 && (m[4] == 0x00 || ((m[4] >> 4) == 2 || (m[4] >> 4) == 3))) {
        r.kind = MessageKind::ZoomDrive;
        r.zoom = m[4] == 0x00 ? Direction::Stop : (m[4] >> 4) == 2 ? Direction::Positive : Direction::Negative;
        r.zoom_speed = m[4] & 0x0F;
        if (r.zoom_speed <= kMaxZoomSpeed) return r;
    }
    if (m[3] == 0x3F && m.size() == 7 && m[4] <= 2 && m[5] <= 0x7F) {
        r.kind = MessageKind::Memory;
        r.memory_action = static_cast<MemoryAction>(m[4]);
        r.memory_number = m[5];
        return r;
    }
    throw ViscaError("VISCA lens command [" + hex(m) + "] is not one this camera knows");
}

}  // namespace

Message parse_message(std::span<const std::uint8_t> m)
{
    check_framing(m, "message");
    if ((m[0] >> 4) != 0x8 || (m[0] & 0x0F) < 1 || (m[0] & 0x0F) > 7)
        throw ViscaError("VISCA message [" + hex(m) + "] is not addressed to a camera 1..7");
    Message r;
    r.address = m[0] & 0x0F;
    if (m.size() >= 4 && m[1] == 0x01 && m[2] == 0x06) return parse_pan_tilt(m, r);
    if (m.size() >= 5 && m[1] == 0x01 && m[2] == 0x04) return parse_lens(m, r);
    if (m.size() == 5 && m[1] == 0x09 && m[2] == 0x06 && m[3] == 0x12) {
        r.kind = MessageKind::PositionInquiry;
        return r;
    }
    if (m.size() == 5 && m[1] == 0x09 && m[2] == 0x04 && m[3] == 0x47) {
        r.kind = MessageKind::ZoomInquiry;
        return r;
    }
    throw ViscaError("VISCA message [" + hex(m) + "] is not one this camera knows");
}

Bytes encode(const Message& m)
{
    switch (m.kind) {
    case MessageKind::Drive:
        return pan_tilt_drive(m.address, m.pan_speed, m.tilt_speed, m.pan, m.tilt);
    case MessageKind::Absolute:
        return pan_tilt_absolute(m.address, m.pan_speed, m.tilt_speed, m.pan_units, m.tilt_units);
    case MessageKind::Relative:
        return pan_tilt_relative(m.address, m.pan_speed, m.tilt_speed, m.pan_units, m.tilt_units);
    case MessageKind::Home:
        return pan_tilt_home(m.address);
    case MessageKind::PositionInquiry:
        return pan_tilt_position_inquiry(m.address);
    case MessageKind::ZoomDirect:
        return zoom_direct(m.address, m.zoom_units);
    case MessageKind::ZoomDrive:
        return zoom_drive(m.address, m.zoom_speed, m.zoom);
    case MessageKind::ZoomInquiry:
        return zoom_position_inquiry(m.address);
    case MessageKind::Memory:
        return memory(m.address, m.memory_action, m.memory_number);
    }
    throw ViscaError("unknown VISCA message kind");
}

std::string describe_error(int error)
{
    switch (error) {
    case 0x01:
        return "message length error";
    case 0x02:
        return "syntax error";
    case 0x03:
        return "command buffer full";
    case 0x04:
        return "command cancelled";
    case 0x05:
        return "no socket";
    case 0x41:
        return "command not executable";
    default: {
        char b[16];
        std::snprintf(b, sizeof b, "error 0x%02X", error & 0xFF);
        return b;
    }
    }
}

Bytes wrap_ip(std::uint16_t type, std::uint32_t seq, std::span<const std::uint8_t> payload)
{
    if (payload.size() > kMaxMessageSize) throw ViscaError("VISCA payload longer than 16 bytes");
    Bytes out(kIpHeaderSize + payload.size());
    out[0] = static_cast<std::uint8_t>(type >> 8);
    out[1] = static_cast<std::uint8_t>(type);
    out[2] = static_cast<std::uint8_t>(payload.size() >> 8);
    out[3] = static_cast<std::uint8_t>(payload.size());
    for (int i = 0; i < 4; ++i) out[4 + i] = static_cast<std::uint8_t>(seq >> (24 - 8 * i));
    std::copy(payload.begin(), payload.end(), out.begin() + kIpHeaderSize);
    return out;
}

IpMessage unwrap_ip(std::span<const std::uint8_t> d)
{
    if (d.size() < kIpHeaderSize) throw ViscaError("VISCA-over-IP datagram shorter than its 8-byte header");
    IpMessage m;
    m.payload_type = static_cast<std::uint16_t>((d[0] << 8) | d[1]);
    const std::size_t length = static_cast<std::size_t>((d[2] << 8) | d[3]);
    m.sequence = (std::uint32_t{d[4]} << 24) | (std::uint32_t{d[5]} << 16) | (std::uint32_t{d[6]} << 8) | d[7];
    if (length != d.size() - kIpHeaderSize)
        throw ViscaError("VISCA-over-IP header says " + std::to_string(length) + " payload bytes, datagram has " +
                         std::to_string(d.size() - kIpHeaderSize));
    if (length == 0 || length > kMaxMessageSize)
        throw ViscaError("VISCA-over-IP payload length " + std::to_string(length) + " is not in 1..16");
    m.payload.assign(d.begin() + kIpHeaderSize, d.end());
    return m;
}

Bytes ip_reset_sequence(std::uint32_t sequence)
{
    const std::uint8_t reset = 0x01;
    return wrap_ip(kIpControl, sequence, std::span<const std::uint8_t>(&reset, 1));
}

double zoom_from_units(double units, double widest, double longest, int tele_units)
{
    return widest + units / tele_units * (longest - widest);
}

double zoom_to_units(double zoom, double widest, double longest, int tele_units)
{
    return (zoom - widest) / (longest - widest) * tele_units;
}

}  // namespace gc::headctl::visca
