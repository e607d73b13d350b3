// The visual track in a recording (contract section 20, docs/recording-format.md): interface
// `track:<gimbal>`, one outbound `gimbald-json` PDU per record, each one JSON object exactly
// as a subscriber receives it - a track event, or STATE `track` after each box gimbald
// handled:
//
//     {"type":"event","gimbal":"main","event":"track_lost","id":3}
//     {"type":"state","gimbal":"main","state":{"track":{"id":3,"state":"lost",...}}}
//
// The record's time is its packet's (EPB) time: when gimbald handled it. Written by the
// daemon's recorder, read back by gimbal-export. Pure.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <variant>

#include "state/event.hpp"
#include "state/part.hpp"
#include "state/track_state.hpp"

namespace gimbal::record {

inline constexpr std::string_view track_prefix = "track:";
inline constexpr std::string_view track_dissector = "gimbald-json";

// True for the events a track records: track_start, track_lost, track_reacquired, track_end.
bool is_track_event(std::string_view kind);

// {"type":"state","gimbal":NAME,"state":{"track":TRACK}}
std::string track_state_record(const std::string& gimbal, const state::TrackState& track);
// {"type":"event","gimbal":NAME,"event":KIND, ...the event's fields}
std::string track_event_record(const std::string& gimbal, const state::Event& event);

// An event record read back, with the fields the track events carry (docs/tracking.md).
struct TrackEvent {
    std::string event;  // track_start, track_lost, track_reacquired, track_end
    std::uint32_t id = 0;
    std::optional<state::TrackImageBox> box;  // track_start
    std::optional<bool> steer;                // track_start
    std::optional<std::string> reason;        // track_end: stopped, overridden, timeout, no_video
    std::optional<std::uint64_t> frames;      // track_end
    std::optional<std::uint64_t> lost_frames;
};

template <class V, state::part_of<TrackEvent> E>
void fields(V& v, E& e) {
    v.string("event", e.event);
    v.integer("id", e.id);
    v.object("box", e.box);
    v.boolean("steer", e.steer);
    v.string("reason", e.reason);
    v.integer("frames", e.frames);
    v.integer("lost_frames", e.lost_frames);
}

struct TrackRecord {
    std::int64_t time_us = 0;  // when gimbald handled it, microseconds since the Unix epoch
    std::string gimbal;
    std::variant<TrackEvent, state::TrackState> what;
};

// One PDU read back. nullopt when it is no track record: not a JSON object, another message
// type or event, a track id of 0, or a member of the wrong type. Keys it does not know are
// ignored (a newer gimbald's).
std::optional<TrackRecord> read_track_record(std::span<const std::uint8_t> pdu,
                                             std::int64_t time_us);

}  // namespace gimbal::record
