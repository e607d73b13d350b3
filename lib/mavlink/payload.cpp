#include "mavlink/payload.hpp"

#include <algorithm>
#include <bit>
#include <type_traits>

namespace gimbal::mavlink {

namespace {

// Little-endian writer over a payload buffer.
class Writer {
  public:
    explicit Writer(PayloadBytes& out) : out_(out) {}
    template <class T>
    void put(T value) {
        using U =
            std::make_unsigned_t<std::conditional_t<std::is_same_v<T, float>, std::uint32_t, T>>;
        const U bits = std::bit_cast<U>(value);
        for (std::size_t i = 0; i < sizeof(U); ++i)
            out_.bytes[out_.size++] = static_cast<std::uint8_t>(bits >> (8 * i));
    }

  private:
    PayloadBytes& out_;
};

// Little-endian reader over a zero-extended payload.
class Reader {
  public:
    explicit Reader(const std::uint8_t* in) : in_(in) {}
    template <class T>
    T get() {
        using U =
            std::make_unsigned_t<std::conditional_t<std::is_same_v<T, float>, std::uint32_t, T>>;
        U bits = 0;
        for (std::size_t i = 0; i < sizeof(U); ++i)
            bits = static_cast<U>(bits | static_cast<U>(static_cast<U>(in_[at_ + i]) << (8 * i)));
        at_ += sizeof(U);
        return std::bit_cast<T>(bits);
    }

  private:
    const std::uint8_t* in_;
    std::size_t at_ = 0;
};

void write(Writer& w, const Heartbeat& m) {
    w.put(m.custom_mode);
    w.put(m.type);
    w.put(m.autopilot);
    w.put(m.base_mode);
    w.put(m.system_status);
    w.put(m.mavlink_version);
}

void read(Reader& r, Heartbeat& m) {
    m.custom_mode = r.get<std::uint32_t>();
    m.type = r.get<std::uint8_t>();
    m.autopilot = r.get<std::uint8_t>();
    m.base_mode = r.get<std::uint8_t>();
    m.system_status = r.get<std::uint8_t>();
    m.mavlink_version = r.get<std::uint8_t>();
}

void write(Writer& w, const SystemTime& m) {
    w.put(m.time_unix_usec);
    w.put(m.time_boot_ms);
}

void read(Reader& r, SystemTime& m) {
    m.time_unix_usec = r.get<std::uint64_t>();
    m.time_boot_ms = r.get<std::uint32_t>();
}

void write(Writer& w, const Attitude& m) {
    w.put(m.time_boot_ms);
    w.put(m.roll);
    w.put(m.pitch);
    w.put(m.yaw);
    w.put(m.rollspeed);
    w.put(m.pitchspeed);
    w.put(m.yawspeed);
}

void read(Reader& r, Attitude& m) {
    m.time_boot_ms = r.get<std::uint32_t>();
    m.roll = r.get<float>();
    m.pitch = r.get<float>();
    m.yaw = r.get<float>();
    m.rollspeed = r.get<float>();
    m.pitchspeed = r.get<float>();
    m.yawspeed = r.get<float>();
}

void write(Writer& w, const GlobalPositionInt& m) {
    w.put(m.time_boot_ms);
    w.put(m.lat);
    w.put(m.lon);
    w.put(m.alt);
    w.put(m.relative_alt);
    w.put(m.vx);
    w.put(m.vy);
    w.put(m.vz);
    w.put(m.hdg);
}

void read(Reader& r, GlobalPositionInt& m) {
    m.time_boot_ms = r.get<std::uint32_t>();
    m.lat = r.get<std::int32_t>();
    m.lon = r.get<std::int32_t>();
    m.alt = r.get<std::int32_t>();
    m.relative_alt = r.get<std::int32_t>();
    m.vx = r.get<std::int16_t>();
    m.vy = r.get<std::int16_t>();
    m.vz = r.get<std::int16_t>();
    m.hdg = r.get<std::uint16_t>();
}

// chancount is declared before the channels in common.xml but, being one byte, travels after
// them.
void write(Writer& w, const RcChannels& m) {
    w.put(m.time_boot_ms);
    for (const std::uint16_t c : m.chan_raw) w.put(c);
    w.put(m.chancount);
    w.put(m.rssi);
}

void read(Reader& r, RcChannels& m) {
    m.time_boot_ms = r.get<std::uint32_t>();
    for (std::uint16_t& c : m.chan_raw) c = r.get<std::uint16_t>();
    m.chancount = r.get<std::uint8_t>();
    m.rssi = r.get<std::uint8_t>();
}

template <class M>
Payload decode_as(std::span<const std::uint8_t> bytes) {
    std::array<std::uint8_t, max_known_length> padded{};
    std::copy_n(bytes.begin(), std::min<std::size_t>(bytes.size(), M::length), padded.begin());
    Reader r(padded.data());
    M m;
    read(r, m);
    return m;
}

constexpr MessageInfo info_of(auto message) {
    using M = decltype(message);
    return {M::id, M::length, M::crc_extra};
}

constexpr std::array known_messages{info_of(Heartbeat{}), info_of(SystemTime{}),
                                    info_of(Attitude{}), info_of(GlobalPositionInt{}),
                                    info_of(RcChannels{})};

}  // namespace

const MessageInfo* find_message(std::uint32_t msgid) {
    for (const MessageInfo& info : known_messages)
        if (info.id == msgid) return &info;
    return nullptr;
}

std::uint32_t message_id(const Payload& payload) {
    return std::visit([](const auto& m) { return std::decay_t<decltype(m)>::id; }, payload);
}

PayloadBytes encode_payload(const Payload& payload) {
    PayloadBytes out;
    Writer w(out);
    std::visit([&](const auto& m) { write(w, m); }, payload);
    return out;
}

std::optional<Payload> decode_payload(std::uint32_t msgid, std::span<const std::uint8_t> bytes) {
    switch (msgid) {
        case Heartbeat::id:
            return decode_as<Heartbeat>(bytes);
        case SystemTime::id:
            return decode_as<SystemTime>(bytes);
        case Attitude::id:
            return decode_as<Attitude>(bytes);
        case GlobalPositionInt::id:
            return decode_as<GlobalPositionInt>(bytes);
        case RcChannels::id:
            return decode_as<RcChannels>(bytes);
        default:
            return std::nullopt;
    }
}

}  // namespace gimbal::mavlink
