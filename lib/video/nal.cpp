#include "video/nal.hpp"

#include <algorithm>

namespace gimbal::video {

namespace {

constexpr std::uint8_t start_code[] = {0, 0, 0, 1};

void append(Bytes& out, ByteView bytes) {
    out.insert(out.end(), bytes.begin(), bytes.end());
}

// Index of the first byte after the next 00 00 01 at or after `from`, or npos.
std::size_t next_start(ByteView s, std::size_t from) {
    for (std::size_t i = from; i + 3 <= s.size();) {
        if (s[i + 2] > 1) {
            i += 3;
        } else if (s[i + 2] == 1 && s[i] == 0 && s[i + 1] == 0) {
            return i + 3;
        } else {
            ++i;
        }
    }
    return ByteView::extent;
}

std::uint8_t h265_type(std::uint8_t b) {
    return static_cast<std::uint8_t>((b >> 1) & 0x3F);
}

}  // namespace

std::vector<ByteView> split_annexb(ByteView stream) {
    std::vector<ByteView> nals;
    std::size_t begin = next_start(stream, 0);
    while (begin != ByteView::extent) {
        const std::size_t next = next_start(stream, begin);
        std::size_t end = next == ByteView::extent ? stream.size() : next - 3;
        while (end > begin && stream[end - 1] == 0) --end;
        if (end > begin) nals.push_back(stream.subspan(begin, end - begin));
        begin = next;
    }
    return nals;
}

std::uint8_t nal_type(Codec codec, ByteView nal) {
    if (nal.empty()) return 0xFF;
    return codec == Codec::h264 ? static_cast<std::uint8_t>(nal[0] & 0x1F) : h265_type(nal[0]);
}

bool is_vcl(Codec codec, std::uint8_t type) {
    return codec == Codec::h264 ? (type >= 1 && type <= 5) : type < 32;
}

bool is_parameter_set(Codec codec, std::uint8_t type) {
    return codec == Codec::h264 ? (type == h264::sps || type == h264::pps)
                                : (type >= h265::vps && type <= h265::pps);
}

bool is_key_nal(Codec codec, std::uint8_t type) {
    return codec == Codec::h264 ? type == h264::idr
                                : (type >= h265::bla_w_lp && type <= h265::rsv_irap_23);
}

bool is_key_frame(Codec codec, ByteView annexb_au) {
    // Every slice of a picture has the same kind, so the first VCL NAL decides; stopping
    // there keeps this cheap on large frames.
    for (std::size_t at = next_start(annexb_au, 0); at != ByteView::extent;
         at = next_start(annexb_au, at)) {
        if (at >= annexb_au.size()) break;
        const std::uint8_t type = nal_type(codec, annexb_au.subspan(at, 1));
        if (is_vcl(codec, type)) return is_key_nal(codec, type);
    }
    return false;
}

bool ParameterSets::has_sps(Codec codec) const {
    const std::uint8_t sps = codec == Codec::h264 ? h264::sps : h265::sps;
    return std::any_of(nals.begin(), nals.end(),
                       [&](const Bytes& n) { return nal_type(codec, n) == sps; });
}

void ParameterSets::update(Codec codec, ByteView nal) {
    const std::uint8_t type = nal_type(codec, nal);
    if (!is_parameter_set(codec, type)) return;
    for (Bytes& existing : nals) {
        if (nal_type(codec, existing) == type) {
            existing.assign(nal.begin(), nal.end());
            return;
        }
    }
    nals.emplace_back(nal.begin(), nal.end());
    // Decoders want VPS, SPS, PPS in that order; types sort that way in both codecs.
    std::stable_sort(nals.begin(), nals.end(), [&](const Bytes& a, const Bytes& b) {
        return nal_type(codec, a) < nal_type(codec, b);
    });
}

Bytes ParameterSets::annexb() const {
    Bytes out;
    for (const Bytes& nal : nals) {
        append(out, start_code);
        append(out, nal);
    }
    return out;
}

namespace {

bool looks_annexb(ByteView b) {
    return (b.size() >= 3 && b[0] == 0 && b[1] == 0 && b[2] == 1) ||
           (b.size() >= 4 && b[0] == 0 && b[1] == 0 && b[2] == 0 && b[3] == 1);
}

class Cursor {
  public:
    explicit Cursor(ByteView b) : b_(b) {}
    bool has(std::size_t n) const { return pos_ + n <= b_.size(); }
    std::uint32_t u8() { return has(1) ? b_[pos_++] : fail(); }
    std::uint32_t u16() { return has(2) ? (u8() << 8) | u8() : fail(); }
    ByteView take(std::size_t n) {
        if (!has(n)) {
            ok_ = false;
            return {};
        }
        const ByteView v = b_.subspan(pos_, n);
        pos_ += n;
        return v;
    }
    void skip(std::size_t n) { (void)take(n); }
    bool ok() const { return ok_; }

