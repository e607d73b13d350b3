// A visual track (STATE `track`, contract section 20) as the MISB ST 0903 VMTI set gimbald
// sends in ST 0601 tag 74: one target with the track's id, its centre and box turned from
// section 16 image coordinates (-1..1, x right, y down) into pixels of the stream's
// width x height (pixel numbers from 1 at the top left, klv/vmti.hpp), its confidence in
// percent, and its ground position (WGS84, height above the ellipsoid) when it has one.
// Pure.
#pragma once

#include <optional>

#include "klv/vmti.hpp"
#include "state/track_state.hpp"

namespace gimbal::klv_state {

// The 1-based pixel row or column an image coordinate falls in, across `pixels`.
std::uint32_t pixel_index(double image_coordinate, int pixels);

// nullopt when the frame size is not known (or not positive): pixels need it.
std::optional<klv::VmtiSet> track_vmti(const state::TrackState& track, std::optional<int> width,
                                       std::optional<int> height);

}  // namespace gimbal::klv_state
