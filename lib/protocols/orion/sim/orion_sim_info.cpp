#include "protocols/orion/sim/orion_sim_info.hpp"

namespace gimbal::sim::info {

namespace {

template <class P>
P version_packet(const char* version, const char* part_number, std::uint32_t on_time_min) {
    P p;
    p.version = version;
    p.part_number = part_number;
    p.on_time_min = on_time_min;
    return p;
}

}  // namespace

orion::ClevisVersion clevis_version() {
    return version_packet<orion::ClevisVersion>("1.4.7-sim", "SIM-CLEVIS-A", 5210);
}
orion::CrownVersion crown_version() {
    return version_packet<orion::CrownVersion>("1.4.7-sim", "SIM-CROWN-B", 5210);
}
orion::PayloadVersion payload_version() {
    return version_packet<orion::PayloadVersion>("1.4.7-sim payload", "SIM-PAYLOAD-C", 5208);
}
orion::TrackerVersion tracker_version() {
    return version_packet<orion::TrackerVersion>("3.2.0-sim", "SIM-TRACKER", 0);
}
orion::RetractVersion retract_version() {
    return version_packet<orion::RetractVersion>("2.0.1-sim", "", 0);
}
orion::LensCtlVersion lensctl_version() {
    return version_packet<orion::LensCtlVersion>("1.1.0-sim", "", 0);
}

std::vector<orion::BoardInfo> boards() {
    std::vector<orion::BoardInfo> list;
    const orion::Board which[] = {orion::Board::clevis, orion::Board::crown, orion::Board::payload};
    std::uint32_t serial = 20001;
    for (auto board : which) {
        orion::BoardInfo b;
        b.board_sn = serial++;
        b.assembly_sn = 7001;
        b.board = board;
        b.manufacture_year = 24;
        b.manufacture_month = 3;
        b.manufacture_day = 14;
        b.calibration_year = 24;
        b.calibration_month = 4;
        b.calibration_day = 2;
        list.push_back(b);
    }
    return list;
}

orion::Cameras cameras() {
    orion::CameraSettings visible;
    visible.type = orion::CameraType::visible;
    visible.protocol = orion::CameraProtocol::sony;
    visible.min_focal_length_mm = 4.3;
    visible.max_focal_length_mm = 129.0;
    visible.pixel_pitch_mm = 0.0029;
    visible.array_width = 1920;
    visible.array_height = 1080;

    orion::CameraSettings infrared;
    infrared.type = orion::CameraType::lwir;
    infrared.protocol = orion::CameraProtocol::flir;
    infrared.min_focal_length_mm = 25.0;
    infrared.max_focal_length_mm = 25.0;
    infrared.pixel_pitch_mm = 0.017;
    infrared.array_width = 640;
    infrared.array_height = 512;

    orion::Cameras c;
    c.cameras = {visible, infrared};
    return c;
}

orion::Limits limits(const AxisLimits& axes) {
    orion::Limits l;
    l.min_pos = {-pi, axes.tilt_min};
    l.max_pos = {pi, axes.tilt_max};
    l.max_vel = {axes.pan_rate_max, axes.tilt_rate_max};
    l.max_accel = {20, 20};
    l.cont_cur = {1.5, 1.5};
    l.peak_cur = {3.0, 3.0};
    l.peak_cur_time_s = {2.0, 2.0};
    l.init_cur = {0.5, 0.5};
    l.max_power = {0, 0};
    return l;
}

AxisLimits axis_limits(const orion::Limits& l) {
    AxisLimits axes;
    axes.pan_rate_max = l.max_vel[0];
    axes.tilt_rate_max = l.max_vel[1];
    axes.tilt_min = l.min_pos[1];
    axes.tilt_max = l.max_pos[1];
    return axes;
}

orion::NetworkSettings network_settings() {
    orion::NetworkSettings n;
    n.ip = 0xC0A80114;       // 192.168.1.20
    n.mask = 0xFFFFFF00;     // 255.255.255.0
    n.gateway = 0xC0A80101;  // 192.168.1.1
    n.low_delay = true;
    n.mtu = 1500;
    return n;
}

orion::NetworkVideo network_video() {
    orion::NetworkVideo v;
    v.dest_ip = 0xEF010101;  // 239.1.1.1
    v.port = 15004;
    v.bitrate = 4000000;
    v.ttl = 1;
    v.stream_type = orion::StreamType::h264;
    v.mjpeg_quality = 30;
    v.ts_packet_count = 7;
    return v;
}

orion::InsOptions ins_options() {
    orion::InsOptions o;
    o.enable_course_is_heading = true;
    return o;
}

orion::UartConfig uart_config(orion::UserDataPort port) {
    orion::UartConfig u;
    u.port = port;
    switch (port) {
        case orion::UserDataPort::ethernet:
        case orion::UserDataPort::current:
        case orion::UserDataPort::primary:
            u.port = port == orion::UserDataPort::current ? orion::UserDataPort::ethernet : port;
            u.baud = 115200;
            u.protocol = orion::UartProtocol::orion;
            break;
        default:
            u.baud = 0;
            u.protocol = orion::UartProtocol::none;
            break;
    }
    return u;
}

}  // namespace gimbal::sim::info
