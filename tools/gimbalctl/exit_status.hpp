// Exit statuses of gimbalctl; scripts branch on these, so they are part of the interface.
#pragma once

namespace gimbalctl {

inline constexpr int exit_ok = 0;           // reply with ok:true (or help, --print-request)
inline constexpr int exit_error_reply = 1;  // reply with ok:false
inline constexpr int exit_no_reply = 2;     // nothing matching arrived within --timeout
inline constexpr int exit_usage = 64;       // EX_USAGE: bad command line

}  // namespace gimbalctl
