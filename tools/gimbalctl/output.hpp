// Everything gimbalctl writes for people and scripts: JSON lines on stdout, diagnostics on
// stderr prefixed "gimbalctl: ".
#pragma once

#include <string>

#include "json_types.hpp"

namespace gimbalctl {

// One line, or indented with --pretty. Invalid UTF-8 is replaced rather than thrown on.
std::string format_json(const Json& value, bool pretty);

// Writes `value` and a newline to stdout and flushes, so pipes see each line at once.
void print_json(const Json& value, bool pretty);

// "gimbalctl: <what>" on stderr.
void print_diagnostic(const std::string& what);

// Prints a reply to stdout; an error reply also as "gimbalctl: CODE: MESSAGE" on stderr.
// Returns the exit status: exit_ok for ok:true, exit_error_reply otherwise.
int report_reply(const Json& reply, bool pretty);

// "2 s", "0.3 s": a duration for messages, without trailing zeros.
std::string format_seconds(double seconds);

// "CODE: MESSAGE" of an error reply, tolerating a malformed "error" member.
std::string error_summary(const Json& reply);

}  // namespace gimbalctl
