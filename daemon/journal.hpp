// Logs in the systemd journal (contract section 14). When standard output is the journal's
// stream, each record goes to journald natively instead (sd_journal_sendv): its level as the
// priority, so `journalctl -p warning` works, and its simple JSON keys as fields, so
// `journalctl EVENT=laser_fire` does; the line itself stays the message. Through the stream
// every line would arrive at one priority with no fields.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "logging.hpp"

namespace gimbal::log {

// True when `journal_stream` ($JOURNAL_STREAM, "DEVICE:INODE" in decimal, systemd.exec(5))
// names the file with that device and inode.
bool journal_stream_matches(std::string_view journal_stream, unsigned long long device,
                            unsigned long long inode);
// True when standard output is the journal's stream (JOURNAL_STREAM matches fstat(stdout)).
bool stdout_is_journal();

// The syslog priority of a level: error 3, warn 4, info 6, debug and trace 7.
int journal_priority(Level level);

// A journal field name for a JSON key: upper case, other characters than A-Z, 0-9 and '_'
// as '_'. Names the journal gives a meaning of its own (MESSAGE, PRIORITY, ...), or that it
// would refuse (a leading '_' or digit), get the prefix GIMBALD_; nothing over 64 characters.
std::string journal_field_name(std::string_view key);

// The KEY=value fields of one record: MESSAGE (`line`, the formatted record), PRIORITY,
// SYSLOG_IDENTIFIER=gimbald, TS, LEVEL, EVENT, MSG and every field whose value is a string,
// number or boolean (strings as they are, the rest as JSON text). Objects, arrays and nulls
// are in MESSAGE only.
std::vector<std::string> journal_fields(const Record& record, std::string_view line);

// Sends one entry over the journal's native socket; false when journald cannot be reached
// (its socket is missing or refuses): the caller writes the line to standard output instead.
bool send_to_journal(const std::vector<std::string>& fields);

}  // namespace gimbal::log
