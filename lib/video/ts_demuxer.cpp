#include "video/ts_demuxer.hpp"

#include <algorithm>
#include <cstring>

#include "video/nal.hpp"
#include "video/pes.hpp"

namespace gimbal::video {

namespace {

constexpr std::uint8_t no_cc = 0x10;
// A PES header is at most 9 + 255 bytes.
constexpr std::size_t max_pes_header_bytes = 264;
// A buffer that grew past this for one large unit gives its memory back afterwards.
constexpr std::size_t keep_capacity_bytes = 1u << 20;

void release_if_large(std::vector<std::uint8_t>& buffer) {
    if (buffer.capacity() > keep_capacity_bytes) std::vector<std::uint8_t>().swap(buffer);
}

bool is_klva_async(const PmtStream& s) {
    return s.stream_type == stream_type::private_pes &&
           registration_format(s.descriptors) == format_klva;
}

bool is_klva_sync(const PmtStream& s) {
    return s.stream_type == stream_type::metadata && has_klva_metadata_descriptor(s.descriptors);
}

std::optional<Codec> video_codec(std::uint8_t type) {
    if (type == stream_type::h264) return Codec::h264;
    if (type == stream_type::h265) return Codec::h265;
    return std::nullopt;
}

// The program a PMT describes, as far as this demuxer follows it.
ProgramInfo describe(std::uint16_t pmt_pid, const Pmt& pmt) {
    ProgramInfo info;
    info.program_number = pmt.program_number;
    info.pmt_pid = pmt_pid;
    info.pcr_pid = pmt.pcr_pid;
    for (const PmtStream& s : pmt.streams) {
        if (!info.codec) {
            if (const auto codec = video_codec(s.stream_type)) {
                info.codec = codec;
                info.video_pid = s.pid;
                continue;
            }
        }
        if (!info.klv) {
            if (is_klva_async(s)) {
                info.klv = KlvCarriage::async;
                info.klv_pid = s.pid;
            } else if (is_klva_sync(s)) {
                info.klv = KlvCarriage::sync;
                info.klv_pid = s.pid;
            }
        }
    }
    return info;
}

}  // namespace

TsDemuxer::TsDemuxer(Handlers handlers) : handlers_(std::move(handlers)) {
    last_cc_.fill(no_cc);
}

void TsDemuxer::push(std::span<const std::uint8_t> bytes) {
    stats_.bytes += bytes.size();
    if (carry_.empty()) {
        // The usual case (whole packets per datagram): no copy.
        const std::size_t used = consume(bytes);
        carry_.assign(bytes.begin() + static_cast<long>(used), bytes.end());
        return;
    }
    carry_.insert(carry_.end(), bytes.begin(), bytes.end());
    const std::size_t used = consume(carry_);
    carry_.erase(carry_.begin(), carry_.begin() + static_cast<long>(used));
}

// In sync, a 0x47 where the next packet should start is taken unless a packet confirmed by
// two sync bytes 188 apart starts inside it: then it is junk that happens to begin with
// 0x47 (junk after a packet instead leaves the packet alone). A packet at the end of the
// bytes is taken without waiting for the next datagram to confirm it.
bool TsDemuxer::overlaps_confirmed_packet(std::span<const std::uint8_t> data, std::size_t i) {
    const std::size_t n = data.size();
    if (n - i <= ts_packet_size || data[i + ts_packet_size] == ts_sync_byte) return false;
    for (std::size_t j = i + 1; j < i + ts_packet_size && j + ts_packet_size < n; ++j) {
        if (data[j] == ts_sync_byte && data[j + ts_packet_size] == ts_sync_byte) return true;
    }
    return false;
}

std::size_t TsDemuxer::consume(std::span<const std::uint8_t> data) {
    const std::size_t n = data.size();
    std::size_t i = 0;
    while (i < n) {
        if (synced_) {
            if (data[i] == ts_sync_byte && !overlaps_confirmed_packet(data, i)) {
                if (n - i < ts_packet_size) break;
                packet(data.subspan(i, ts_packet_size));
                i += ts_packet_size;
                continue;
            }
            synced_ = false;
            ++stats_.sync_losses;
        }
        // Hunting: a sync byte counts only when another follows one packet later.
        const void* found = std::memchr(data.data() + i, ts_sync_byte, n - i);
        if (found == nullptr) {
            stats_.junk_bytes += n - i;
            return n;
        }
        const auto at =
            static_cast<std::size_t>(static_cast<const std::uint8_t*>(found) - data.data());
        stats_.junk_bytes += at - i;
        i = at;
        if (n - i <= ts_packet_size) break;  // wait for the byte that confirms it
        if (data[i + ts_packet_size] == ts_sync_byte) {
            synced_ = true;
        } else {
            ++stats_.junk_bytes;
            ++i;
        }
    }
    return i;
}

void TsDemuxer::damage(std::uint16_t pid) {
    if (program_ && pid == program_->video_pid) video_.damaged = video_.active;
    if (program_ && pid == program_->klv_pid) klv_.damaged = klv_.active;
    if (pid == pat_pid) pat_assembler_.reset();
    if (const auto it = pmt_assemblers_.find(pid); it != pmt_assemblers_.end()) it->second.reset();
}

void TsDemuxer::packet(std::span<const std::uint8_t> bytes) {
    ++stats_.packets;
    const auto p = parse_ts_packet(bytes);
    if (!p) {
        ++stats_.bad_packets;
        return;
    }
    if (p->transport_error) {
        // The header itself may be wrong; the CC check of the next good packet finds the gap.
        ++stats_.transport_errors;
        return;
    }
    if (p->pid == null_pid) return;

    if (p->has_payload) {
        std::uint8_t& last = last_cc_[p->pid];
        if (last != no_cc && !p->discontinuity) {
            if (p->continuity_counter == last) return;  // duplicate packet
            if (p->continuity_counter != ((last + 1) & 0x0F)) {
                ++stats_.cc_errors;
                damage(p->pid);
            }
        }
        last = p->continuity_counter;
    }

    if (p->pcr && program_ && p->pid == program_->pcr_pid) {
        last_pcr_ = p->pcr;
        ++stats_.pcrs;
    }
    if (!p->has_payload) return;

    if (p->pid == pat_pid) {
        pat_assembler_.push(p->payload, p->payload_unit_start,
                            [&](std::span<const std::uint8_t> s) { on_pat(s); });
        return;
    }
    if (const auto it = pmt_assemblers_.find(p->pid); it != pmt_assemblers_.end()) {
        it->second.push(p->payload, p->payload_unit_start,
                        [&, pid = p->pid](std::span<const std::uint8_t> s) { on_pmt(pid, s); });
        return;
    }
    if (!program_) return;
    const bool video = p->pid == program_->video_pid;
    if (!video && p->pid != program_->klv_pid) return;
    if (p->scrambling != 0) {
        ++stats_.scrambled;
        damage(p->pid);
        return;
    }
    pes_packet(video ? video_ : klv_, *p, video);
}

void TsDemuxer::on_pat(std::span<const std::uint8_t> section) {
    if (pat_section_.size() == section.size() &&
        std::equal(section.begin(), section.end(), pat_section_.begin()))
        return;  // the usual repetition
    const auto pat = parse_pat(section);
    if (!pat) {
        ++stats_.psi_errors;
        return;
    }
    pat_section_.assign(section.begin(), section.end());
    std::map<std::uint16_t, std::uint16_t> pids;
    for (const PatProgram& prog : pat->programs) {
        if (prog.program_number != 0 && prog.pmt_pid != pat_pid && prog.pmt_pid != null_pid)
            pids.emplace(prog.pmt_pid, prog.program_number);
    }
    if (pids == pmt_pids_) return;
    pmt_pids_ = std::move(pids);
    // Forget the PMTs of PIDs no longer listed, and any whose program moved.
    for (auto it = pmt_assemblers_.begin(); it != pmt_assemblers_.end();) {
        it = pmt_pids_.count(it->first) ? std::next(it) : pmt_assemblers_.erase(it);
    }
    for (auto it = pmts_.begin(); it != pmts_.end();) {
        const auto listed = pmt_pids_.find(it->first);
        const bool keep = listed != pmt_pids_.end() && listed->second == it->second.program_number;
        if (!keep) pmt_sections_.erase(it->first);
        it = keep ? std::next(it) : pmts_.erase(it);
    }
    for (const auto& [pid, number] : pmt_pids_) pmt_assemblers_[pid];
    select_program();
}

void TsDemuxer::on_pmt(std::uint16_t pid, std::span<const std::uint8_t> section) {
    auto& last = pmt_sections_[pid];
    if (last.size() == section.size() && std::equal(section.begin(), section.end(), last.begin()))
        return;
    const auto pmt = parse_pmt(section);
    if (!pmt || pmt_pids_[pid] != pmt->program_number) {
        ++stats_.psi_errors;
        return;
    }
    last.assign(section.begin(), section.end());
    pmts_[pid] = *pmt;
    select_program();
}

void TsDemuxer::select_program() {
    std::optional<ProgramInfo> chosen;
    // PAT order by PMT PID is stable; prefer the first program with video, then one with KLV.
    for (const auto& [pid, pmt] : pmts_) {
        const ProgramInfo info = describe(pid, pmt);
        if (info.codec) {
            chosen = info;
            break;
        }
        if (info.klv && !chosen) chosen = info;
    }
    if (chosen == program_) return;
    const bool video_changed = !chosen || !program_ || chosen->video_pid != program_->video_pid ||
                               chosen->codec != program_->codec;
    const bool klv_changed = !chosen || !program_ || chosen->klv_pid != program_->klv_pid ||
                             chosen->klv != program_->klv;
    // The old PIDs are done: a PES still open on them ends here, as at the end of a stream.
    if (video_changed) {
        if (video_.active && program_ && program_->codec) finish_pes(video_, true);
        video_ = PesStream{};
    }
    if (klv_changed) {
        if (klv_.active && program_ && program_->klv) finish_pes(klv_, false);
        klv_ = PesStream{};
        klv_fragment_.clear();
        klv_fragment_open_ = false;
    }
    if (program_) ++stats_.program_changes;
    program_ = chosen;
    if (!program_) last_pcr_.reset();
    if (program_ && handlers_.program) handlers_.program(*program_);
}

void TsDemuxer::pes_packet(PesStream& s, const TsPacket& p, bool video) {
    if (p.payload_unit_start) {
        if (s.active) finish_pes(s, video);
        s.data.assign(p.payload.begin(), p.payload.end());
        s.active = true;
        s.damaged = false;
    } else {
        if (!s.active) return;  // joined mid-PES: wait for the next start
        const std::size_t bound =
            max_pes_header_bytes + (video ? max_access_unit_bytes : max_klv_pes_bytes);
        if (s.data.size() + p.payload.size() > bound) {
            // No end in sight (a broken or hostile stream): memory stays bounded.
            ++(video ? stats_.oversized_units : stats_.oversized_klv);
            s.active = false;
            s.data.clear();
            release_if_large(s.data);
            return;
        }
        s.data.insert(s.data.end(), p.payload.begin(), p.payload.end());
    }
    // A bounded PES is complete as soon as its length is in; an unbounded one (video from
    // most encoders) when a packet is stuffed, which a muxer does only at the end of a PES.
    // Either way the unit goes out now instead of when the next one starts.
    if (s.data.size() >= 6) {
        const std::size_t length = (std::size_t{s.data[4]} << 8) | s.data[5];
        if (length != 0 ? s.data.size() >= 6 + length : p.stuffed) finish_pes(s, video);
    }
}

void TsDemuxer::finish_pes(PesStream& s, bool video) {
    s.active = false;
    deliver_pes(s, video);
    release_if_large(s.data);
}

void TsDemuxer::deliver_pes(PesStream& s, bool video) {
    if (s.damaged) {
        ++stats_.dropped_units;
        return;
    }
    const auto header = parse_pes_header(s.data);
    if (!header) {
        ++stats_.pes_errors;
        return;
    }
    std::size_t end = s.data.size();
    if (header->packet_length != 0) end = std::min(end, 6 + header->packet_length);
    if (end < header->header_size) {
        ++stats_.pes_errors;
        return;
    }
    const std::span<const std::uint8_t> payload(s.data.data() + header->header_size,
                                                end - header->header_size);
    if (video) {
        AccessUnit au;
        au.codec = *program_->codec;
        au.pts = header->pts;
        au.dts = header->dts;
        au.key_frame = is_key_frame(au.codec, payload);
        au.data = payload;
        ++stats_.access_units;
        if (handlers_.access_unit) handlers_.access_unit(au);
        return;
    }
    if (program_->klv == KlvCarriage::sync) {
        deliver_klv_cells(payload, header->pts);
        return;
    }
    ++stats_.klv_units;
    if (handlers_.klv) handlers_.klv(KlvUnit{KlvCarriage::async, header->pts, payload});
}

// Metadata access unit cells (13818-1 Table 2-99): service id, sequence number, fragment
// indication (2 bits: 11 whole, 10 first, 00 middle, 01 last), flags, 16-bit length, data.
void TsDemuxer::deliver_klv_cells(std::span<const std::uint8_t> payload,
                                  std::optional<std::uint64_t> pts) {
    std::size_t i = 0;
    while (i + 5 <= payload.size()) {
        const unsigned fragment = payload[i + 2] >> 6;
        const std::size_t length = (std::size_t{payload[i + 3]} << 8) | payload[i + 4];
        if (i + 5 + length > payload.size()) {
            ++stats_.pes_errors;
            return;
        }
        const auto cell = payload.subspan(i + 5, length);
        i += 5 + length;
        if (fragment == 3) {
            ++stats_.klv_units;
            if (handlers_.klv) handlers_.klv(KlvUnit{KlvCarriage::sync, pts, cell});
            continue;
        }
        if (fragment == 2) {
            if (klv_fragment_open_) ++stats_.metadata_dropped;  // its last part never came
            klv_fragment_.clear();
            klv_fragment_open_ = true;
        }
        if (!klv_fragment_open_) {  // a middle or last part without its first
            ++stats_.metadata_dropped;
            continue;
        }
        if (klv_fragment_.size() + cell.size() > max_metadata_au_bytes) {
            // Middle parts without end (a broken or hostile stream): memory stays bounded.
            ++stats_.metadata_dropped;
            klv_fragment_.clear();
            klv_fragment_open_ = false;
            continue;
        }
        klv_fragment_.insert(klv_fragment_.end(), cell.begin(), cell.end());
        if (fragment == 1) {
            ++stats_.klv_units;
            if (handlers_.klv) handlers_.klv(KlvUnit{KlvCarriage::sync, pts, klv_fragment_});
            klv_fragment_.clear();
            klv_fragment_open_ = false;
        }
    }
}

void TsDemuxer::flush() {
    if (!program_) return;
    if (video_.active) finish_pes(video_, true);
    if (klv_.active) finish_pes(klv_, false);
}

}  // namespace gimbal::video
