// gen-dissector: writes the OrionPublic schema table of dissectors/gimbald.lua from the codec's
// packet declarations (lib/protocols/orion/codec/packets_*.hpp), so the dissector cannot drift from
// the codec.
//
//   gen-dissector                 print the generated block
//   gen-dissector --check FILE    exit 1 if FILE's generated block differs (a ctest)
//   gen-dissector --write FILE    replace FILE's generated block (target update-dissector)
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "protocols/orion/codec/packets.hpp"
#include "schema.hpp"

using namespace gimbal;
using gimbal::dissector::Entry;

namespace {

constexpr const char* begin_marker = "-- BEGIN GENERATED ORION SCHEMA";
constexpr const char* end_marker = "-- END GENERATED ORION SCHEMA";

struct PacketSchema {
    int id = 0;
    std::string name;
    std::size_t min_length = 0;
    std::size_t max_length = 0;
    std::vector<Entry> entries;
};

template <class P>
std::vector<Entry> schema_of(P packet, dissector::EnumRegistry& enums) {
    std::vector<Entry> out;
    dissector::SchemaVisitor v(out, enums);
    packet.fields(v);
    return out;
}

bool named(const Entry& e) {
    return e.kind != "reserved" && e.kind != "reserved_bits" && e.kind != "optional";
}

std::set<std::string> keys_of(const std::vector<Entry>& entries) {
    std::set<std::string> keys;
    for (const auto& e : entries)
        if (named(e)) keys.insert(e.key);
    return keys;
}

// A scalar field whose value might switch later fields on or off (`if (x) v.field(...)`).
struct Controller {
    std::string key;
    std::vector<std::int64_t> domain;
    std::map<std::int64_t, std::set<std::string>> present;  // keys visited for each value
    std::int64_t widest = 0;                                // the value that shows the most
};

template <class P>
PacketSchema describe(dissector::EnumRegistry& enums) {
    PacketSchema schema;
    schema.id = P::id;
    schema.name = std::string(P::name);
    schema.min_length = P::min_length;
    schema.max_length = P::max_length;

    // Probe every scalar bool, enum or integer field with each value it can take; the fields
    // that appear or disappear are conditional on it.
    const auto base = schema_of(P{}, enums);
    std::vector<Controller> controllers;
    for (const auto& e : base) {
        if ((e.kind != "field" && e.kind != "bits") || e.n != 0 || !e.count_key.empty() ||
            e.member == "float")
            continue;
        Controller c;
        c.key = e.key;
        c.domain = {0, 1};
        if (e.member == "enum")
            for (const auto& [value, name] :
                 enums.tables()[static_cast<std::size_t>(e.enum_id)].names)
                c.domain.push_back(value);
        std::sort(c.domain.begin(), c.domain.end());
        c.domain.erase(std::unique(c.domain.begin(), c.domain.end()), c.domain.end());
        bool varies = false;
        for (const auto value : c.domain) {
            P probe{};
            dissector::SetVisitor set(c.key, value);
            probe.fields(set);
            c.present[value] = keys_of(schema_of(probe, enums));
            if (c.present[value] != c.present[c.domain.front()]) varies = true;
            if (c.present[value].size() > c.present[c.widest].size()) c.widest = value;
        }
        if (varies) controllers.push_back(std::move(c));
    }

    P full{};
    for (const auto& c : controllers) {
        dissector::SetVisitor set(c.key, c.widest);
        full.fields(set);
    }
    schema.entries = schema_of(full, enums);
    const auto all_keys = keys_of(schema.entries);

    for (auto& e : schema.entries) {
        if (!named(e)) continue;
        for (const auto& c : controllers) {
            std::vector<std::int64_t> with, without;
            for (const auto value : c.domain)
                (c.present.at(value).count(e.key) ? with : without).push_back(value);
            if (with.empty() || without.empty()) continue;  // not switched by this field
            if (!e.cond_key.empty())
                throw std::runtime_error(schema.name + "." + e.key + " depends on two fields (" +
                                         e.cond_key + ", " + c.key +
                                         "); the dissector cannot say so");
            e.cond_key = c.key;
            // A bool or "if (x)" reads best as "absent when 0"; an "== value" test as present.
            e.cond_present = with.size() < without.size();
            e.cond_values = e.cond_present ? with : without;
        }
    }
    for (const auto& c : controllers)
        for (const auto& [value, keys] : c.present)
            for (const auto& k : keys)
                if (!all_keys.count(k))
                    throw std::runtime_error(schema.name + "." + k +
                                             " appears only for a combination of fields");
    return schema;
}

std::string number(double v) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return buf;
}

std::string quoted(const std::string& s) {
    return "\"" + s + "\"";
}

