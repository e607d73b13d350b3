#include "video/psi.hpp"

#include "video/crc32.hpp"

namespace gimbal::video {

namespace {

using Bytes = std::vector<std::uint8_t>;
using View = std::span<const std::uint8_t>;

std::uint16_t u16(View b, std::size_t at) {
    return static_cast<std::uint16_t>((b[at] << 8) | b[at + 1]);
}

// Checks the long-form section header common to PAT and PMT; returns the body between the
// 8-byte header and the CRC.
std::optional<View> section_body(View s, std::uint8_t table_id) {
    if (s.size() < 12 || s[0] != table_id || (s[1] & 0x80) == 0) return std::nullopt;
    const std::size_t length = u16(s, 1) & 0x0FFFu;
    if (length + 3 != s.size() || length > 1021) return std::nullopt;
    if (crc32_mpeg2(s) != 0) return std::nullopt;
    if ((s[5] & 0x01) == 0) return std::nullopt;  // current_next_indicator: not yet valid
    return s.subspan(8, s.size() - 12);
}

void put16(Bytes& out, std::uint32_t v) {
    out.push_back(static_cast<std::uint8_t>(v >> 8));
    out.push_back(static_cast<std::uint8_t>(v));
}

// table_id, lengths, table_id_extension, version, section numbers 0/0, body, CRC.
Bytes finish_section(std::uint8_t table_id, std::uint16_t extension, std::uint8_t version,
                     const Bytes& body) {
    Bytes s;
    s.push_back(table_id);
    put16(s, 0xB000u | static_cast<std::uint32_t>(body.size() + 9));  // syntax 1, '0', reserved
    put16(s, extension);
    s.push_back(static_cast<std::uint8_t>(0xC1 | ((version & 0x1F) << 1)));
    s.push_back(0);  // section_number
    s.push_back(0);  // last_section_number
    s.insert(s.end(), body.begin(), body.end());
    const std::uint32_t crc = crc32_mpeg2(s);
    put16(s, crc >> 16);
    put16(s, crc & 0xFFFFu);
    return s;
}

}  // namespace

std::optional<Pat> parse_pat(View section) {
    const auto body = section_body(section, 0x00);
    if (!body || body->size() % 4 != 0) return std::nullopt;
    Pat pat;
    pat.transport_stream_id = u16(section, 3);
    pat.version = static_cast<std::uint8_t>((section[5] >> 1) & 0x1F);
    for (std::size_t i = 0; i < body->size(); i += 4) {
        pat.programs.push_back(
            {u16(*body, i), static_cast<std::uint16_t>(u16(*body, i + 2) & 0x1FFF)});
    }
    return pat;
}

std::optional<Pmt> parse_pmt(View section) {
    const auto body = section_body(section, 0x02);
    if (!body || body->size() < 4) return std::nullopt;
    const View b = *body;
    Pmt pmt;
    pmt.program_number = u16(section, 3);
    pmt.version = static_cast<std::uint8_t>((section[5] >> 1) & 0x1F);
    pmt.pcr_pid = u16(b, 0) & 0x1FFF;
    const std::size_t info = u16(b, 2) & 0x0FFFu;
    if (4 + info > b.size()) return std::nullopt;
    pmt.program_descriptors.assign(b.begin() + 4, b.begin() + static_cast<long>(4 + info));
    for (std::size_t i = 4 + info; i < b.size();) {
        if (i + 5 > b.size()) return std::nullopt;
        PmtStream s;
        s.stream_type = b[i];
        s.pid = u16(b, i + 1) & 0x1FFF;
        const std::size_t es_info = u16(b, i + 3) & 0x0FFFu;
        if (i + 5 + es_info > b.size()) return std::nullopt;
        s.descriptors.assign(b.begin() + static_cast<long>(i + 5),
                             b.begin() + static_cast<long>(i + 5 + es_info));
        pmt.streams.push_back(std::move(s));
        i += 5 + es_info;
    }
    return pmt;
}

Bytes build_pat(const Pat& pat) {
    Bytes body;
    for (const PatProgram& p : pat.programs) {
        put16(body, p.program_number);
        put16(body, 0xE000u | (p.pmt_pid & 0x1FFFu));
    }
    return finish_section(0x00, pat.transport_stream_id, pat.version, body);
}

Bytes build_pmt(const Pmt& pmt) {
    Bytes body;
    put16(body, 0xE000u | (pmt.pcr_pid & 0x1FFFu));
    put16(body, 0xF000u | static_cast<std::uint32_t>(pmt.program_descriptors.size()));
    body.insert(body.end(), pmt.program_descriptors.begin(), pmt.program_descriptors.end());
    for (const PmtStream& s : pmt.streams) {
        body.push_back(s.stream_type);
        put16(body, 0xE000u | (s.pid & 0x1FFFu));
        put16(body, 0xF000u | static_cast<std::uint32_t>(s.descriptors.size()));
        body.insert(body.end(), s.descriptors.begin(), s.descriptors.end());
    }
    return finish_section(0x02, pmt.program_number, pmt.version, body);
}

namespace {

template <class F>
void for_each_descriptor(View d, F&& f) {
    for (std::size_t i = 0; i + 2 <= d.size();) {
        const std::size_t length = d[i + 1];
        if (i + 2 + length > d.size()) return;
        f(d[i], d.subspan(i + 2, length));
        i += 2 + length;
    }
}

std::uint32_t u32(View b, std::size_t at) {
    return (std::uint32_t{b[at]} << 24) | (std::uint32_t{b[at + 1]} << 16) |
           (std::uint32_t{b[at + 2]} << 8) | b[at + 3];
}

}  // namespace

std::optional<std::uint32_t> registration_format(View descriptors) {
    std::optional<std::uint32_t> format;
    for_each_descriptor(descriptors, [&](std::uint8_t tag, View body) {
        if (tag == 0x05 && body.size() >= 4 && !format) format = u32(body, 0);
    });
    return format;
}

bool has_klva_metadata_descriptor(View descriptors) {
    bool found = false;
    for_each_descriptor(descriptors, [&](std::uint8_t tag, View body) {
        if (tag != 0x26 || body.size() < 3) return;
        // metadata_application_format (0xFFFF adds a 32-bit identifier), then metadata_format
        // (0xFF adds metadata_format_identifier).
        std::size_t at = 2;
        if (u16(body, 0) == 0xFFFF) at += 4;
        if (at >= body.size()) return;
        if (body[at] == 0xFF) {
            found = found || (at + 5 <= body.size() && u32(body, at + 1) == format_klva);
        }
    });
    return found;
}

}  // namespace gimbal::video
