// A time code drawn into each rendered frame, so a viewer can tell when the simulator made
// the picture it is showing (glass-to-glass latency): the frame's time, Unix milliseconds in
// 48 bits, as black and white blocks in the top-left corner, large enough to survive H.264.
//
// Layout (docs/simulator.md "Time code"): 64 square cells of block_px pixels, 32 per row in
// two rows from the frame's top-left pixel, numbered left to right, top row first.
//   cells  0..3   start mark: white, black, white, black
//   cells  4..51  the time, most significant bit first (white = 1)
//   cells 52..59  CRC-8 of the time's 6 bytes, big-endian (polynomial 0x07, initial 0, no
//                 reflection, no final xor: CRC-8/SMBUS), most significant bit first
//   cells 60..63  stop mark: black, white, black, white
// White is Y 235, black Y 16, chroma neutral (128). block_px is 16 when the frame is at
// least 512 x 64 pixels, else the largest even size that fits (at least 4; smaller frames
// carry no code).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

#include "sim/i420_frame.hpp"

namespace gimbal::sim {

inline constexpr int frame_code_cells_per_row = 32;
inline constexpr int frame_code_rows = 2;
inline constexpr std::uint64_t frame_code_max = (std::uint64_t{1} << 48) - 1;

// Cell size for a frame of this size; 0 when the frame is too small for a code.
int frame_code_block_px(int width, int height);

std::uint8_t crc8_smbus(std::span<const std::uint8_t> bytes);

// Draws the code for `unix_ms` over the frame. False (and the frame unchanged) when the time
// does not fit 48 bits or the frame is too small.
bool draw_frame_code(I420Frame& frame, std::uint64_t unix_ms);

// Reads the code back from a luma plane (`stride` bytes per row): each cell's mean over its
// central half, thresholded halfway between the marks' white and black. nullopt when the
// marks do not read as drawn, white is not clearly brighter than black, a cell is ambiguous,
// or the CRC does not match.
std::optional<std::uint64_t> decode_frame_code(std::span<const std::uint8_t> luma, int width,
                                               int height, std::size_t stride);
std::optional<std::uint64_t> decode_frame_code(const I420Frame& frame);

}  // namespace gimbal::sim
