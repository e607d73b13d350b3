// Builds pcapng files block by block, in either byte order, for the recording tests.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace gimbal::test {

using Bytes = std::vector<std::uint8_t>;

// Builds pcapng blocks in either byte order.
class Builder {
  public:
    explicit Builder(bool big_endian) : big_(big_endian) {}

    Builder& shb() {
        Bytes body;
        u32(body, 0x1A2B3C4D);
        u16(body, 1);
        u16(body, 0);
        u32(body, 0xFFFFFFFF);
        u32(body, 0xFFFFFFFF);
        return block(0x0A0D0D0A, body);
    }
    Builder& idb(const std::string& name, int tsresol = 6, std::uint16_t link = 252,
                 std::int64_t tsoffset = 0, const std::string& description = "") {
        Bytes body;
        u16(body, link);
        u16(body, 0);
        u32(body, 0);
        option(body, 2, Bytes(name.begin(), name.end()));
        if (!description.empty()) option(body, 3, Bytes(description.begin(), description.end()));
        if (tsresol >= 0) option(body, 9, {static_cast<std::uint8_t>(tsresol)});
        if (tsoffset != 0) {
            Bytes v;
            u32(v, static_cast<std::uint32_t>(static_cast<std::uint64_t>(tsoffset) >>
                                              (big_ ? 32 : 0)));
            u32(v, static_cast<std::uint32_t>(static_cast<std::uint64_t>(tsoffset) >>
                                              (big_ ? 0 : 32)));
            option(body, 14, v);
        }
        u32(body, 0);
        return block(1, body);
    }
    static Bytes exported_pdu(const std::string& dissector, const Bytes& pdu) {
        // Sized first and copied into: insert() at the end of a vector built from a brace
        // list makes GCC 12 -O3 on aarch64 report a false -Warray-bounds.
        const std::size_t name_end = 4 + dissector.size();
        const std::size_t padded = (name_end + 3) / 4 * 4;
        Bytes d(padded + 4 + pdu.size(), 0);
        d[1] = 0x0C;
        d[3] = static_cast<std::uint8_t>(dissector.size());
        std::copy(dissector.begin(), dissector.end(), d.begin() + 4);
        std::copy(pdu.begin(), pdu.end(), d.begin() + static_cast<std::ptrdiff_t>(padded + 4));
        return d;
    }
    Builder& epb(std::uint32_t itf, std::uint64_t ticks, const Bytes& data,
                 std::optional<std::uint32_t> flags = 1) {
        Bytes body;
        u32(body, itf);
        u32(body, static_cast<std::uint32_t>(ticks >> 32));
        u32(body, static_cast<std::uint32_t>(ticks));
        u32(body, static_cast<std::uint32_t>(data.size()));
        u32(body, static_cast<std::uint32_t>(data.size()));
        body.insert(body.end(), data.begin(), data.end());
        while (body.size() % 4) body.push_back(0);
        if (flags) {
            Bytes v;
            u32(v, *flags);
            option(body, 2, v);
            u32(body, 0);
        }
        return block(6, body);
    }
    Builder& block(std::uint32_t type, const Bytes& body) {
        boundaries.push_back(out.size());
        const auto total = static_cast<std::uint32_t>(body.size() + 12);
        u32(out, type);
        u32(out, total);
        out.insert(out.end(), body.begin(), body.end());
        u32(out, total);
        return *this;
    }

    Bytes out;
    std::vector<std::size_t> boundaries;  // start offset of every block

  private:
    void u16(Bytes& b, std::uint16_t v) {
        if (big_)
            b.insert(b.end(), {static_cast<std::uint8_t>(v >> 8), static_cast<std::uint8_t>(v)});
        else
            b.insert(b.end(), {static_cast<std::uint8_t>(v), static_cast<std::uint8_t>(v >> 8)});
    }
    void u32(Bytes& b, std::uint32_t v) {
        u16(b, static_cast<std::uint16_t>(big_ ? v >> 16 : v));
        u16(b, static_cast<std::uint16_t>(big_ ? v : v >> 16));
    }
    void option(Bytes& b, std::uint16_t code, const Bytes& value) {
        u16(b, code);
        u16(b, static_cast<std::uint16_t>(value.size()));
        b.insert(b.end(), value.begin(), value.end());
        while (b.size() % 4) b.push_back(0);
    }
    bool big_;
};

}  // namespace gimbal::test
