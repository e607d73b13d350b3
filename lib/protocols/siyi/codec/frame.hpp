// The frame of SIYI's SDK protocol ("SIYI Gimbal Camera External SDK Protocol", chapter 1):
//
//   STX 55 66 | CTRL | Data_len (2, LE) | SEQ (2, LE) | CMD_ID | DATA (Data_len) | CRC16 (2, LE)
//
// CTRL bit 0 is need_ack (a request that wants its reply), bit 1 ack_pack (this frame is a
// reply); bits 2-7 are reserved. The CRC (crc16.hpp) covers STX through DATA.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace gimbal::siyi {

inline constexpr std::uint8_t stx0 = 0x55;  // "0x6655, low byte in the front"
inline constexpr std::uint8_t stx1 = 0x66;
inline constexpr std::size_t header_size = 8;  // STX, CTRL, Data_len, SEQ, CMD_ID
inline constexpr std::size_t crc_size = 2;
inline constexpr std::size_t frame_overhead = header_size + crc_size;
// Data_len is 16 bits, but the longest message of SDK v0.1.1 carries 38 bytes (0x23, RC
// channels). A longer length is taken for a false sync at once rather than waited for: the
// framer never holds more than one such frame before it re-scans.
inline constexpr std::size_t max_data_length = 128;
inline constexpr std::size_t max_frame_size = frame_overhead + max_data_length;

inline constexpr std::uint8_t ctrl_need_ack = 0x01;
inline constexpr std::uint8_t ctrl_ack_pack = 0x02;

// The DATA of one frame.
struct Payload {
    std::array<std::uint8_t, max_data_length> bytes{};
    std::size_t size = 0;
    std::span<const std::uint8_t> view() const { return {bytes.data(), size}; }
};

// One complete, CRC-valid frame.
struct Frame {
    std::uint8_t ctrl = 0;
    std::uint16_t seq = 0;
    std::uint8_t cmd = 0;
    Payload data;

    bool need_ack() const { return (ctrl & ctrl_need_ack) != 0; }
    bool is_ack() const { return (ctrl & ctrl_ack_pack) != 0; }
    std::size_t wire_size() const { return frame_overhead + data.size; }
};

// What a sender chooses per frame: requests go with need_ack (as every example of the SDK
// document does), replies with ack_pack; SEQ counts the sender's frames.
struct Header {
    std::uint8_t ctrl = ctrl_need_ack;
    std::uint16_t seq = 0;
};

// Appends one frame. `data` longer than max_data_length is cut to it (the codec never makes
// such a payload).
void append_frame(std::vector<std::uint8_t>& out, Header header, std::uint8_t cmd,
                  std::span<const std::uint8_t> data);
std::vector<std::uint8_t> frame_bytes(Header header, std::uint8_t cmd,
                                      std::span<const std::uint8_t> data);
std::vector<std::uint8_t> frame_bytes(const Frame& frame);

// nullopt unless `bytes` is exactly one valid frame.
std::optional<Frame> make_frame(std::span<const std::uint8_t> bytes);

}  // namespace gimbal::siyi
