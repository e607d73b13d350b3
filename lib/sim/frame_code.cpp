#include "sim/frame_code.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace gimbal::sim {

namespace {

constexpr int cells = frame_code_cells_per_row * frame_code_rows;
constexpr int data_first = 4;
constexpr int crc_first = 52;
constexpr int stop_first = 60;
constexpr std::array<bool, 4> start_mark{true, false, true, false};
constexpr std::array<bool, 4> stop_mark{false, true, false, true};
constexpr std::uint8_t white = 235;
constexpr std::uint8_t black = 16;
// Decoding: white must be this much brighter than black, and each cell this fraction of
// their difference away from the threshold.
constexpr double min_contrast = 60;
constexpr double min_margin = 0.25;

std::array<bool, cells> cell_bits(std::uint64_t value) {
    std::array<bool, cells> bits{};
    std::copy(start_mark.begin(), start_mark.end(), bits.begin());
    for (int i = 0; i < 48; ++i)
        bits[static_cast<std::size_t>(data_first + i)] = (value >> (47 - i)) & 1u;
    std::array<std::uint8_t, 6> bytes{};
    for (std::size_t i = 0; i < bytes.size(); ++i)
        bytes[i] = static_cast<std::uint8_t>(value >> (40 - 8 * i));
    const std::uint8_t crc = crc8_smbus(bytes);
    for (int i = 0; i < 8; ++i)
        bits[static_cast<std::size_t>(crc_first + i)] = (crc >> (7 - i)) & 1u;
    std::copy(stop_mark.begin(), stop_mark.end(), bits.begin() + stop_first);
    return bits;
}

}  // namespace

int frame_code_block_px(int width, int height) {
    const int fit = std::min({16, width / frame_code_cells_per_row, height / frame_code_rows});
    const int even = fit - fit % 2;
    return even >= 4 ? even : 0;
}

std::uint8_t crc8_smbus(std::span<const std::uint8_t> bytes) {
    std::uint8_t crc = 0;
    for (const std::uint8_t b : bytes) {
        crc ^= b;
        for (int i = 0; i < 8; ++i)
            crc = static_cast<std::uint8_t>((crc & 0x80) ? (crc << 1) ^ 0x07 : crc << 1);
    }
    return crc;
}

bool draw_frame_code(I420Frame& frame, std::uint64_t unix_ms) {
    const int b = frame_code_block_px(frame.width, frame.height);
    if (b == 0 || unix_ms > frame_code_max) return false;
    const auto bits = cell_bits(unix_ms);
    const int cw = frame.chroma_width();
    for (int k = 0; k < cells; ++k) {
        const int x0 = (k % frame_code_cells_per_row) * b, y0 = (k / frame_code_cells_per_row) * b;
        const std::uint8_t level = bits[static_cast<std::size_t>(k)] ? white : black;
        for (int y = y0; y < y0 + b; ++y)
            std::fill_n(frame.y.begin() + y * frame.width + x0, b, level);
        for (int y = y0 / 2; y < (y0 + b) / 2; ++y) {
            std::fill_n(frame.u.begin() + y * cw + x0 / 2, b / 2, std::uint8_t{128});
            std::fill_n(frame.v.begin() + y * cw + x0 / 2, b / 2, std::uint8_t{128});
        }
    }
    return true;
}

std::optional<std::uint64_t> decode_frame_code(std::span<const std::uint8_t> luma, int width,
                                               int height, std::size_t stride) {
    const int b = frame_code_block_px(width, height);
    if (b == 0 || stride < static_cast<std::size_t>(width) ||
        luma.size() < stride * static_cast<std::size_t>(frame_code_rows * b))
        return std::nullopt;
    std::array<double, cells> level{};
    for (int k = 0; k < cells; ++k) {
        const int x0 = (k % frame_code_cells_per_row) * b + b / 4;
        const int y0 = (k / frame_code_cells_per_row) * b + b / 4;
        double sum = 0;
        for (int y = y0; y < y0 + b / 2; ++y)
            for (int x = x0; x < x0 + b / 2; ++x)
                sum += luma[static_cast<std::size_t>(y) * stride + static_cast<std::size_t>(x)];
        level[static_cast<std::size_t>(k)] = sum / (b / 2 * b / 2);
    }
    double white_sum = 0, black_sum = 0;
    for (std::size_t i = 0; i < 4; ++i) {
        (start_mark[i] ? white_sum : black_sum) += level[i];
        (stop_mark[i] ? white_sum : black_sum) += level[stop_first + i];
    }
    const double hi = white_sum / 4, lo = black_sum / 4;
    if (hi - lo < min_contrast) return std::nullopt;
    const double threshold = (hi + lo) / 2, margin = min_margin * (hi - lo);
    std::array<bool, cells> bits{};
    for (std::size_t k = 0; k < cells; ++k) {
        if (std::abs(level[k] - threshold) < margin) return std::nullopt;
        bits[k] = level[k] > threshold;
    }
    std::uint64_t value = 0;
    for (int i = 0; i < 48; ++i)
        value = value << 1 | (bits[static_cast<std::size_t>(data_first + i)] ? 1u : 0u);
    if (cell_bits(value) != bits) return std::nullopt;  // marks and CRC as drawn
    return value;
}

std::optional<std::uint64_t> decode_frame_code(const I420Frame& frame) {
    return decode_frame_code(frame.y, frame.width, frame.height,
                             static_cast<std::size_t>(frame.width));
}

}  // namespace gimbal::sim
