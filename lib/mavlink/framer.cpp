#include "mavlink/framer.hpp"

#include "mavlink/payload.hpp"
#include "mavlink/signing.hpp"

namespace gimbal::mavlink {

Framer::Step Framer::examine(const std::uint8_t* frame, std::size_t available, bool last) {
    // Past the end of a datagram nothing more will come: what does not fit is no frame.
    const Step need_more{last ? Outcome::false_start : Outcome::need_more};
    const bool v2 = frame[0] == magic_v2;
    // An unknown incompat flag may change the frame layout: nothing after it can be trusted.
    if (v2 && available >= 3 && (frame[2] & ~incompat_signed) != 0) {
        ++stats_.bad_incompat;
        return {Outcome::false_start};
    }
    const std::size_t header = v2 ? header_size_v2 : header_size_v1;
    if (available < header) return need_more;

    const std::size_t length = frame[1];
    const bool is_signed = v2 && (frame[2] & incompat_signed) != 0;
    const std::uint32_t msgid =
        v2 ? static_cast<std::uint32_t>(frame[7] | (frame[8] << 8) | (frame[9] << 16)) : frame[5];
    const MessageInfo* info = find_message(msgid);
    // MAVLink 1 has no truncation: a short payload is not this message.
    if (!v2 && info && length < info->length) {
        ++stats_.bad_length;
        return {Outcome::false_start};
    }
    const std::size_t total =
        header + length + checksum_size + (is_signed ? signature_size : std::size_t{0});

    if (!info) {
        // No CRC_EXTRA, no CRC check: trust the length only if the next frame starts after it
        // (or, in a datagram, the datagram ends right after it).
        const bool ends_here = last && available == total;
        if (available < total + 1 && !ends_here) return need_more;
        if (!ends_here && !is_magic(frame[total])) return {Outcome::false_start};
        ++stats_.unknown_ids;
        return {Outcome::skipped, total};
    }

    if (available < total) return need_more;
    const std::uint16_t crc = frame_crc({frame + 1, header - 1 + length}, info->crc_extra);
    const std::size_t at = header + length;
    if (frame[at] != (crc & 0xFF) || frame[at + 1] != (crc >> 8)) {
        ++stats_.bad_crc;
        return {Outcome::false_start};
    }
    if (is_signed && !options_.accept_signed) {
        ++stats_.signed_rejected;
        return {Outcome::skipped, total};
    }

    message_.version = v2 ? 2 : 1;
    message_.seq = frame[v2 ? 4 : 2];
    message_.sysid = frame[v2 ? 5 : 3];
    message_.compid = frame[v2 ? 6 : 4];
    message_.msgid = msgid;
    message_.payload = *decode_payload(msgid, {frame + header, length});
    message_.signature.reset();
    if (is_signed) {
        const std::uint8_t* sig = frame + header + length + checksum_size;
        Signature s{sig[0], 0, false};
        for (std::size_t i = 0; i < 6; ++i) s.timestamp |= std::uint64_t{sig[1 + i]} << (8 * i);
        if (options_.signing_key)
            s.verified = verify_signature(*options_.signing_key, {frame, total});
        message_.signature = s;
    }
    return {Outcome::delivered, total};
}

}  // namespace gimbal::mavlink
