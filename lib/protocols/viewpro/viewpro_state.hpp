// The live state of one Viewpro gimbal: its latest OUTx frame (contract section 5, `output`).
// Pure: every call takes now_s (monotonic seconds).
#pragma once

#include <algorithm>
#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

#include "protocols/viewpro/codec/output.hpp"
#include "state/event.hpp"
#include "state/writer.hpp"

namespace gimbal::state {

class ViewproState {
  public:
    explicit ViewproState(double stale_after_s = 1.0) : stale_after_s_(stale_after_s) {}

    // Applies one checksum-valid frame; false (and nothing changed) if it does not decode.
    bool apply(const viewpro::OutputFrame& frame, double now_s);
    // Appends a `lost` event when output goes stale (once per loss).
    void tick(double now_s, std::vector<Event>& events);
    bool stale(double now_s) const;
    // Seconds since the latest OUTx frame; nullopt before the first.
    std::optional<double> telemetry_age_s(double now_s) const {
        if (!output_) return std::nullopt;
        return std::max(0.0, now_s - received_s_);
    }
    // OUTx frames applied so far (streams that follow new telemetry).
    std::uint64_t telemetry_count() const { return telemetry_count_; }
    // STATE `output`: the latest OUTx as the codec writes it, with "format" and "age_s"; null
    // before the first.
    void write(JsonWriter& w, double now_s) const;
    nlohmann::json snapshot(double now_s) const;  // write() as a JSON object
    // The latest OUTx frame, decoded (contract units); nullopt before the first.
    const std::optional<viewpro::Output>& output() const { return output_; }
    std::uint64_t decode_errors() const { return decode_errors_; }

  private:
    double stale_after_s_;
    std::optional<viewpro::Output> output_;
    double received_s_ = 0;
    std::uint64_t telemetry_count_ = 0;
    bool lost_reported_ = false;
    std::uint64_t decode_errors_ = 0;
};

}  // namespace gimbal::state
