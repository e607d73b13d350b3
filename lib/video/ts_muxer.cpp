#include "video/ts_muxer.hpp"

#include <algorithm>
#include <cstring>

#include "video/pes.hpp"
#include "video/psi.hpp"
#include "video/ts_packet.hpp"

namespace gimbal::video {

namespace {

// Forward distance a -> b on the 33-bit clock, or nullopt when b is behind a (a jump back:
// a restarted encoder) so the caller can start over.
std::optional<std::uint64_t> elapsed(std::uint64_t a, std::uint64_t b) {
    const std::uint64_t d = (b - a) & (pts_modulus - 1);
    if (d > pts_modulus / 2) return std::nullopt;
    return d;
}

// A bounded PES leaves no doubt where it ends; KLV must be bounded (only video may be 0).
constexpr std::size_t max_klv_payload = 0xFFFF - 3 - 5;

}  // namespace

TsMuxer::TsMuxer(MuxerOptions options, Codec codec, Sink sink)
    : options_(options), codec_(codec), sink_(std::move(sink)) {
    options_.packets_per_chunk = std::max<std::size_t>(options_.packets_per_chunk, 1);
    chunk_.reserve(options_.packets_per_chunk * ts_packet_size);
}

void TsMuxer::set_codec(Codec codec) {
    if (codec == codec_) return;
    codec_ = codec;
    pmt_version_ = static_cast<std::uint8_t>((pmt_version_ + 1) & 0x1F);
    psi_due_ = true;
}

std::uint8_t& TsMuxer::cc_of(std::uint16_t pid) {
    if (pid == pat_pid) return cc_pat_;
    if (pid == options_.pmt_pid) return cc_pmt_;
    if (pid == options_.video_pid) return cc_video_;
    return cc_klv_;
}

std::size_t TsMuxer::packet(std::uint16_t pid, bool unit_start, const AdaptationFlags& flags,
                            std::span<const std::uint8_t> a, std::span<const std::uint8_t> b,
                            bool has_payload) {
    const std::size_t available = a.size() + b.size();
    const bool need_flags =
        flags.pcr_base.has_value() || flags.random_access || flags.discontinuity;
    std::size_t af_size = 0;  // adaptation field including its length byte
    if (need_flags) af_size = 2 + (flags.pcr_base ? 6 : 0);
    std::size_t payload = has_payload ? std::min(available, 184 - af_size) : 0;
    if (payload + af_size < 184) af_size = 184 - payload;  // stuff the rest
    // Only packets with payload advance the counter; one without repeats the last (2.4.3.3).
    std::uint8_t& counter = cc_of(pid);
    const std::uint8_t cc =
        has_payload ? counter : static_cast<std::uint8_t>((counter + 15) & 0x0F);
    if (has_payload) counter = static_cast<std::uint8_t>((counter + 1) & 0x0F);
    const std::size_t at = chunk_.size();
    chunk_.resize(at + ts_packet_size);
    std::uint8_t* p = chunk_.data() + at;
    p[0] = ts_sync_byte;
    p[1] = static_cast<std::uint8_t>((unit_start ? 0x40 : 0) | ((pid >> 8) & 0x1F));
    p[2] = static_cast<std::uint8_t>(pid & 0xFF);
    const unsigned control = (af_size > 0 ? 2u : 0u) | (has_payload ? 1u : 0u);
    p[3] = static_cast<std::uint8_t>((control << 4) | cc);
    std::size_t pos = 4;
    if (af_size > 0) {
        p[pos++] = static_cast<std::uint8_t>(af_size - 1);
        if (af_size > 1) {
            const std::size_t af_end = 4 + af_size;
            p[pos++] = static_cast<std::uint8_t>((flags.discontinuity ? 0x80 : 0) |
                                                 (flags.random_access ? 0x40 : 0) |
                                                 (flags.pcr_base ? 0x10 : 0));
            if (flags.pcr_base) {
                const std::uint64_t base = *flags.pcr_base % pts_modulus;
                p[pos++] = static_cast<std::uint8_t>(base >> 25);
                p[pos++] = static_cast<std::uint8_t>(base >> 17);
                p[pos++] = static_cast<std::uint8_t>(base >> 9);
                p[pos++] = static_cast<std::uint8_t>(base >> 1);
                p[pos++] = static_cast<std::uint8_t>(((base & 1) << 7) | 0x7E);  // reserved, ext 0
                p[pos++] = 0x00;
            }
            std::memset(p + pos, 0xFF, af_end - pos);
            pos = af_end;
        }
    }
    const std::size_t from_a = std::min(payload, a.size());
    if (from_a) std::memcpy(p + pos, a.data(), from_a);
    if (payload > from_a) std::memcpy(p + pos + from_a, b.data(), payload - from_a);
    ++stats_.packets;
    emit_if_full();
    return payload;
}

void TsMuxer::emit_if_full() {
    if (chunk_.size() < options_.packets_per_chunk * ts_packet_size) return;
    flush();
}

void TsMuxer::flush() {
    if (chunk_.empty()) return;
    ++stats_.chunks;
    if (sink_) sink_(chunk_);
    chunk_.clear();
}

void TsMuxer::write_psi() {
    Pat pat;
    pat.transport_stream_id = options_.transport_stream_id;
    pat.programs.push_back({options_.program_number, options_.pmt_pid});
    Pmt pmt;
    pmt.program_number = options_.program_number;
    pmt.version = pmt_version_;
    pmt.pcr_pid = options_.video_pid;
    pmt.streams.push_back(
        {codec_ == Codec::h264 ? stream_type::h264 : stream_type::h265, options_.video_pid, {}});
    if (options_.klv) {
        pmt.streams.push_back({stream_type::private_pes,
                               options_.klv_pid,
                               {0x05, 0x04, 'K', 'L', 'V', 'A'}});  // registration_descriptor
    }
    // pointer_field 0, the section, 0xFF to the end of the payload (2.4.4.1), as players
    // expect it (no adaptation-field stuffing in PSI packets).
    for (const auto& [pid, section] :
         {std::pair{pat_pid, build_pat(pat)}, std::pair{options_.pmt_pid, build_pmt(pmt)}}) {
        std::vector<std::uint8_t> payload(184, 0xFF);
        payload[0] = 0;
        std::copy(section.begin(), section.end(), payload.begin() + 1);
        packet(pid, true, {}, payload, {});
    }
    ++stats_.psi_repeats;
    psi_due_ = false;
}

void TsMuxer::maybe_psi(std::optional<std::uint64_t> now, bool key_frame) {
    bool due = psi_due_ || key_frame;
    if (now) {
        const auto since = last_psi_ ? elapsed(*last_psi_, *now) : std::nullopt;
        if (!since || *since >= options_.psi_interval) due = true;
    } else if (stats_.packets % 200 == 0) {
        due = true;  // no timestamps at all: fall back to a packet count
    }
    if (!due) return;
    write_psi();
    if (now) last_psi_ = now;
}

void TsMuxer::write_pes(std::uint16_t pid, std::span<const std::uint8_t> header,
                        std::span<const std::uint8_t> payload, const AdaptationFlags& first) {
    std::size_t h = 0;
    std::size_t p = 0;
    bool start = true;
    while (start || h < header.size() || p < payload.size()) {
        const auto a = std::span(header).subspan(h);
        const auto b = payload.subspan(p);
        const std::size_t n = packet(pid, start, start ? first : AdaptationFlags{}, a, b);
        const std::size_t from_a = std::min(n, a.size());
        h += from_a;
        p += n - from_a;
        start = false;
    }
}

// The PCR for a unit decoded at `dts`: dts - pcr_lead, never behind the last PCR (KLV
// may have moved it on a little); a jump of more than a second either way (a restarted
// encoder, a PTS wrap of the input) is flagged with discontinuity_indicator (2.4.3.5).
std::uint64_t TsMuxer::next_pcr(std::uint64_t dts, bool& discontinuity) {
    std::uint64_t pcr = (dts + pts_modulus - options_.pcr_lead % pts_modulus) % pts_modulus;
    discontinuity = false;
    if (last_pcr_) {
        const auto forward = elapsed(*last_pcr_, pcr);
        const auto back = elapsed(pcr, *last_pcr_);
        if (forward && *forward > pts_hz) {
            discontinuity = true;
        } else if (!forward && back && *back <= pts_hz) {
            pcr = *last_pcr_;
        } else if (!forward) {
            discontinuity = true;
        }
    }
    last_pcr_ = pcr;
    return pcr;
}

void TsMuxer::write_pcr_only(std::uint64_t pcr_base) {
    AdaptationFlags flags;
    flags.pcr_base = pcr_base;
    packet(options_.video_pid, false, flags, {}, {}, false);
    last_pcr_ = pcr_base;
    ++stats_.pcrs;
}

void TsMuxer::write_video(const AccessUnit& au) {
    if (au.data.empty()) {
        ++stats_.rejected;
        return;
    }
    if (au.codec != codec_) set_codec(au.codec);
    const std::optional<std::uint64_t> now = au.dts ? au.dts : au.pts;
    if (now) clock_ = now;
    maybe_psi(now, au.key_frame);
    AdaptationFlags first;
    first.random_access = au.key_frame;
    if (now) {
        first.pcr_base = next_pcr(*now, first.discontinuity);
        ++stats_.pcrs;
    }
    header_.clear();
    write_pes_header(header_, stream_id::video, au.data.size(), au.pts, au.dts, true);
    write_pes(options_.video_pid, header_, au.data, first);
    ++stats_.access_units;
    flush();
}

void TsMuxer::write_klv(std::span<const std::uint8_t> klv, std::optional<std::uint64_t> pts) {
    if (!options_.klv || klv.empty() || klv.size() > max_klv_payload) {
        ++stats_.rejected;
        return;
    }
    maybe_psi(pts ? pts : clock_, false);
    if (pts) {
        const std::uint64_t pcr =
            (*pts + pts_modulus - options_.pcr_lead % pts_modulus) % pts_modulus;
        // Only when the video has stalled: KLV timestamps may run ahead of the video's
        // DTS, and a PCR must not pass the DTS of the next unit.
        const auto since = last_pcr_ ? elapsed(*last_pcr_, pcr) : std::nullopt;
        if (since && *since >= options_.pcr_interval && *since <= pts_hz) write_pcr_only(pcr);
    }
    header_.clear();
    write_pes_header(header_, stream_id::private_stream_1, klv.size(), pts, std::nullopt, true);
    write_pes(options_.klv_pid, header_, klv, {});
    ++stats_.klv_units;
    flush();
}

}  // namespace gimbal::video
