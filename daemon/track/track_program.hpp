// Where gimbal-track is: the GIMBAL_TRACK environment variable when set (tests, a custom
// build), else beside gimbald's own executable - the same folder (a build's or a plain
// install's), ../bin (the package: /usr/sbin/gimbald, /usr/bin/gimbal-track) or ../tools
// (the build tree: daemon/gimbald, tools/gimbal-track).
#pragma once

#include <string>

namespace gimbald::track {

// The first candidate that is an executable file; else the first candidate, so that the
// failure to start it names a path.
std::string find_track_program();

}  // namespace gimbald::track
