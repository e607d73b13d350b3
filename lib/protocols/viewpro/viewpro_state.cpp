#include "protocols/viewpro/viewpro_state.hpp"

#include <algorithm>

#include "protocols/viewpro/codec/json.hpp"
#include "state/precision.hpp"

namespace gimbal::state {

bool ViewproState::apply(const viewpro::OutputFrame& frame, double now_s) {
    auto output = viewpro::decode_output(frame);
    if (!output) {
        ++decode_errors_;
        return false;
    }
    output_ = *output;
    received_s_ = now_s;
    ++telemetry_count_;
    lost_reported_ = false;
    return true;
}

bool ViewproState::stale(double now_s) const {
    return !output_ || now_s - received_s_ > stale_after_s_;
}

void ViewproState::tick(double now_s, std::vector<Event>& events) {
    if (output_ && !lost_reported_ && stale(now_s)) {
        lost_reported_ = true;
        events.push_back(Event{"lost", {{"age_s", seconds(now_s - received_s_)}}});
    }
}

void ViewproState::write(JsonWriter& w, double now_s) const {
    if (!output_) return w.null("output");
    nlohmann::json out = viewpro::to_json(*output_);
    out["age_s"] = seconds(std::max(0.0, now_s - received_s_));
    w.json("output", std::move(out));
}

nlohmann::json ViewproState::snapshot(double now_s) const {
    nlohmann::json out = nlohmann::json::object();
    JsonWriter w(out);
    write(w, now_s);
    return out;
}

}  // namespace gimbal::state
