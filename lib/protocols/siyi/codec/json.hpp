// Messages and frames as JSON: field names from the declarations, angles in degrees, enums
// by name (the number for a value the SDK does not list), versions as "major.minor.patch",
// hardware ids as printable text. For logs, the rx log and the fuzzers.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <type_traits>

#include "protocols/siyi/codec/fields.hpp"
#include "protocols/siyi/codec/messages.hpp"

namespace gimbal::siyi {

// "3.2.3" for the version word 0x6E030203 (the high byte is ignored).
std::string version_string(std::uint32_t word);
// Printable ASCII as it is, any other byte as \xHH.
std::string printable(std::string_view bytes);

class JsonWriter {
  public:
    explicit JsonWriter(nlohmann::json& out) : out_(out) {}

    template <class T, class Raw>
    void field(std::string_view key, const T& member, Enc<Raw>, double = 1.0,
               Unit unit = Unit::none) {
        auto& slot = out_[std::string(key)];
        if constexpr (std::is_enum_v<T>) {
            const std::string_view name = enum_name(member);
            if (!name.empty())
                slot = name;
            else
                slot = static_cast<long long>(member);
        } else if constexpr (std::is_same_v<T, bool>) {
            slot = member;
        } else if constexpr (std::is_floating_point_v<T>) {
            const double v = static_cast<double>(member);
            slot = unit == Unit::radians ? v * rad2deg : v;
        } else if constexpr (std::is_unsigned_v<T>) {
            slot = static_cast<unsigned long long>(member);  // a u64 above 2^63 stays positive
        } else {
            slot = static_cast<long long>(member);
        }
    }
    template <class Raw>
    void reserved(Enc<Raw>) {}
    void text(std::string_view key, const std::string& s, std::size_t) {
        out_[std::string(key)] = printable(s);
    }
    void version(std::string_view key, const std::uint32_t& word) {
        out_[std::string(key)] = version_string(word);
    }
    void zoom(std::string_view key, const double& ratio) { out_[std::string(key)] = ratio; }
    void optional() {}

  private:
    nlohmann::json& out_;
};

template <class M>
nlohmann::json to_json(M m) {
    nlohmann::json out = nlohmann::json::object();
    out["message"] = M::name;
    JsonWriter w(out);
    m.fields(w);
    return out;
}

nlohmann::json to_json(const ToGimbal& m);
nlohmann::json to_json(const FromGimbal& m);
// A frame with its header and decoded message: {"cmd", "ctrl", "seq", "message", fields...},
// or {"cmd", "ctrl", "seq", "error", "length"} when it does not decode.
nlohmann::json frame_to_json(const Frame& frame, Direction direction);

}  // namespace gimbal::siyi
