// The wire details of the ST 0903 VMTI local set shared by its encoder and decoder (the
// numbers are cited in vmti.hpp): item tags, the lengths each item may have, and the IMAPB
// maps of a target location. Internal to lib/klv.
#pragma once

#include <cstddef>
#include <cstdint>

#include "klv/imapb.hpp"

namespace gimbal::klv::vmti_wire {

// VMTI LS tags.
inline constexpr std::uint32_t checksum = 1;
inline constexpr std::uint32_t time_stamp = 2;
inline constexpr std::uint32_t version = 4;
inline constexpr std::uint32_t total_targets = 5;
inline constexpr std::uint32_t reported_targets = 6;
inline constexpr std::uint32_t frame_number = 7;
inline constexpr std::uint32_t frame_width = 8;
inline constexpr std::uint32_t frame_height = 9;
inline constexpr std::uint32_t vtarget_series = 101;

// VTarget pack tags.
inline constexpr std::uint32_t centroid = 1;
inline constexpr std::uint32_t top_left = 2;
inline constexpr std::uint32_t bottom_right = 3;
inline constexpr std::uint32_t confidence = 5;
inline constexpr std::uint32_t location = 17;
inline constexpr std::uint32_t centroid_row = 19;
inline constexpr std::uint32_t centroid_column = 20;

// Most bytes of each unsigned item (at least one byte each).
inline constexpr std::size_t time_stamp_bytes = 8;  // exactly 8
inline constexpr std::size_t version_bytes = 2;
inline constexpr std::size_t target_count_bytes = 3;
inline constexpr std::size_t frame_number_bytes = 4;
inline constexpr std::size_t frame_size_bytes = 3;
inline constexpr std::size_t pixel_number_bytes = 6;
inline constexpr std::size_t pixel_index_bytes = 4;  // tags 19, 20
inline constexpr std::size_t confidence_bytes = 1;

// Target location (VTarget tag 17): latitude, longitude, height; then optionally three
// standard deviations and three correlations of 2 bytes each.
inline constexpr std::size_t location_bytes = 10;
inline constexpr std::size_t location_with_sigmas_bytes = 16;
inline constexpr std::size_t location_with_rhos_bytes = 22;
inline constexpr Imapb location_lat{-90.0, 90.0, 4};
inline constexpr Imapb location_lon{-180.0, 180.0, 4};
inline constexpr Imapb location_hae{-900.0, 19000.0, 2};

inline constexpr std::uint64_t max_confidence_pct = 100;

}  // namespace gimbal::klv::vmti_wire
