// A typed STATE part's fields() visits it for the JsonWriter (a const part) and, for a part
// gimbald reads back from its own JSON (reader.hpp), for the JsonReader (a part to fill). One
// declaration serves both:
//
//     template <class V, part_of<TrackGround> G>
//     void fields(V& v, G& g) { v.latlon("lat", g.lat); ... }
#pragma once

#include <concepts>
#include <type_traits>

namespace gimbal::state {

// `T` is `Part`, const or not.
template <class T, class Part>
concept part_of = std::same_as<std::remove_const_t<T>, Part>;

}  // namespace gimbal::state
