#include "record/track_records.hpp"

#include <algorithm>
#include <nlohmann/json.hpp>

#include "state/messages.hpp"
#include "state/reader.hpp"
#include "state/writer.hpp"

namespace gimbal::record {

namespace {

constexpr std::string_view track_events[] = {"track_start", "track_lost", "track_reacquired",
                                             "track_end"};

// What every record has, and STATE's part of a state record.
struct StateTrack {
    std::optional<state::TrackState> track;
};

template <class V, state::part_of<StateTrack> S>
void fields(V& v, S& s) {
    v.object("track", s.track);
}

struct Envelope {
    std::string type;  // "event" or "state"
    std::string gimbal;
    std::optional<StateTrack> state;
};

template <class V, state::part_of<Envelope> E>
void fields(V& v, E& e) {
    v.string("type", e.type);
    v.string("gimbal", e.gimbal);
    v.object("state", e.state);
}

}  // namespace

bool is_track_event(std::string_view kind) {
    return std::find(std::begin(track_events), std::end(track_events), kind) !=
           std::end(track_events);
}

std::string track_state_record(const std::string& gimbal, const state::TrackState& track) {
    return state::state_message(gimbal, {{"track", state::write(track)}}).dump();
}

std::string track_event_record(const std::string& gimbal, const state::Event& event) {
    return state::event_message(gimbal, event).dump();
}

std::optional<TrackRecord> read_track_record(std::span<const std::uint8_t> pdu,
                                             std::int64_t time_us) {
    const auto message = nlohmann::json::parse(pdu.begin(), pdu.end(), nullptr, false);
    const auto envelope = state::read<Envelope>(message);
    if (!envelope) return std::nullopt;
    TrackRecord record{time_us, envelope->gimbal, TrackEvent{}};
    if (envelope->type == "event") {
        auto event = state::read<TrackEvent>(message);
        if (!event || !is_track_event(event->event) || event->id == 0) return std::nullopt;
        record.what = std::move(*event);
        return record;
    }
    if (envelope->type == "state" && envelope->state && envelope->state->track &&
        envelope->state->track->id != 0) {
        record.what = std::move(*envelope->state->track);
        return record;
    }
    return std::nullopt;
}

}  // namespace gimbal::record
