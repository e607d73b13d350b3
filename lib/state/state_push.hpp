// The STATE pushes of a stream (UDP subscription, WebSocket, MQTT), plain or as a delta
// stream (contract section 14, `subscribe.changes`). A DeltaCursor is what one subscriber
// last got of one gimbal; a PushBatch builds one tick's messages of one gimbal and shares
// them among subscribers: one key selection per key list, one full message per key list and
// one patch per (key list, previous push) - subscribers that got the same previous push share
// the same patch. Time is passed in.
//
// On the UDP socket a patch is kept to one payload where it can be (split(): the 1 Hz
// reports landing with the telemetry would make one of about 1,600 bytes): it goes as
// several patches back to back, each of whole top-level members.
#pragma once

#include <cstddef>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

namespace gimbal::state {

// One UDP payload over Ethernet (MTU 1500 - IPv4 20 - UDP 8): what a UDP delta-stream patch
// is kept to when its members allow (docs/json-api.md, "Delta streams").
inline constexpr std::size_t patch_budget_bytes = 1472;

// How a subscriber wants STATE: `keys` (empty: all) and, with `changes`, merge patches with a
// full STATE every `full_every_s`.
struct StreamOptions {
    std::vector<std::string> keys;
    bool changes = false;
    double full_every_s = 10.0;
};

// What one subscriber last received of one gimbal's STATE.
class DeltaCursor {
  public:
    // True when the next push must be a full STATE: nothing pushed yet (or restart()), or
    // full_every_s passed since the last full one.
    bool full_due(double now_s) const { return !last_ || now_s >= next_full_s_; }
    const std::shared_ptr<const nlohmann::json>& last() const { return last_; }
    void pushed(std::shared_ptr<const nlohmann::json> state, bool full, double now_s,
                double full_every_s);
    // The next push is full (a dropped message broke the chain of patches).
    void restart() { last_.reset(); }

  private:
    std::shared_ptr<const nlohmann::json> last_;
    double next_full_s_ = 0;
};

// One message of a tick: {"type":"state","gimbal":NAME,"state":BODY}, with "full" on a
// delta stream. Its text and its JSON are made on first use, from a body that may be shared
// with other messages (the whole STATE is never copied for a plain subscriber).
class PushMessage {
  public:
    PushMessage(const std::string& gimbal, std::optional<bool> full,
                std::shared_ptr<const nlohmann::json> body)
        : gimbal_(gimbal), full_(full), body_(std::move(body)) {}
    // The message as JSON (a signed subscriber signs it).
    const nlohmann::json& json() const;
    // Its text, as nlohmann::json would print the message (keys sorted, compact).
    const std::shared_ptr<const std::string>& text() const;
    // Delta stream: true for a full STATE, false for a patch; nullopt on a plain stream.
    std::optional<bool> full() const { return full_; }
    // What the message carries under "state".
    const std::shared_ptr<const nlohmann::json>& body() const { return body_; }

  private:
    std::string gimbal_;
    std::optional<bool> full_;
    std::shared_ptr<const nlohmann::json> body_;
    mutable std::optional<nlohmann::json> json_;
    mutable std::shared_ptr<const std::string> text_;
};

class PushBatch {
  public:
    PushBatch(std::string gimbal, nlohmann::json state);

    // The message for one subscriber, and with `changes` its cursor moved on. `now_s` decides
    // whether a full STATE is due.
    const PushMessage& next(const StreamOptions& options, DeltaCursor& cursor, double now_s);
    // The STATE restricted to `keys`, shared by every caller of this batch.
    const std::shared_ptr<const nlohmann::json>& selected(const std::vector<std::string>& keys);
    // `message` (one that next() returned) as it goes where a datagram should not exceed
    // `budget` bytes: a patch over it as several patches to send back to back, each of whole
    // top-level members and within the budget where a member allows (split_patch); merged
    // in order they are the one patch. Anything else, or a patch that fits: itself alone.
    // Shared by every subscriber of the message.
    const std::vector<PushMessage>& split(const PushMessage& message, std::size_t budget);

  private:
    enum class Kind { plain, full, patch };
    using Key = std::tuple<std::vector<std::string>, Kind, const nlohmann::json*>;

    std::string gimbal_;
    std::shared_ptr<const nlohmann::json> state_;
    std::map<std::vector<std::string>, std::shared_ptr<const nlohmann::json>> selected_;
    std::map<Key, PushMessage> messages_;
    std::map<const PushMessage*, std::vector<PushMessage>> parts_;
    // Previous pushes a patch was made against stay alive for the batch, so their addresses
    // (part of the key) cannot be reused by a new object.
    std::vector<std::shared_ptr<const nlohmann::json>> pinned_;
};

// {"type":"state","gimbal":NAME,"full":BOOL,"state":STATE-or-PATCH}
nlohmann::json delta_message(const std::string& gimbal, bool full, nlohmann::json state);

// JSON text as every stream sends it (invalid UTF-8 replaced, never thrown).
std::string dump_message(const nlohmann::json& message);

}  // namespace gimbal::state
