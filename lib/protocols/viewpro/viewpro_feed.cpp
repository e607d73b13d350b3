#include "protocols/viewpro/viewpro_feed.hpp"

#include "protocols/viewpro/viewpro_feed_packets.hpp"
#include "vehicle/feeds.hpp"

namespace gimbal::protocols {

namespace {

constexpr std::uint64_t frame_ticks = ticks_per(0.1);  // 10 Hz

}  // namespace

std::string_view ViewproFeeder::kind() const {
    switch (frames_) {
        case ViewproFeed::in2:
            return "in2";
        case ViewproFeed::in1:
            return "in1";
        case ViewproFeed::mavlink:
            return "mavlink";
    }
    return "in2";
}

void ViewproFeeder::tick(const vehicle::VehicleState& v, const FeedTime& t,
                         std::vector<FeedBytes>& out) {
    if (t.tick % frame_ticks != 0) return;
    if (frames_ == ViewproFeed::mavlink) {
        auto bytes = vehicle::mavlink_forward(v, t.now_s, mavlink_seq_);
        if (!bytes.empty()) out.push_back(std::move(bytes));
        return;
    }
    const auto frame =
        frames_ == ViewproFeed::in1 ? vehicle::ViewproFrame::in1 : vehicle::ViewproFrame::in2;
    if (auto bytes = vehicle::viewpro_in(v, t.now_s, t.unix_s, frame))
        out.push_back(std::move(*bytes));
}

std::unique_ptr<VehicleFeeder> make_viewpro_feeder(const nlohmann::json& gimbal) {
    return std::make_unique<ViewproFeeder>(config::read_checked<ViewproConfig>(gimbal).feed);
}

}  // namespace gimbal::protocols
