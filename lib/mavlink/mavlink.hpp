// The MAVLink codec gimbald uses to read the aircraft's state: CRC, messages, v1/v2 frames and
// the streaming framer. Pure: no I/O, no clocks.
#pragma once

#include "mavlink/crc.hpp"              // IWYU pragma: export
#include "mavlink/framer.hpp"           // IWYU pragma: export
#include "mavlink/framing.hpp"          // IWYU pragma: export
#include "mavlink/gimbal_messages.hpp"  // IWYU pragma: export
#include "mavlink/messages.hpp"         // IWYU pragma: export
#include "mavlink/payload.hpp"          // IWYU pragma: export
#include "mavlink/signing.hpp"          // IWYU pragma: export
