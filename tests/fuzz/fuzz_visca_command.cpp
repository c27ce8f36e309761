// Fuzzes the simulated camera's side of VISCA: any bytes either parse as a message that
// encodes back to the same bytes or throw ViscaError, and whatever the responder answers to
// them, as a bare message or a VISCA-over-IP datagram, is a reply the client's parser takes.
#include "headctl/sim/visca_responder.hpp"

#include <cstdint>
#include <cstdlib>

using namespace gc::headctl;

namespace {

void expect_replies(const std::vector<visca::Bytes>& replies, bool wrapped)
{
    for (const visca::Bytes& r : replies) {
        try {
            if (!wrapped) {
                visca::parse_reply(r);
                continue;
            }
            const visca::IpMessage m = visca::unwrap_ip(r);
            if (m.payload_type == visca::kIpReply) visca::parse_reply(m.payload);
        } catch (const visca::ViscaError&) {
            std::abort();  // the responder said something its own client cannot read
        }
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    const std::span<const std::uint8_t> bytes(data, size);
    try {
        const visca::Message m = visca::parse_message(bytes);
        if (visca::encode(m) != visca::Bytes(bytes.begin(), bytes.end())) std::abort();
    } catch (const visca::ViscaError&) {
    }
    HeadModel model(HeadModelConfig{});
    expect_replies(answer_visca(model, 0.5, bytes, ViscaUnits{}), false);
    expect_replies(answer_visca_datagram(model, 1.0, bytes, ViscaUnits{}), true);
    return 0;
}