  private:
    std::uint32_t fail() {
        ok_ = false;
        return 0;
    }
    ByteView b_;
    std::size_t pos_ = 0;
    bool ok_ = true;
};

std::optional<Extradata> parse_avcc(ByteView b) {
    Cursor c(b);
    Extradata out;
    c.skip(4);  // configurationVersion, profile, compatibility, level
    out.length_size = static_cast<int>(c.u8() & 3) + 1;
    for (int kind = 0; kind < 2; ++kind) {  // SPS then PPS
        const std::uint32_t count = kind == 0 ? (c.u8() & 0x1F) : c.u8();
        for (std::uint32_t i = 0; i < count && c.ok(); ++i) {
            const ByteView nal = c.take(c.u16());
            if (c.ok() && !nal.empty()) out.sets.update(Codec::h264, nal);
        }
    }
    if (!c.ok() || out.length_size == 3) return std::nullopt;
    return out;
}

std::optional<Extradata> parse_hvcc(ByteView b) {
    Cursor c(b);
    Extradata out;
    c.skip(21);  // version, profile/tier/level, segmentation, parallelism, formats, frame rate
    out.length_size = static_cast<int>(c.u8() & 3) + 1;
    const std::uint32_t arrays = c.u8();
    for (std::uint32_t a = 0; a < arrays && c.ok(); ++a) {
        c.skip(1);  // array_completeness, reserved, NAL_unit_type
        const std::uint32_t count = c.u16();
        for (std::uint32_t i = 0; i < count && c.ok(); ++i) {
            const ByteView nal = c.take(c.u16());
            if (c.ok() && !nal.empty()) out.sets.update(Codec::h265, nal);
        }
    }
    if (!c.ok() || out.length_size == 3) return std::nullopt;
    return out;
}

}  // namespace

std::optional<Extradata> parse_extradata(Codec codec, ByteView extradata) {
    if (extradata.empty()) return std::nullopt;
    if (looks_annexb(extradata)) {
        Extradata out;
        for (const ByteView nal : split_annexb(extradata)) out.sets.update(codec, nal);
        return out;
    }
    if (extradata[0] != 1) return std::nullopt;  // configurationVersion
    return codec == Codec::h264 ? parse_avcc(extradata) : parse_hvcc(extradata);
}

std::optional<Bytes> length_prefixed_to_annexb(ByteView sample, int length_size) {
    if (length_size < 1 || length_size > 4) return std::nullopt;
    const auto ls = static_cast<std::size_t>(length_size);
    Bytes out;
    out.reserve(sample.size() + 16);
    std::size_t pos = 0;
    while (pos < sample.size()) {
        if (pos + ls > sample.size()) return std::nullopt;
        std::size_t n = 0;
        for (std::size_t i = 0; i < ls; ++i) n = (n << 8) | sample[pos + i];
        pos += ls;
        if (n > sample.size() - pos) return std::nullopt;
        append(out, start_code);
        append(out, sample.subspan(pos, n));
        pos += n;
    }
    return out;
}

Bytes with_parameter_sets(Codec codec, ByteView annexb_au, const ParameterSets& sets) {
    const std::vector<ByteView> nals = split_annexb(annexb_au);
    const bool key = is_key_frame(codec, annexb_au);
    bool has_sps = false;
    for (const ByteView nal : nals) {
        has_sps = has_sps || nal_type(codec, nal) == (codec == Codec::h264 ? h264::sps : h265::sps);
    }
    if (!key || has_sps || sets.empty()) return Bytes(annexb_au.begin(), annexb_au.end());
    Bytes out;
    out.reserve(annexb_au.size() + 256);
    bool inserted = false;
    for (const ByteView nal : nals) {
        if (!inserted && is_vcl(codec, nal_type(codec, nal))) {
            append(out, sets.annexb());
            inserted = true;
        }
        append(out, start_code);
        append(out, nal);
    }
    return out;
}

std::optional<VideoFormat> find_format(Codec codec, ByteView annexb_au) {
    const std::uint8_t sps = codec == Codec::h264 ? h264::sps : h265::sps;
    for (const ByteView nal : split_annexb(annexb_au)) {
        if (nal_type(codec, nal) == sps) return parse_sps(codec, nal);
    }
    return std::nullopt;
}

}  // namespace gimbal::video
