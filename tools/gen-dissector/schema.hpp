// A schema visitor over the OrionPublic packet declarations
// (lib/protocols/orion/codec/fields.hpp): walks every packet's fields() and records, row by
// row, what the wire holds - so the Wireshark dissector is generated from the same
// declarations the codec's encoder, decoder and JSON writer visit.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "protocols/orion/codec/fields.hpp"
#include "protocols/orion/codec/wire.hpp"

namespace gimbal::dissector {

// One row of a packet declaration.
struct Entry {
    std::string kind;  // field bits reserved reserved_bits count group string fixed_string ipv4
                       // optional
    std::string key;
    std::string enc;       // "u", "i" (integer), "sf" (F16:X), "f32", "f64"
    std::size_t size = 0;  // bytes of one wire item
    int sig = 0;           // significand bits of "sf"
    double factor = 1.0;
    double offset = 0.0;
    bool radians = false;         // wire radians, JSON degrees
    std::string member;           // float int bool enum (what the decoded value is)
    int enum_id = -1;             // index into the enum tables
    std::size_t n = 0;            // fixed repeat length (arrays, fixed groups); 0 = scalar
    std::string count_key;        // a repeat sized by an earlier count field
    int width = 0;                // bits
    std::size_t max = 0;          // count maximum, string maximum bytes
    std::vector<Entry> children;  // a group's structure
    // Present only when the decoded value of cond_key is (cond_present) / is not
    // (!cond_present) one of cond_values.
    std::string cond_key;
    bool cond_present = false;
    std::vector<std::int64_t> cond_values;
    const void* vector_address = nullptr;  // links a count to its repeat while visiting
};

// Enum name tables, one per enum type, shared by every field of that type.
struct EnumTable {
    std::vector<std::pair<std::int64_t, std::string>> names;  // canonical name first per value
};

class EnumRegistry {
  public:
    template <class E>
    int add() {
        const auto names = enum_names(E{});
        const void* identity = names.data();
        const auto it = ids_.find(identity);
        if (it != ids_.end()) return it->second;
        EnumTable table;
        for (const auto& entry : names)
            table.names.emplace_back(
                static_cast<std::int64_t>(static_cast<std::underlying_type_t<E>>(entry.value)),
                std::string(entry.name));
        tables_.push_back(std::move(table));
        const int id = static_cast<int>(tables_.size()) - 1;
        ids_.emplace(identity, id);
        return id;
    }
    const std::vector<EnumTable>& tables() const { return tables_; }

  private:
    std::map<const void*, int> ids_;
    std::vector<EnumTable> tables_;
};

class SchemaVisitor {
  public:
    SchemaVisitor(std::vector<Entry>& out, EnumRegistry& enums) : out_(out), enums_(enums) {}

    template <class T, class E>
    void field(std::string_view key, T& member, E enc, orion::Scale s = {},
               orion::Unit unit = orion::Unit::none) {
        Entry e = make("field", key);
        describe_encoding(e, enc);
        e.factor = s.factor;
        e.offset = s.offset;
        e.radians = unit == orion::Unit::radians;
        if constexpr (orion::is_std_array<T>) {
            e.n = member.size();
            describe_member<typename T::value_type>(e);
        } else if constexpr (orion::is_std_vector<T>) {
            e.count_key = count_of(&member);
            describe_member<typename T::value_type>(e);
        } else {
            describe_member<T>(e);
        }
        out_.push_back(std::move(e));
    }

    template <class T>
    void bits(std::string_view key, T&, int width) {
        Entry e = make("bits", key);
        e.width = width;
        describe_member<T>(e);
        out_.push_back(std::move(e));
    }

    template <class E>
    void reserved(E) {
        Entry e = make("reserved", "reserved");
        e.size = E::size;
        out_.push_back(std::move(e));
    }
    void reserved_bits(int width) {
        Entry e = make("reserved_bits", "reserved");
        e.width = width;
        out_.push_back(std::move(e));
    }

    template <class T, class E>
    void count(std::string_view key, std::vector<T>& items, E enc, std::size_t max) {
        Entry e = make("count", key);
        describe_encoding(e, enc);
        e.member = "int";
        e.max = max;
        e.vector_address = &items;
        out_.push_back(std::move(e));
    }

