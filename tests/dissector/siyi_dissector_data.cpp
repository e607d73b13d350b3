// siyi-dissector-data: the SIYI dissector's schema table, generated from the codec's message
// declarations (lib/protocols/siyi/codec/*_gimbal.hpp), and the frames its test decodes.
//
//   siyi-dissector-data --schema            print the generated block
//   siyi-dissector-data --check FILE        exit 1 if FILE's generated block differs (a ctest)
//   siyi-dissector-data --write FILE        replace FILE's generated block
//   siyi-dissector-data --vectors [SEED]    one JSON line per frame: {"hex","direction",
//                                           "codec"} - the SDK's golden frames, then every
//                                           message of both directions filled with random
//                                           bytes, as the codec decodes them
//
// lib/protocols/siyi/dissector/siyi.lua interprets the table, so the dissector cannot drift
// from the codec; tests/dissector/test_siyi_dissector.py compares the two.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include "../unit/siyi/vectors.hpp"
#include "framing/hex.hpp"
#include "protocols/siyi/codec/framer.hpp"
#include "protocols/siyi/codec/json.hpp"
#include "protocols/siyi/codec/messages.hpp"

using namespace gimbal;

namespace {

constexpr const char* begin_marker = "-- BEGIN GENERATED SIYI SCHEMA";
constexpr const char* end_marker = "-- END GENERATED SIYI SCHEMA";

template <class Raw>
std::string enc_name() {
    if constexpr (std::is_same_v<Raw, float>) return "f32";
    std::string n = std::is_signed_v<Raw> ? "i" : "u";
    return n + std::to_string(sizeof(Raw) * 8);
}

std::string number(double v) {
    if (std::isinf(v)) return v > 0 ? "math.huge" : "-math.huge";
    std::ostringstream s;
    s.precision(17);
    s << v;
    return s.str();
}

std::string lua_string(std::string_view s) {
    return "\"" + std::string(s) + "\"";
}

// Enumerations by first appearance: their Lua table index.
struct Enums {
    std::vector<std::string> tables;  // Lua text of each
    std::map<std::string, int> index;

    template <class E>
    int of() {
        std::string text = "{";
        for (const auto& e : enum_names(E{}))
            text += " [" + std::to_string(static_cast<long long>(e.value)) +
                    "] = " + lua_string(e.name) + ",";
        text += " }";
        const auto [it, added] = index.emplace(text, static_cast<int>(tables.size()) + 1);
        if (added) tables.push_back(text);
        return it->second;
    }
};

// Records each row of a message's fields(): what siyi.lua reads, in wire order.
class SchemaVisitor {
  public:
    explicit SchemaVisitor(Enums& enums) : enums_(enums) {}
    std::vector<std::string> rows;

    template <class T, class Raw>
    void field(std::string_view key, const T&, siyi::Enc<Raw>, double scale = 1.0,
               siyi::Unit unit = siyi::Unit::none) {
        std::string row = "{ k = \"field\", key = " + lua_string(key) +
                          ", enc = " + lua_string(enc_name<Raw>()) + ", scale = " + number(scale);
        if constexpr (std::is_enum_v<T>) {
            using U = std::underlying_type_t<T>;
            row += ", kind = \"enum\", enum = " + std::to_string(enums_.template of<T>()) +
                   ", min = " + number(static_cast<double>(std::numeric_limits<U>::lowest())) +
                   ", max = " + number(static_cast<double>(std::numeric_limits<U>::max()));
        } else if constexpr (std::is_same_v<T, bool>) {
            row += ", kind = \"bool\"";
        } else if constexpr (std::is_same_v<T, float>) {
            row += ", kind = \"f32\"";
        } else if constexpr (std::is_floating_point_v<T>) {
            row += ", kind = \"double\"";
        } else {
            row += ", kind = \"int\", min = " +
                   number(static_cast<double>(std::numeric_limits<T>::lowest())) +
                   ", max = " + number(static_cast<double>(std::numeric_limits<T>::max()));
        }
        if (unit == siyi::Unit::radians) row += ", degrees = true";
        rows.push_back(row + " }");
    }
    template <class Raw>
    void reserved(siyi::Enc<Raw>) {
        rows.push_back("{ k = \"reserved\", enc = " + lua_string(enc_name<Raw>()) + " }");
    }
    void text(std::string_view key, const std::string&, std::size_t bytes) {
        rows.push_back("{ k = \"text\", key = " + lua_string(key) +
                       ", bytes = " + std::to_string(bytes) + " }");
    }
    void version(std::string_view key, const std::uint32_t&) {
        rows.push_back("{ k = \"version\", key = " + lua_string(key) + " }");
    }
    void zoom(std::string_view key, const double&) {
        rows.push_back("{ k = \"zoom\", key = " + lua_string(key) + " }");
    }
    void optional() { rows.push_back("{ k = \"optional\" }"); }

