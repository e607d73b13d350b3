#include "mavlink/framing.hpp"

#include "mavlink/crc.hpp"
#include "mavlink/payload.hpp"

namespace gimbal::mavlink {

namespace {

void append_crc(std::vector<std::uint8_t>& frame, std::uint8_t crc_extra) {
    const std::uint16_t crc = frame_crc(std::span<const std::uint8_t>(frame).subspan(1), crc_extra);
    frame.push_back(static_cast<std::uint8_t>(crc & 0xFF));
    frame.push_back(static_cast<std::uint8_t>(crc >> 8));
}

std::uint8_t crc_extra_of(const Payload& payload) {
    return std::visit([](const auto& m) { return std::decay_t<decltype(m)>::crc_extra; }, payload);
}

std::size_t base_length_of(const Payload& payload) {
    return std::visit([](const auto& m) { return std::size_t{std::decay_t<decltype(m)>::length}; },
                      payload);
}

}  // namespace

std::uint16_t frame_crc(std::span<const std::uint8_t> covered, std::uint8_t crc_extra) {
    return crc16_mcrf4xx_byte(crc_extra, crc16_mcrf4xx(covered));
}

std::vector<std::uint8_t> encode_v1(const Payload& payload, std::uint8_t sysid, std::uint8_t compid,
                                    std::uint8_t seq) {
    PayloadBytes data = encode_payload(payload);
    data.size = base_length_of(payload);  // MAVLink 1 carries no extension fields
    std::vector<std::uint8_t> frame;
    frame.reserve(header_size_v1 + data.size + checksum_size);
    frame.push_back(magic_v1);
    frame.push_back(static_cast<std::uint8_t>(data.size));
    frame.push_back(seq);
    frame.push_back(sysid);
    frame.push_back(compid);
    frame.push_back(static_cast<std::uint8_t>(message_id(payload)));  // all our ids are < 256
    frame.insert(frame.end(), data.view().begin(), data.view().end());
    append_crc(frame, crc_extra_of(payload));
    return frame;
}

std::vector<std::uint8_t> encode_v2(const Payload& payload, std::uint8_t sysid, std::uint8_t compid,
                                    std::uint8_t seq) {
    return encode_v2(payload, sysid, compid, seq, false);
}

std::vector<std::uint8_t> encode_v2(const Payload& payload, std::uint8_t sysid, std::uint8_t compid,
                                    std::uint8_t seq, bool signed_flag) {
    const PayloadBytes data = encode_payload(payload);
    std::size_t length = data.size;
    while (length > 1 && data.bytes[length - 1] == 0) --length;
    const std::uint32_t msgid = message_id(payload);
    std::vector<std::uint8_t> frame;
    frame.reserve(header_size_v2 + length + checksum_size + signature_size);
    frame.push_back(magic_v2);
    frame.push_back(static_cast<std::uint8_t>(length));
    frame.push_back(signed_flag ? incompat_signed : std::uint8_t{0});  // incompat flags
    frame.push_back(0);                                                // compat flags
    frame.push_back(seq);
    frame.push_back(sysid);
    frame.push_back(compid);
    frame.push_back(static_cast<std::uint8_t>(msgid & 0xFF));
    frame.push_back(static_cast<std::uint8_t>((msgid >> 8) & 0xFF));
    frame.push_back(static_cast<std::uint8_t>((msgid >> 16) & 0xFF));
    frame.insert(frame.end(), data.bytes.begin(),
                 data.bytes.begin() + static_cast<std::ptrdiff_t>(length));
    append_crc(frame, crc_extra_of(payload));
    return frame;
}

}  // namespace gimbal::mavlink
