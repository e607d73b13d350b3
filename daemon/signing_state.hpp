// The MAVLink signing state that must survive a restart (contract section 14, issue 17 item
// 12): the last timestamp accepted on every signing stream, and our own last timestamp. Kept
// as a small JSON file, by default in systemd's state directory ($STATE_DIRECTORY, the
// service's StateDirectory=), written atomically (temporary file, then rename).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "mavlink/signing.hpp"

namespace gimbald {

struct SigningState {
    std::vector<gimbal::mavlink::SigningStreams::Stream> streams;
    std::uint64_t local_timestamp = 0;  // the latest timestamp we sent or accepted
};

// `configured` (mavlink.signing_state_file), else mavlink-signing.json in the first directory
// of `state_directory` ($STATE_DIRECTORY: colon-separated), else nothing.
std::optional<std::string> signing_state_path(const std::optional<std::string>& configured,
                                              const char* state_directory);

// A missing file is an empty state (the first start). Throws std::runtime_error naming the
// path for a file that cannot be read or does not hold a signing state.
SigningState load_signing_state(const std::string& path);
// Returns "" or the reason it could not be written.
std::string save_signing_state(const std::string& path, const SigningState& state);

}  // namespace gimbald
