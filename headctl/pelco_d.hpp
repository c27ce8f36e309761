// Pelco-D messages: pure encoding and decoding, no I/O. Every message is seven bytes:
// FF, address, command 1, command 2, data 1, data 2, and the sum of bytes 2..6 modulo 256.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <stdexcept>

namespace gc::headctl::pelco {

using Message = std::array<std::uint8_t, 7>;

inline constexpr int kMaxSpeed = 0x3F;  // pan and tilt speed codes 0..0x3F

class PelcoError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// -1 negative (pan left, tilt down, zoom wide), 0 still, +1 positive.
struct Drive {
    int pan = 0;
    int tilt = 0;
    int zoom = 0;
    int pan_speed = 0;  // clamped to 0..kMaxSpeed
    int tilt_speed = 0;
};

// Commands to camera `address` (1..255); throw PelcoError for one out of range.
Message drive(int address, const Drive& d);
Message stop(int address);
enum class PresetAction : std::uint8_t { Set = 0x03, Clear = 0x05, GoTo = 0x07 };
Message preset(int address, PresetAction action, int number);  // number 1..255
// Absolute positions in hundredths of a degree (0..35999) or zoom units (0..65535).
Message set_pan(int address, int hundredths);
Message set_tilt(int address, int hundredths);
Message set_zoom(int address, int units);
Message query_pan(int address);
Message query_tilt(int address);
Message query_zoom(int address);

enum class Reading { Pan, Tilt, Zoom };
struct Report {
    int address = 1;
    Reading reading = Reading::Pan;
    int value = 0;  // hundredths of a degree, or zoom units
};

// A position report (FF addr 00 59|5B|5D MSB LSB sum); nullopt for a well-formed message that
// is not one. Throws PelcoError for a bad sync byte or checksum.
std::optional<Report> parse_report(std::span<const std::uint8_t, 7> message);

}  // namespace gc::headctl::pelco