void emit_entries(std::ostream& out, const std::vector<Entry>& entries, const std::string& indent) {
    for (const auto& e : entries) {
        out << indent << "{ kind = " << quoted(e.kind);
        if (!e.key.empty()) out << ", key = " << quoted(e.key);
        if (!e.enc.empty()) out << ", enc = " << quoted(e.enc);
        if (e.size) out << ", size = " << e.size;
        if (e.sig) out << ", sig = " << e.sig;
        if (e.factor != 1.0) out << ", factor = " << number(e.factor);
        if (e.offset != 0.0) out << ", offset = " << number(e.offset);
        if (e.radians) out << ", radians = true";
        if (!e.member.empty()) out << ", member = " << quoted(e.member);
        if (e.enum_id >= 0) out << ", enum = " << e.enum_id + 1;
        if (e.n) out << ", n = " << e.n;
        if (!e.count_key.empty()) out << ", count = " << quoted(e.count_key);
        if (e.width) out << ", width = " << e.width;
        if (e.max) out << ", max = " << e.max;
        if (!e.cond_key.empty()) {
            out << ", cond = { key = " << quoted(e.cond_key)
                << ", present = " << (e.cond_present ? "true" : "false") << ", values = {";
            for (std::size_t i = 0; i < e.cond_values.size(); ++i)
                out << (i ? ", " : " ") << e.cond_values[i];
            out << " } }";
        }
        if (e.kind == "group") {
            out << ", fields = {\n";
            emit_entries(out, e.children, indent + "    ");
            out << indent << "  } },\n";
        } else {
            out << " },\n";
        }
    }
}

std::string generate() {
    dissector::EnumRegistry enums;
    std::vector<PacketSchema> packets;
    orion::for_each_packet([&]<class P>() { packets.push_back(describe<P>(enums)); });
    std::sort(packets.begin(), packets.end(),
              [](const auto& a, const auto& b) { return a.id < b.id; });

    std::ostringstream out;
    out << begin_marker << " (tools/gen-dissector from lib/protocols/orion/codec/packets_*.hpp;"
        << " do not edit by hand:\n"
        << "-- cmake --build build/debug --target update-dissector)\n";
    out << "local orion_enums = {\n";
    for (std::size_t i = 0; i < enums.tables().size(); ++i) {
        out << "  [" << i + 1 << "] = {";
        std::set<std::int64_t> seen;
        for (const auto& [value, name] : enums.tables()[i].names) {
            if (!seen.insert(value).second) continue;  // later entries are aliases
            out << " [" << value << "] = " << quoted(name) << ",";
        }
        out << " },\n";
    }
    out << "}\n";
    out << "local orion_packets = {\n";
    for (const auto& p : packets) {
        out << "  [" << p.id << "] = { name = " << quoted(p.name) << ", min = " << p.min_length
            << ", max = " << p.max_length << ", fields = {\n";
        emit_entries(out, p.entries, "    ");
        out << "  } },\n";
    }
    out << "}\n";
    out << end_marker << "\n";
    return out.str();
}

bool split(const std::string& text, std::string& before, std::string& block, std::string& after) {
    const auto b = text.find(begin_marker);
    const auto e = text.find(end_marker);
    if (b == std::string::npos || e == std::string::npos || e < b) return false;
    const auto e_end = text.find('\n', e);
    before = text.substr(0, b);
    block = text.substr(b, (e_end == std::string::npos ? text.size() : e_end + 1) - b);
    after = e_end == std::string::npos ? "" : text.substr(e_end + 1);
    return true;
}

}  // namespace

int main(int argc, char** argv) {
    try {
        const std::string generated = generate();
        if (argc == 1) {
            std::cout << generated;
            return 0;
        }
        if (argc != 3 || (std::string(argv[1]) != "--check" && std::string(argv[1]) != "--write")) {
            std::cerr << "usage: gen-dissector [--check|--write FILE]\n";
            return 2;
        }
        const std::string path = argv[2];
        std::ifstream in(path, std::ios::binary);
        std::stringstream buf;
        buf << in.rdbuf();
        std::string before, block, after;
        if (!in || !split(buf.str(), before, block, after)) {
            std::cerr << path << ": no '" << begin_marker << "' ... '" << end_marker << "' block\n";
            return 1;
        }
        if (std::string(argv[1]) == "--check") {
            if (block == generated) return 0;
            std::cerr << path
                      << ": the generated Orion schema differs from the codec's declarations;\n"
                         "run: cmake --build build/debug --target update-dissector\n";
            return 1;
        }
        if (block != generated) {
            std::ofstream out(path, std::ios::binary | std::ios::trunc);
            out << before << generated << after;
            if (!out) {
                std::cerr << path << ": cannot write\n";
                return 1;
            }
        }
        return 0;
    } catch (const std::exception& e) {
        std::cerr << "gen-dissector: " << e.what() << "\n";
        return 1;
    }
}