    template <class G>
    void group(std::string_view key, std::vector<G>& items) {
        Entry e = make("group", key);
        e.count_key = count_of(&items);
        if (e.count_key.empty()) e.n = items.size();  // a fixed repeat sized by the declaration
        G element{};
        SchemaVisitor sub(e.children, enums_);
        element.fields(sub);
        out_.push_back(std::move(e));
    }

    void string(std::string_view key, std::string&, std::size_t max_bytes) {
        Entry e = make("string", key);
        e.max = max_bytes;
        out_.push_back(std::move(e));
    }
    void fixed_string(std::string_view key, std::string&, std::size_t bytes) {
        Entry e = make("fixed_string", key);
        e.size = bytes;
        out_.push_back(std::move(e));
    }
    void ipv4(std::string_view key, std::uint32_t&) {
        Entry e = make("ipv4", key);
        e.enc = "u";
        e.size = 4;
        out_.push_back(std::move(e));
    }
    void optional() { out_.push_back(make("optional", "")); }

  private:
    static Entry make(const char* kind, std::string_view key) {
        Entry e;
        e.kind = kind;
        e.key = std::string(key);
        return e;
    }

    std::string count_of(const void* vector_address) const {
        for (const auto& e : out_)
            if (e.kind == "count" && e.vector_address == vector_address) return e.key;
        return {};
    }

    template <int B, bool S>
    static void describe_encoding(Entry& e, orion::IntEnc<B, S>) {
        e.enc = S ? "i" : "u";
        e.size = B;
    }
    template <int B, int Sig>
    static void describe_encoding(Entry& e, orion::SmallFloatEnc<B, Sig>) {
        e.enc = "sf";
        e.size = B;
        e.sig = Sig;
    }
    static void describe_encoding(Entry& e, orion::F32Enc) {
        e.enc = "f32";
        e.size = 4;
    }
    static void describe_encoding(Entry& e, orion::F64Enc) {
        e.enc = "f64";
        e.size = 8;
    }

    template <class T>
    void describe_member(Entry& e) {
        if constexpr (std::is_enum_v<T>) {
            e.member = "enum";
            e.enum_id = enums_.add<T>();
        } else if constexpr (std::is_same_v<T, bool>) {
            e.member = "bool";
        } else if constexpr (std::is_integral_v<T>) {
            e.member = "int";
        } else {
            e.member = "float";
        }
    }

    std::vector<Entry>& out_;
    EnumRegistry& enums_;
};

// Sets one scalar member (by key) to a raw wire value: how the generator finds out which
// fields a conditional `if (x)` in a declaration depends on.
class SetVisitor {
  public:
    SetVisitor(std::string_view key, std::int64_t raw) : key_(key), raw_(raw) {}

    template <class T, class E>
    void field(std::string_view key, T& member, E, orion::Scale = {},
               orion::Unit = orion::Unit::none) {
        if (key == key_) assign(member);
    }
    template <class T>
    void bits(std::string_view key, T& member, int) {
        if (key == key_) assign(member);
    }
    template <class E>
    void reserved(E) {}
    void reserved_bits(int) {}
    template <class T, class E>
    void count(std::string_view, std::vector<T>&, E, std::size_t) {}
    template <class G>
    void group(std::string_view, std::vector<G>&) {}
    void string(std::string_view, std::string&, std::size_t) {}
    void fixed_string(std::string_view, std::string&, std::size_t) {}
    void ipv4(std::string_view, std::uint32_t&) {}
    void optional() {}

  private:
    template <class T>
    void assign(T& member) {
        if constexpr (std::is_enum_v<T>)
            member = static_cast<T>(static_cast<std::underlying_type_t<T>>(raw_));
        else if constexpr (std::is_same_v<T, bool>)
            member = raw_ != 0;
        else if constexpr (std::is_integral_v<T>)
            member = static_cast<T>(raw_);
    }

    std::string_view key_;
    std::int64_t raw_;
};

}  // namespace gimbal::dissector
