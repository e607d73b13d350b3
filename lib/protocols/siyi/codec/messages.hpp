// Every SIYI message gimbald knows, by direction, for dispatch by CMD_ID: a CMD_ID names a
// request on the way to the gimbal and its reply (or a push of the same layout) on the way
// back, so decoding needs the direction.
#pragma once

#include <cstdint>
#include <span>
#include <string_view>
#include <variant>
#include <vector>

#include "protocols/siyi/codec/codec.hpp"
#include "protocols/siyi/codec/frame.hpp"
#include "protocols/siyi/codec/from_gimbal.hpp"
#include "protocols/siyi/codec/to_gimbal.hpp"

namespace gimbal::siyi {

enum class Direction : std::uint8_t { to_gimbal, from_gimbal };

using ToGimbalList =
    MessageList<TcpHeartbeat, FirmwareVersionRequest, HardwareIdRequest, AutoFocus, ManualZoom,
                ManualFocus, GimbalRotation, Center, CameraSystemInfoRequest, Capture,
                GimbalAttitudeRequest, SetGimbalAttitude, AbsoluteZoom, LaserDistanceRequest,
                ZoomRangeRequest, LaserTargetRequest, CurrentZoomRequest, GimbalModeRequest,
                AircraftAttitude, DataStreamRequest, SetUtcTime, RawGps>;

using FromGimbalList =
    MessageList<FirmwareVersion, HardwareId, AutoFocusReply, ManualZoomReply, ManualFocusReply,
                GimbalRotationReply, CenterReply, CameraSystemInfo, FunctionFeedback,
                GimbalAttitude, SetGimbalAttitudeReply, AbsoluteZoomReply, LaserDistance, ZoomRange,
                LaserTarget, CurrentZoom, GimbalMode, DataStreamReply, MagneticEncoder,
                SetUtcTimeReply>;

template <class L>
struct VariantOf;
template <class... M>
struct VariantOf<MessageList<M...>> {
    using type = std::variant<M...>;
};

using ToGimbal = VariantOf<ToGimbalList>::type;
using FromGimbal = VariantOf<FromGimbalList>::type;

// Calls f(static_cast<M*>(nullptr)) for every message M of the list.
template <class... M, class F>
void for_each_message(MessageList<M...>, F&& f) {
    (f(static_cast<M*>(nullptr)), ...);
}

Decoded<ToGimbal> decode_to_gimbal(std::uint8_t cmd, std::span<const std::uint8_t> data);
Decoded<FromGimbal> decode_from_gimbal(std::uint8_t cmd, std::span<const std::uint8_t> data);
inline Decoded<ToGimbal> decode_to_gimbal(const Frame& f) {
    return decode_to_gimbal(f.cmd, f.data.view());
}
inline Decoded<FromGimbal> decode_from_gimbal(const Frame& f) {
    return decode_from_gimbal(f.cmd, f.data.view());
}

std::vector<std::uint8_t> encode(const ToGimbal& m, Header header);
std::vector<std::uint8_t> encode(const FromGimbal& m, Header header);
void append(std::vector<std::uint8_t>& out, const ToGimbal& m, Header header);
void append(std::vector<std::uint8_t>& out, const FromGimbal& m, Header header);

std::uint8_t command_of(const ToGimbal& m);
std::uint8_t command_of(const FromGimbal& m);
std::string_view name_of(const ToGimbal& m);
std::string_view name_of(const FromGimbal& m);
// The message name of a CMD_ID in a direction, or "" for one we do not know.
std::string_view message_name(Direction direction, std::uint8_t cmd);

}  // namespace gimbal::siyi
