// Everything of the Viewpro target-GPS protocol codec: include this one header.
//   mode.hpp          mode and shift commands (AA 55 .. .. FF)
//   time.hpp          DateTime and its ISO-8601 form
//   input.hpp         IN1/IN2/IN3 (controller -> gimbal)
//   output.hpp        OUT1..OUT4 (gimbal -> controller)
//   output_framer.hpp / input_framer.hpp   streaming framers with re-scan
//   json.hpp          JSON in the units of the interface contract
#pragma once

#include "viewpro/checksum.hpp"
#include "viewpro/input.hpp"
#include "viewpro/input_framer.hpp"
#include "viewpro/json.hpp"
#include "viewpro/mode.hpp"
#include "viewpro/output.hpp"
#include "viewpro/output_framer.hpp"
#include "viewpro/time.hpp"
