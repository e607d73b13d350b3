// A Viewpro gimbal's own configuration keys (contract section 3): `feed`, the input frame
// that carries the vehicle feed, and `viewpro.output`, the mode command sent on every
// (re)connect. Declared once here; daemon/config.cpp reads and writes them through the
// registry (viewpro_entry.cpp), and the session and feeder read them back from the gimbal's
// configuration object.
#pragma once

#include <array>

#include "config/fields.hpp"
#include "protocols/viewpro/codec/mode.hpp"

namespace gimbal::protocols {

enum class ViewproFeed { in2, in1, mavlink };

struct ViewproConfig {
    ViewproFeed feed = ViewproFeed::in2;
    viewpro::Mode output;
    bool operator==(const ViewproConfig&) const = default;
};

inline constexpr std::array<config::Named<ViewproFeed>, 3> viewpro_feed_names{
    {{"in2", ViewproFeed::in2}, {"in1", ViewproFeed::in1}, {"mavlink", ViewproFeed::mavlink}}};
inline constexpr std::array<config::Named<viewpro::Osd>, 2> viewpro_osd_names{
    {{"target", viewpro::Osd::target}, {"uav", viewpro::Osd::uav}}};
inline constexpr std::array<config::Named<viewpro::OutFormat>, 4> viewpro_format_names{
    {{"out1", viewpro::OutFormat::out1},
     {"out2", viewpro::OutFormat::out2},
     {"out3", viewpro::OutFormat::out3},
     {"out4", viewpro::OutFormat::out4}}};

template <class V>
void fields(V& v, ViewproConfig& c) {
    v.choice("feed", c.feed, viewpro_feed_names);
    v.section("viewpro", [&](auto& viewpro) {
        viewpro.section("output", [&](auto& o) {
            o.choice("osd", c.output.osd, viewpro_osd_names);
            o.boolean("serial", c.output.serial);
            o.boolean("network", c.output.network);
            o.choice("format", c.output.format, viewpro_format_names);
        });
    });
}

}  // namespace gimbal::protocols