  private:
    Enums& enums_;
};

template <class List>
std::string messages_table(List list, Enums& enums) {
    std::string out;
    siyi::for_each_message(list, [&]<class M>(M*) {
        M m{};
        SchemaVisitor v(enums);
        m.fields(v);
        char id[8];
        std::snprintf(id, sizeof id, "0x%02X", M::cmd);
        out += "    [" + std::string(id) + "] = { name = " + lua_string(M::name) + ", rows = {\n";
        for (const auto& r : v.rows) out += "      " + r + ",\n";
        out += "    } },\n";
    });
    return out;
}

std::string schema() {
    Enums enums;
    const std::string to = messages_table(siyi::ToGimbalList{}, enums);
    const std::string from = messages_table(siyi::FromGimbalList{}, enums);
    std::string out = std::string(begin_marker) +
                      " (tests/dissector/siyi_dissector_data.cpp from "
                      "lib/protocols/siyi/codec/*_gimbal.hpp; do not edit by hand:\n"
                      "-- build/debug/tests/dissector/siyi-dissector-data --write "
                      "lib/protocols/siyi/dissector/siyi.lua)\n";
    out += "local siyi_enums = {\n";
    for (std::size_t i = 0; i < enums.tables.size(); ++i)
        out += "  [" + std::to_string(i + 1) + "] = " + enums.tables[i] + ",\n";
    out += "}\nlocal siyi_messages = {\n  to_gimbal = {\n" + to + "  },\n  from_gimbal = {\n" +
           from + "  },\n}\n" + end_marker + "\n";
    return out;
}

// FILE's text with its generated block replaced by `block`; empty when it has no markers.
std::string with_block(const std::string& text, const std::string& block) {
    const auto begin = text.find(begin_marker);
    const auto end_at = text.find(end_marker);
    if (begin == std::string::npos || end_at == std::string::npos || end_at < begin) return {};
    const auto end = text.find('\n', end_at);
    return text.substr(0, begin) + block +
           (end == std::string::npos ? std::string() : text.substr(end + 1));
}

// The length of a CMD_ID's message with every optional field (0: not declared).
std::size_t full_length(siyi::Direction direction, std::uint8_t cmd) {
    std::size_t length = 0;
    const auto find = [&]<class M>(M*) {
        if (M::cmd == cmd) length = siyi::max_length<M>();
    };
    if (direction == siyi::Direction::to_gimbal)
        siyi::for_each_message(siyi::ToGimbalList{}, find);
    else
        siyi::for_each_message(siyi::FromGimbalList{}, find);
    return length;
}

void print_vector(const std::vector<std::uint8_t>& bytes, siyi::Direction direction) {
    siyi::Framer framer;
    framer.push(bytes, [&](const siyi::Frame& f) {
        nlohmann::json line = {
            {"hex", framing::to_hex(bytes)},
            {"direction", direction == siyi::Direction::to_gimbal ? "to_gimbal" : "from_gimbal"},
            {"codec", siyi::frame_to_json(f, direction)},
            // Shorter than the message's every field: the codec shows the absent optional
            // fields' defaults, which the dissector leaves out.
            {"partial", f.data.size < full_length(direction, f.cmd)}};
        std::cout << line.dump() << "\n";
    });
}

// Every message of a direction, its whole length filled with random bytes, as the codec
// decodes it: the frame re-encoded from the decoded message (so that the bytes are the
// codec's), with the header of the direction.
template <class List>
void random_vectors(List list, siyi::Direction direction, std::mt19937& rng, int per_message) {
    siyi::for_each_message(list, [&]<class M>(M*) {
        for (int i = 0; i < per_message; ++i) {
            std::vector<std::uint8_t> data(siyi::max_length<M>());
            for (auto& b : data) b = static_cast<std::uint8_t>(rng());
            M m{};
            siyi::Decoder d(data);
            m.fields(d);
            if (d.error() != siyi::DecodeError::none) continue;
            siyi::Header h;
            h.ctrl =
                direction == siyi::Direction::to_gimbal ? siyi::ctrl_need_ack : siyi::ctrl_ack_pack;
            h.seq = static_cast<std::uint16_t>(rng());
            print_vector(siyi::encode(m, h), direction);
        }
    });
}

int vectors(std::uint32_t seed) {
    for (const auto& g : siyi_test::sdk_requests())
        print_vector(g.bytes, siyi::Direction::to_gimbal);
    for (const auto& g : siyi_test::sdk_undeclared())
        print_vector(g.bytes, siyi::Direction::to_gimbal);
    for (const auto* reply :
         {&siyi_test::mk15_hardware_id_reply, &siyi_test::captured_attitude_reply,
          &siyi_test::captured_attitude_reply2})
        print_vector(*reply, siyi::Direction::from_gimbal);
    std::mt19937 rng(seed);
    random_vectors(siyi::ToGimbalList{}, siyi::Direction::to_gimbal, rng, 4);
    random_vectors(siyi::FromGimbalList{}, siyi::Direction::from_gimbal, rng, 4);
    return 0;
}

std::string read_file(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

}  // namespace

int main(int argc, char** argv) {
    const std::string mode = argc > 1 ? argv[1] : "--schema";
    if (mode == "--schema") {
        std::cout << schema();
        return 0;
    }
    if (mode == "--vectors")
        return vectors(argc > 2 ? static_cast<std::uint32_t>(std::stoul(argv[2])) : 1u);
    if ((mode == "--check" || mode == "--write") && argc == 3) {
        const std::string text = read_file(argv[2]);
        const std::string updated = with_block(text, schema());
        if (updated.empty()) {
            std::cerr << argv[2] << ": no generated block (" << begin_marker << " ... "
                      << end_marker << ")\n";
            return 1;
        }
        if (mode == "--check") {
            if (updated == text) return 0;
            std::cerr << argv[2]
                      << ": the generated SIYI schema is stale; run siyi-dissector-data --write "
                      << argv[2] << "\n";
            return 1;
        }
        std::ofstream(argv[2], std::ios::binary) << updated;
        return 0;
    }
    std::cerr << "usage: siyi-dissector-data [--schema | --check FILE | --write FILE | "
                 "--vectors [SEED]]\n";
    return 2;
}
