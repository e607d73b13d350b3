#include "mavlink/payload.hpp"

#include <algorithm>
#include <bit>
#include <type_traits>
#include <utility>
#include <variant>

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
    template <class T, std::size_t N>
    void put(const std::array<T, N>& values) {
        for (const T& v : values) put(v);
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
    template <class T, std::size_t N>
    void get(std::array<T, N>& values) {
        for (T& v : values) v = get<T>();
    }
    template <class T>
    void get(T& value) {
        value = get<T>();
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

// The gimbal-manager messages (ids from 75 on): one field list each, in wire order, shared by read
// and write.
template <class IO, class Q>
void fields(IO& io, Q& m) {
    using M = std::remove_const_t<Q>;
    if constexpr (std::is_same_v<M, CommandInt>) {
        io(m.param1, m.param2, m.param3, m.param4, m.x, m.y, m.z, m.command, m.target_system,
           m.target_component, m.frame, m.current, m.autocontinue);
    } else if constexpr (std::is_same_v<M, CommandLong>) {
        io(m.param, m.command, m.target_system, m.target_component, m.confirmation);
    } else if constexpr (std::is_same_v<M, CommandAck>) {
        io(m.command, m.result, m.progress, m.result_param2, m.target_system, m.target_component);
    } else if constexpr (std::is_same_v<M, CameraInformation>) {
        io(m.time_boot_ms, m.firmware_version, m.focal_length, m.sensor_size_h, m.sensor_size_v,
           m.flags, m.resolution_h, m.resolution_v, m.cam_definition_version, m.vendor_name,
           m.model_name, m.lens_id, m.cam_definition_uri, m.gimbal_device_id, m.camera_device_id);
    } else if constexpr (std::is_same_v<M, CameraSettings>) {
        io(m.time_boot_ms, m.mode_id, m.zoom_level, m.focus_level, m.camera_device_id);
    } else if constexpr (std::is_same_v<M, StorageInformation>) {
        io(m.time_boot_ms, m.total_capacity, m.used_capacity, m.available_capacity, m.read_speed,
           m.write_speed, m.storage_id, m.storage_count, m.status, m.type, m.name, m.storage_usage);
    } else if constexpr (std::is_same_v<M, CameraCaptureStatus>) {
        io(m.time_boot_ms, m.image_interval, m.recording_time_ms, m.available_capacity,
           m.image_status, m.video_status, m.image_count, m.camera_device_id);
    } else if constexpr (std::is_same_v<M, VideoStreamInformation>) {
        io(m.framerate, m.bitrate, m.flags, m.resolution_h, m.resolution_v, m.rotation, m.hfov,
           m.stream_id, m.count, m.type, m.name, m.uri, m.encoding, m.camera_device_id);
    } else if constexpr (std::is_same_v<M, VideoStreamStatus>) {
        io(m.framerate, m.bitrate, m.flags, m.resolution_h, m.resolution_v, m.rotation, m.hfov,
           m.stream_id, m.camera_device_id);
    } else if constexpr (std::is_same_v<M, CameraTrackingImageStatus>) {
        io(m.point_x, m.point_y, m.radius, m.rec_top_x, m.rec_top_y, m.rec_bottom_x, m.rec_bottom_y,
           m.tracking_status, m.tracking_mode, m.target_data, m.camera_device_id);
    } else if constexpr (std::is_same_v<M, CameraTrackingGeoStatus>) {
        io(m.lat, m.lon, m.alt, m.h_acc, m.v_acc, m.vel_n, m.vel_e, m.vel_d, m.vel_acc, m.dist,
           m.hdg, m.hdg_acc, m.tracking_status, m.camera_device_id);
    } else if constexpr (std::is_same_v<M, CameraFovStatus>) {
        io(m.time_boot_ms, m.lat_camera, m.lon_camera, m.alt_camera, m.lat_image, m.lon_image,
           m.alt_image, m.q, m.hfov, m.vfov, m.camera_device_id);
    } else if constexpr (std::is_same_v<M, GimbalManagerInformation>) {
        io(m.time_boot_ms, m.cap_flags, m.roll_min, m.roll_max, m.pitch_min, m.pitch_max, m.yaw_min,
           m.yaw_max, m.gimbal_device_id);
    } else if constexpr (std::is_same_v<M, GimbalManagerStatus>) {
        io(m.time_boot_ms, m.flags, m.gimbal_device_id, m.primary_control_sysid,
           m.primary_control_compid, m.secondary_control_sysid, m.secondary_control_compid);
    } else if constexpr (std::is_same_v<M, GimbalManagerSetAttitude>) {
        io(m.flags, m.q, m.angular_velocity_x, m.angular_velocity_y, m.angular_velocity_z,
           m.target_system, m.target_component, m.gimbal_device_id);
    } else if constexpr (std::is_same_v<M, GimbalDeviceInformation>) {
        io(m.uid, m.time_boot_ms, m.firmware_version, m.hardware_version, m.roll_min, m.roll_max,
           m.pitch_min, m.pitch_max, m.yaw_min, m.yaw_max, m.cap_flags, m.custom_cap_flags,
           m.vendor_name, m.model_name, m.custom_name, m.gimbal_device_id, m.cap_flags2);
    } else if constexpr (std::is_same_v<M, GimbalDeviceSetAttitude>) {
        io(m.q, m.angular_velocity_x, m.angular_velocity_y, m.angular_velocity_z, m.flags,
           m.target_system, m.target_component);
    } else if constexpr (std::is_same_v<M, GimbalDeviceAttitudeStatus>) {
        io(m.time_boot_ms, m.q, m.angular_velocity_x, m.angular_velocity_y, m.angular_velocity_z,
           m.failure_flags, m.flags, m.target_system, m.target_component, m.delta_yaw,
           m.delta_yaw_velocity, m.gimbal_device_id);
    } else if constexpr (std::is_same_v<M, AutopilotStateForGimbalDevice>) {
        io(m.time_boot_us, m.q, m.q_estimated_delay_us, m.vx, m.vy, m.vz, m.v_estimated_delay_us,
           m.feed_forward_angular_velocity_z, m.estimator_status, m.target_system,
           m.target_component, m.landed_state, m.angular_velocity_z);
    } else if constexpr (std::is_same_v<M, GimbalManagerSetPitchyaw>) {
        io(m.flags, m.pitch, m.yaw, m.pitch_rate, m.yaw_rate, m.target_system, m.target_component,
           m.gimbal_device_id);
    }
}

template <class M>
requires(M::id >= 75) void write(Writer& w, const M& m) {
    auto io = [&](const auto&... f) { (w.put(f), ...); };
    fields(io, m);
}

template <class M>
requires(M::id >= 75) void read(Reader& r, M& m) {
    auto io = [&](auto&... f) { (r.get(f), ...); };
    fields(io, m);
}

template <class M>
Payload decode_as(std::span<const std::uint8_t> bytes) {
    std::array<std::uint8_t, max_known_length> padded{};
    std::copy_n(bytes.begin(), std::min<std::size_t>(bytes.size(), M::max_length), padded.begin());
    Reader r(padded.data());
    M m;
    read(r, m);
    return m;
}

constexpr MessageInfo info_of(auto message) {
    using M = decltype(message);
    return {M::id, M::length, M::crc_extra, M::max_length};
}

template <std::size_t... I>
constexpr auto all_infos(std::index_sequence<I...>) {
    return std::array{info_of(std::variant_alternative_t<I, Payload>{})...};
}

constexpr auto known_messages = all_infos(std::make_index_sequence<std::variant_size_v<Payload>>{});

template <std::size_t... I>
std::optional<Payload> decode_by_id(std::uint32_t msgid, std::span<const std::uint8_t> bytes,
                                    std::index_sequence<I...>) {
    std::optional<Payload> out;
    const auto try_one = [&]<class M>(M*) {
        if (M::id != msgid) return false;
        out = decode_as<M>(bytes);
        return true;
    };
    (void)(try_one(static_cast<std::variant_alternative_t<I, Payload>*>(nullptr)) || ...);
    return out;
}

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
    return decode_by_id(msgid, bytes, std::make_index_sequence<std::variant_size_v<Payload>>{});
}

}  // namespace gimbal::mavlink
