// What gimbal-track does with gimbald's messages (docs/tracking.md "The process"): a start
// opens a track; access units are decoded only while one runs (the decoder opens with the
// first unit and closes with the track), each decoded frame is scaled to the track's width
// and given to the engine (lib/track), and every tracked frame is answered with a box; the
// track's state machine ends it (timeout) on the frames' own clock. No I/O here: messages
// go out through `send`.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "json_log.hpp"
#include "track/decode/video_decoder.hpp"
#include "track/ground/frame_clock.hpp"
#include "track/ground/track_state.hpp"
#include "track/object_tracker.hpp"
#include "track/wire/assembler.hpp"
#include "track/wire/messages.hpp"

namespace gimbal_track {

namespace wire = gimbal::track::wire;

struct SessionStats {
    std::uint64_t messages = 0;
    std::uint64_t refused = 0;     // datagrams that were not a valid message
    std::uint64_t units = 0;       // access units received (whole)
    std::uint64_t units_idle = 0;  // ... while no track ran (not decoded)
    std::uint64_t frames = 0;      // decoded
    std::uint64_t tracked = 0;     // given to the engine and answered
    std::uint64_t skipped = 0;     // decoded but not tracked: more input was waiting
    std::uint64_t decoder_errors = 0;
    std::uint64_t tracks = 0;
};

class TrackSession {
  public:
    using Send = std::function<void(const wire::Message&)>;

    TrackSession(Send send, const Log& log);
    ~TrackSession();

    static wire::Hello hello();

    // One datagram. `behind`: another one is already waiting, so a frame decoded now need
    // not be tracked (the next one will be, fresher) - it is still decoded.
    void datagram(std::span<const std::uint8_t> bytes, bool behind);
    // A datagram that could not even be read whole (larger than the limit).
    void refuse(const std::string& error);
    // The process is stopping (SIGTERM): ends a running track (reason stopped).
    void shutdown();

    bool tracking() const { return track_ != nullptr; }
    // A track runs and has not tracked its first frame yet.
    bool starting() const;
    const SessionStats& stats() const { return stats_; }

  private:
    struct Track;

    void start(const wire::Start& start);
    void stop(const wire::Stop& stop);
    void access_unit(const wire::AccessUnitAssembler::Unit& unit, bool behind);
    void frame(gimbal::track::DecodedFrame& frame);
    void end(wire::EndReason reason, std::string_view why);
    void report_decoder_error();

    Send send_;
    const Log& log_;
    wire::AccessUnitAssembler assembler_;
    std::unique_ptr<Track> track_;
    SessionStats stats_;
};

}  // namespace gimbal_track
