// command.token (contract sections 4 and 14): the shared secret of auth "none", compared in
// constant time so the reply's timing does not tell how much of a guess was right.
#pragma once

#include <string_view>

namespace gimbal::auth {

// True when `given` equals `expected`. Both are hashed first (SHA-256, OpenSSL) and the
// digests compared with CRYPTO_memcmp: the time depends on neither where they differ nor
// whether their lengths do.
bool token_matches(std::string_view given, std::string_view expected);

}  // namespace gimbal::auth
