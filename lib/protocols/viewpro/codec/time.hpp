// Date and time as the Viewpro frames carry it: whole seconds, UTC, no time zone. The
// calendar itself is protocol-neutral (calendar/utc.hpp); the codec names it as its own.
#pragma once

#include "calendar/utc.hpp"

namespace gimbal::viewpro {

using calendar::DateTime;
using calendar::from_unix_seconds;
using calendar::parse_iso8601;
using calendar::to_iso8601;
using calendar::to_unix_seconds;

}  // namespace gimbal::viewpro
