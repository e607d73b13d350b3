#include "auth/verifier.hpp"

#include <cmath>
#include <cstdio>

#include "command/request.hpp"
#include "command/request_limits.hpp"

namespace gimbal::auth {

Verifier::Verifier(std::vector<Key> keys, double max_skew_s, std::size_t nonces_per_key)
    : keys_(std::move(keys)), max_skew_ms_(std::llround(max_skew_s * 1000.0)) {
    for (const auto& k : keys_) nonces_.emplace(k.id, NonceWindow(nonces_per_key));
}

const Key* Verifier::find(const std::string& id) const {
    for (const auto& k : keys_)
        if (k.id == id) return &k;
    return nullptr;
}

Result<nlohmann::json> read_signed_payload(std::string_view payload) {
    // A key holder's request meets the same limits as anyone's, before it is parsed.
    if (auto refused = command::check_request_limits(payload))
        return Error{refused->code, "the signed payload: " + refused->message};
    auto parsed = command::parse_object(payload);
    if (!parsed) return Error{code::bad_json, "the signed payload is not a JSON object"};
    return std::move(*parsed);
}

Result<Verified> Verifier::verify(const SignedEnvelope& envelope, std::int64_t now_unix_ms) {
    auto key = authenticate(envelope);
    if (!key) return key.error();
    auto payload = read_signed_payload(envelope.payload);
    if (!payload) return payload.error();
    return accept(**key, std::move(payload).value(), now_unix_ms);
}

Result<const Key*> Verifier::authenticate(const SignedEnvelope& envelope) const {
    const Key* key = find(envelope.key);
    if (key == nullptr) return Error{code::forbidden, "unknown key '" + envelope.key + "'"};
    // Nothing of the payload is looked at before its MAC is known to be right.
    if (!mac_matches(envelope, key->secret))
        return Error{code::forbidden,
                     "bad MAC: the payload was not signed with key '" + key->id + "'"};
    return key;
}

Result<Verified> Verifier::accept(const Key& key, nlohmann::json payload,
                                  std::int64_t now_unix_ms) {
    auto forbid = [](std::string reason) { return Error{code::forbidden, std::move(reason)}; };
    if (!payload.is_object())
        return Error{code::bad_json, "the signed payload is not a JSON object"};
    Verified v;
    v.key = &key;
    v.request = std::move(payload);

    const auto ts = v.request.find("ts");
    if (ts == v.request.end() || !ts->is_number_integer())
        return forbid("the signed payload needs \"ts\": Unix time in milliseconds");
    const std::int64_t skew = ts->get<std::int64_t>() - now_unix_ms;
    if (skew > max_skew_ms_ || skew < -max_skew_ms_) {
        char text[128];
        std::snprintf(text, sizeof text,
                      "\"ts\" is %.1f s %s the daemon's clock (command.max_skew_s is %.0f)",
                      std::fabs(static_cast<double>(skew)) / 1000.0,
                      skew > 0 ? "ahead of" : "behind", static_cast<double>(max_skew_ms_) / 1000.0);
        return forbid(text);
    }
    const auto nonce = v.request.find("nonce");
    if (nonce == v.request.end() || !nonce->is_string() ||
        nonce->get_ref<const std::string&>().size() < min_nonce_chars ||
        nonce->get_ref<const std::string&>().size() > max_nonce_chars)
        return forbid("the signed payload needs \"nonce\": a string of 8..64 characters");
    v.nonce = nonce->get<std::string>();
    // Remembered until its ts leaves the window: a later replay fails the ts check instead.
    const std::int64_t forget_at = ts->get<std::int64_t>() + max_skew_ms_ + 1;
    switch (nonces_.at(key.id).remember(v.nonce, forget_at, now_unix_ms)) {
        case NonceWindow::Result::fresh:
            break;
        case NonceWindow::Result::replayed:
            return forbid("replayed: nonce already used with key '" + key.id +
                          "' within the time window");
        case NonceWindow::Result::full:
            return forbid("too many signed requests with key '" + key.id +
                          "' in the time window; retry later");
    }
    return v;
}

}  // namespace gimbal::auth
