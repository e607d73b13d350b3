#include "signing.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <fstream>
#include <sstream>

#include "auth/hmac.hpp"
#include "auth/secret.hpp"
#include "auth/signed_envelope.hpp"
#include "cli.hpp"
#include "exit_status.hpp"
#include "output.hpp"

namespace gimbalctl {

std::optional<SigningKey> load_signing_key(const std::string& file, const std::string& id,
                                           std::string& problem) {
    std::ifstream in(file);
    if (!in) {
        problem = "--key-file " + file + ": " + std::strerror(errno);
        return std::nullopt;
    }
    std::stringstream text;
    text << in.rdbuf();
    auto secret = gimbal::auth::parse_secret(text.str());
    if (auto* message = std::get_if<std::string>(&secret)) {
        problem = "--key-file " + file + ": " + *message;
        return std::nullopt;
    }
    return SigningKey{id, std::move(std::get<std::vector<std::uint8_t>>(secret))};
}

std::optional<SigningKey> signing_key_for(const GlobalOptions& globals, int& status) {
    if (!globals.key_file) return std::nullopt;
    std::string problem;
    auto key = load_signing_key(*globals.key_file, globals.key_id.value_or(""), problem);
    if (!key) {
        print_diagnostic(problem);
        status = exit_usage;
    }
    return key;
}

std::string Sealer::seal(const Json& request) {
    if (!key_) return format_json(request, false);
    Json payload = request;
    payload["ts"] = std::chrono::duration_cast<std::chrono::milliseconds>(
                        std::chrono::system_clock::now().time_since_epoch())
                        .count();
    nonce_ = gimbal::auth::to_hex(gimbal::auth::random_bytes(12));
    payload["nonce"] = nonce_;
    return gimbal::auth::sign(key_->id, key_->secret, format_json(payload, false));
}

Sealer::Opened Sealer::open(Json& datagram) const {
    const auto envelope = gimbal::auth::parse_signed(datagram);
    if (envelope && !*envelope) return Opened::plain;
    const gimbal::auth::SignedEnvelope* signed_envelope = envelope ? &**envelope : nullptr;
    if (!key_ || signed_envelope == nullptr || signed_envelope->key != key_->id ||
        !gimbal::auth::mac_matches(*signed_envelope, key_->secret))
        return Opened::forged;
    Json payload = Json::parse(signed_envelope->payload, nullptr, false);
    if (payload.is_discarded() || !payload.is_object()) return Opened::forged;
    datagram = std::move(payload);
    return Opened::authentic;
}

int run_keygen(const std::string& file) {
    const int fd = ::open(file.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
    if (fd < 0) {
        print_diagnostic("keygen " + file + ": " + std::strerror(errno) +
                         (errno == EEXIST ? " (refusing to overwrite a key)" : ""));
        return exit_error_reply;
    }
    const std::string text = gimbal::auth::new_secret_text();
    const bool written = ::write(fd, text.data(), text.size()) == static_cast<ssize_t>(text.size());
    const bool closed = ::close(fd) == 0;
    if (!written || !closed) {
        print_diagnostic("keygen " + file + ": cannot write the key");
        ::unlink(file.c_str());
        return exit_error_reply;
    }
    return exit_ok;
}

}  // namespace gimbalctl
