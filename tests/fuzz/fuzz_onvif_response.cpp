// Fuzzes the ONVIF SOAP reader: any bytes either parse or throw SoapError, on both sides
// (the backend's responses, the responder's requests); a parsed status, written back as a
// response, reads back the same.
#include "headctl/onvif_soap.hpp"

#include <cstdint>
#include <cstdlib>

using namespace gc::headctl;

namespace {

void read_as_response(const onvif::Envelope& e)
{
    if (onvif::fault(e)) return;
    try {
        const onvif::PtzStatus s = onvif::parse_status(e);
        const onvif::PtzStatus again = onvif::parse_status(onvif::parse_envelope(onvif::status_response(s)));
        if (std::abs(again.pan_tilt.x - s.pan_tilt.x) > 1e-6 * (1 + std::abs(s.pan_tilt.x)) ||
            again.pan_tilt_moving != s.pan_tilt_moving || again.zoom_moving != s.zoom_moving)
            std::abort();
    } catch (const onvif::SoapError&) {
    }
    try {
        onvif::parse_presets(e);
    } catch (const onvif::SoapError&) {
    }
    try {
        onvif::parse_set_preset(e);
    } catch (const onvif::SoapError&) {
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    try {
        const onvif::Envelope e = onvif::parse_envelope(std::string_view(reinterpret_cast<const char*>(data), size));
        read_as_response(e);
        try {
            onvif::username_token(e);
        } catch (const onvif::SoapError&) {
        }
        onvif::parse_request(e);
    } catch (const onvif::SoapError&) {
    }
    return 0;
}
