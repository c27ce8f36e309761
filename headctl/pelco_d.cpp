#include "headctl/pelco_d.hpp"

#include <algorithm>
#include <string>

namespace gc::headctl::pelco {

namespace {

Message make(int address, std::uint8_t cmd1, std::uint8_t cmd2, int data1, int data2)
{
    if (address < 1 || address > 255)
        throw PelcoError("Pelco-D address " + std::to_string(address) + " is not in 1..255");
    Message m{0xFF, static_cast<std::uint8_t>(address), cmd1,
              cmd2, static_cast<std::uint8_t>(data1),   static_cast<std::uint8_t>(data2),
              0};
    m[6] = static_cast<std::uint8_t>(m[1] + m[2] + m[3] + m[4] + m[5]);
    return m;
}

Message position(int address, std::uint8_t cmd2, int value, int max, const char* what)
{
    if (value < 0 || value > max)
        throw PelcoError(std::string("Pelco-D ") + what + " " + std::to_string(value) + " is not in 0.." +
                         std::to_string(max));
    return make(address, 0x00, cmd2, value >> 8, value & 0xFF);
}

}  // namespace

Message drive(int address, const Drive& d)
{
    std::uint8_t cmd2 = 0;
    if (d.pan > 0) cmd2 |= 0x02;
    if (d.pan < 0) cmd2 |= 0x04;
    if (d.tilt > 0) cmd2 |= 0x08;
    if (d.tilt < 0) cmd2 |= 0x10;
    if (d.zoom > 0) cmd2 |= 0x20;
    if (d.zoom < 0) cmd2 |= 0x40;
    return make(address, 0x00, cmd2, d.pan ? std::clamp(d.pan_speed, 0, kMaxSpeed) : 0,
                d.tilt ? std::clamp(d.tilt_speed, 0, kMaxSpeed) : 0);
}

Message stop(int address) { return make(address, 0x00, 0x00, 0, 0); }

Message preset(int address, PresetAction action, int number)
{
    if (number < 1 || number > 255) throw PelcoError("Pelco-D preset " + std::to_string(number) + " is not in 1..255");
    return make(address, 0x00, static_cast<std::uint8_t>(action), 0, number);
}

Message set_pan(int address, int hundredths) { return position(address, 0x4B, hundredths, 35999, "pan"); }
Message set_tilt(int address, int hundredths) { return position(address, 0x4D, hundredths, 35999, "tilt"); }
Message set_zoom(int address, int units) { return position(address, 0x4F, units, 0xFFFF, "zoom"); }
Message query_pan(int address) { return make(address, 0x00, 0x51, 0, 0); }
Message query_tilt(int address) { return make(address, 0x00, 0x53, 0, 0); }
Message query_zoom(int address) { return make(address, 0x00, 0x55, 0, 0); }

std::optional<Report> parse_report(std::span<const std::uint8_t, 7> m)
{
    if (m[0] != 0xFF) throw PelcoError("Pelco-D message does not start with FF");
    if (static_cast<std::uint8_t>(m[1] + m[2] + m[3] + m[4] + m[5]) != m[6])
        throw PelcoError("Pelco-D checksum mismatch");
    if (m[2] != 0x00) return std::nullopt;
    Report r;
    r.address = m[1];
    r.value = (m[4] << 8) | m[5];
    switch (m[3]) {
    case 0x59:
        r.reading = Reading::Pan;
        return r;
    case 0x5B:
        r.reading = Reading::Tilt;
        return r;
    case 0x5D:
        r.reading = Reading::Zoom;
        return r;
    default:
        return std::nullopt;
    }
}

}  // namespace gc::headctl::pelco
