#include <stdexcept>
#include <string>

#include "protocols/siyi/codec/json.hpp"
#include "protocols/siyi/sim/siyi_sim.hpp"
#include "protocols/siyi/sim/siyi_sim_camera.hpp"
#include "protocols/siyi/siyi_entry.hpp"

namespace gimbal::protocols {

using nlohmann::json;

namespace {

using Flag = SimFlag;

constexpr std::string_view manual =
    R"(       --protocol siyi: a simulated SIYI gimbal camera (SDK v0.1.1, docs/siyi.md),
       usually over --udp (the camera's port is 37260) or --pty (115200 8N1). It
       answers as the --model would: its hardware id (the model's two-character
       prefix), firmware versions (0.0.0 for --boot-time seconds), attitude (0x0D,
       and the 0x25 stream at the rate asked for), zoom (0x0F absolute, 0x05 steps,
       0x16 range, 0x18 current), recording (0x0C, 0x0A, the 0x0B feedback; without
       an SD card a recording fails), and on the ZT30 the laser's range (0x15 and
       its stream) and target (0x17) over flat ground --height metres below. Its
       axes slew at the model's top rate within its limits, to absolute angles
       (0x0E, 0x08) or at speeds (0x07). Unknown commands get no reply, as on a
       camera that does not support them. --video renders what its main camera
       sees (the model's field of view at the current zoom, pitch stabilized, yaw
       from the nose) from where the aircraft is: as gimbald last sent it (0x3E
       position, 0x22 attitude), else at --lat, --lon and --alt (metres above
       MSL; --geoid-undulation below the ellipsoid), level and heading north.
       --alt above --terrain-alt sets the laser's --height.
)";

constexpr std::string_view rx_log_manual =
    R"(       With --protocol siyi, one line per valid SIYI frame:
           {"t": 1.234, "src": "udp", "kind": "set_gimbal_attitude", "cmd": 14,
            "ctrl": 1, "seq": 3, "len": 14, "hex": "5566...", "message": {...}}
       kind is the message's name; message its fields (angles in degrees, SIYI's
       frame: yaw positive left).
)";

constexpr Flag flags[] = {
    {"--model", "model", Flag::Type::text, "Camera model: a8mini, zr10, zr30, zt30 or zt6"},
    {"--angle-noise", "angle_noise_deg", Flag::Type::number,
     "Noise (1 sigma) on the reported angles, degrees", Flag::Check::non_negative},
    {"--boot-time", "boot_time_s", Flag::Type::number,
     "Seconds the firmware versions read 0.0.0 after start", Flag::Check::non_negative},
    {"--no-sd-card", "no_sd_card", Flag::Type::flag, "No SD card: recordings fail"},
    {"--height", "height_above_ground_m", Flag::Type::number,
     "Flat ground this far below the camera (the ZT30's laser), metres", Flag::Check::positive},
};

json defaults() {
    const SiyiSimOptions o;
    return {{"model", std::string(siyi::model_info(o.model).key)},
            {"angle_noise_deg", o.angle_noise_deg},
            {"boot_time_s", o.boot_time_s},
            {"no_sd_card", !o.sd_card},
            {"height_above_ground_m", o.height_above_ground_m}};
}

std::unique_ptr<sim::Device> make(const SimScenario& s) {
    SiyiSimOptions o;
    o.seed = s.seed;
    const json& x = s.options;
    if (const auto m = x.find("model"); m != x.end() && m->is_string()) {
        const auto model = siyi::model_from_key(m->get<std::string>());
        if (!model)
            throw std::invalid_argument("--model: must be one of a8mini, zr10, zr30, zt30, zt6");
        o.model = *model;
    }
    o.angle_noise_deg = x.value("angle_noise_deg", o.angle_noise_deg);
    o.boot_time_s = x.value("boot_time_s", o.boot_time_s);
    o.sd_card = !x.value("no_sd_card", false);
    if (s.lat_deg) o.lat_deg = *s.lat_deg;
    if (s.lon_deg) o.lon_deg = *s.lon_deg;
    if (s.alt_m) o.alt_msl_m = *s.alt_m;
    if (s.geoid_undulation_m) o.geoid_undulation_m = *s.geoid_undulation_m;
    if (s.alt_m && s.terrain_alt_m && *s.alt_m > *s.terrain_alt_m)
        o.height_above_ground_m = *s.alt_m - *s.terrain_alt_m;
    o.height_above_ground_m = x.value("height_above_ground_m", o.height_above_ground_m);
    return make_siyi_sim(o);
}

// STX, CTRL, Data_len: the length says the size.
std::size_t frame_size_at(std::span<const std::uint8_t> in) {
    if (in.size() < 5 || in[0] != siyi::stx0 || in[1] != siyi::stx1) return 0;
    const std::size_t length = in[3] | static_cast<std::size_t>(in[4]) << 8;
    return length > siyi::max_data_length ? 0 : siyi::frame_overhead + length;
}

sim::FrameShape fault_frames() {
    return sim::FrameShape{frame_size_at, siyi::stx0, siyi::stx1};
}

class SiyiRxDecoder final : public RxDecoder {
  public:
    void push(std::span<const std::uint8_t> bytes, std::vector<json>& lines) override {
        framer_.push(bytes, [&](const siyi::Frame& f) {
            const auto bytes_of = siyi::frame_bytes(f);
            json line = siyi::frame_to_json(f, siyi::Direction::to_gimbal);
            json out;
            out["kind"] = line.value("message", std::string("unknown"));
            out["cmd"] = f.cmd;
            out["ctrl"] = f.ctrl;
            out["seq"] = f.seq;
            out["len"] = bytes_of.size();
            out["hex"] = hex_text(bytes_of);
            out["message"] = std::move(line);
            lines.push_back(std::move(out));
        });
    }
    void reset() override { framer_.reset(); }

  private:
    siyi::Framer framer_;
};

}  // namespace

Simulator siyi_simulator() {
    Simulator s;
    s.manual = manual;
    s.rx_log_manual = rx_log_manual;
    s.make = make;
    s.flags = flags;
    s.defaults = defaults;
    s.fault_frames = fault_frames;
    s.make_rx_decoder = [] {
        return std::unique_ptr<RxDecoder>(std::make_unique<SiyiRxDecoder>());
    };
    s.camera = siyi_sim_camera;
    return s;
}

}  // namespace gimbal::protocols
