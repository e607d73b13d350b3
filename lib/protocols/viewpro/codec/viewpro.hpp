// Everything of the Viewpro target-GPS protocol codec: include this one header.
//   mode.hpp          mode and shift commands (AA 55 .. .. FF)
//   time.hpp          DateTime and its ISO-8601 form
//   input.hpp         IN1/IN2/IN3 (controller -> gimbal)
//   output.hpp        OUT1..OUT4 (gimbal -> controller)
//   output_framer.hpp / input_framer.hpp   streaming framers with re-scan
//   json.hpp          JSON in the units of the interface contract
#pragma once

#include "protocols/viewpro/codec/checksum.hpp"
#include "protocols/viewpro/codec/input.hpp"
#include "protocols/viewpro/codec/input_framer.hpp"
#include "protocols/viewpro/codec/json.hpp"
#include "protocols/viewpro/codec/mode.hpp"
#include "protocols/viewpro/codec/output.hpp"
#include "protocols/viewpro/codec/output_framer.hpp"
#include "protocols/viewpro/codec/time.hpp"
