// Writes ST 0601 local sets for the lib/klv agreement test (klv_st0601_agreement.py): every
// tag of the table with a random value inside its range, plus sets at the range ends and
// with the reserved values. For set N it writes, into the output folder:
//   N.klv          the encoded set
//   N.input.json   the values given to encode() (JSON units; enumerations by name, time
//                  stamps in microseconds, flags and nibbles as the wire integer, raw as hex;
//                  tag 74, a MISB ST 0903 VMTI set, under "vmti" as lib/klv's JSON of it)
//   N.decoded.json lib/klv's decode() of N.klv: {"status": ..., "json": {...}}
// Usage: klv_sample_sets OUTPUT_DIR [COUNT] [SEED]
#include <cstdio>
#include <fstream>
#include <random>
#include <stdexcept>
#include <string>

#include "klv/local_set.hpp"
#include "klv/mapping.hpp"
#include "klv/vmti.hpp"

namespace klv = gimbal::klv;
using nlohmann::json;

namespace {

enum class Pick { random, low, high, reserved };

std::string hex(const klv::Bytes& b) {
    static constexpr char digits[] = "0123456789ABCDEF";
    std::string s;
    for (const auto x : b) {
        s.push_back(digits[x >> 4]);
        s.push_back(digits[x & 15]);
    }
    return s;
}

struct Maker {
    std::mt19937_64 rng;

    std::uint64_t below(std::uint64_t n) {  // 0..n-1 (n = 0: any)
        const std::uint64_t r = rng();
        return n == 0 ? r : r % n;
    }
    double uniform(double lo, double hi) {
        return std::uniform_real_distribution<double>(lo, hi)(rng);
    }

    // Tag 74: a VMTI set (lib/klv/vmti.hpp) at its ranges' low or high ends, or random: one
    // to three targets with pixels inside the frame, and a location half of the time.
    void add_vmti(Pick pick, klv::LocalSet& set, json& input) {
        klv::VmtiSet vmti;
        klv::VmtiTarget t;
        if (pick == Pick::low || pick == Pick::high) {
            const bool high = pick == Pick::high;
            const std::uint32_t side = high ? 16777215 : 1;  // 3 bytes at most
            vmti.frame_width = vmti.frame_height = side;
            vmti.total_targets = vmti.reported_targets = high ? 16777215u : 0u;
            t.id = high ? UINT64_MAX : 0;
            t.centroid = t.top_left = t.bottom_right = std::uint64_t{side} * side;
            t.confidence_pct = high ? 100 : 0;
            t.location = high ? klv::VmtiLocation{90.0, 180.0, 19000.0}
                              : klv::VmtiLocation{-90.0, -180.0, -900.0};
            vmti.targets.push_back(t);
        } else {
            const auto width = static_cast<std::uint32_t>(1 + below(4096));
            const auto height = static_cast<std::uint32_t>(1 + below(4096));
            vmti.frame_width = width;
            vmti.frame_height = height;
            const std::size_t n = 1 + below(3);
            vmti.total_targets = vmti.reported_targets = static_cast<std::uint32_t>(n);
            const auto pixel = [&] {
                return klv::vmti_pixel_number(static_cast<std::uint32_t>(1 + below(height)),
                                              static_cast<std::uint32_t>(1 + below(width)), width);
            };
            for (std::size_t i = 0; i < n; ++i) {
                t = {};
                t.id = below(1ull << (7 * (1 + below(6))));
                t.centroid = pixel();
                t.top_left = pixel();
                t.bottom_right = pixel();
                t.confidence_pct = static_cast<std::uint8_t>(below(101));
                if (below(2) == 0)
                    t.location = klv::VmtiLocation{uniform(-90, 90), uniform(-180, 180),
                                                   uniform(-900, 19000)};
                vmti.targets.push_back(t);
            }
        }
        const auto bytes = klv::encode_vmti(vmti);
        if (!bytes.ok()) throw std::runtime_error(bytes.error().message);
        set.add(74, bytes.value());
        input["vmti"] = klv::vmti_json(vmti);
    }

    // Adds one item for `row` to `set` and records the value given in `input`.
    void add(const klv::TagSpec& row, Pick pick, klv::LocalSet& set, json& input) {
        const std::string name(row.name);
        if (row.tag == 74) return add_vmti(pick, set, input);
        switch (row.kind) {
            case klv::Kind::checksum:
                return;
            case klv::Kind::linear:
            case klv::Kind::imapb: {
                if (pick == Pick::reserved && row.reserved) {
                    set.add(row.tag, klv::Reserved{});
                    input[name] = nullptr;
                    return;
                }
                const double lo = row.min * row.to_json, hi = row.max * row.to_json;
                const double x = pick == Pick::low ? lo : pick == Pick::high ? hi : uniform(lo, hi);
                const auto length = row.kind == klv::Kind::imapb
                                        ? static_cast<std::uint8_t>(2 + below(3))
                                        : std::uint8_t{0};
                set.add(row.tag, x, length);
                input[name] = x;
                return;
            }
            case klv::Kind::time_us: {
                const std::uint64_t us = pick == Pick::low    ? 0
                                         : pick == Pick::high ? 253402300799999999ull
                                                              : below(4102444800000000ull);
                set.add(row.tag, us);
                input[name] = us;
                return;
            }
            case klv::Kind::uint: {
                const std::size_t n = row.max_length != 0 ? 1 + below(row.max_length) : row.length;
                const std::uint64_t top = n >= 8 ? ~0ull : (1ull << (8 * n)) - 1;
                const std::uint64_t v = pick == Pick::low    ? 0
                                        : pick == Pick::high ? top
                                                             : below(top);
                set.add(row.tag, v);
                input[name] = v;
                return;
            }
            case klv::Kind::sint: {
                const std::size_t n = row.max_length != 0 ? 1 + below(row.max_length) : row.length;
                const std::int64_t top = n >= 8 ? INT64_MAX : (std::int64_t{1} << (8 * n - 1)) - 1;
                std::int64_t v =
                    pick == Pick::low ? -top - 1
                    : pick == Pick::high
                        ? top
                        : static_cast<std::int64_t>(below(static_cast<std::uint64_t>(top))) -
                              static_cast<std::int64_t>(below(static_cast<std::uint64_t>(top)));
                if (row.to_json < 1.0) v /= 1048576;  // seconds with microseconds a double holds
                if (row.to_json < 1.0) {
                    const double seconds = static_cast<double>(v) * row.to_json;
                    set.add(row.tag, seconds);
                    input[name] = seconds;
                } else {
                    set.add(row.tag, v);
                    input[name] = v;
                }
                return;
            }
            case klv::Kind::string: {
                static const std::string alphabet =
                    "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789 -_./:";
                std::string s;
                const std::size_t n = pick == Pick::high ? 127 : 1 + below(40);
                while (s.size() < n) s.push_back(alphabet[below(alphabet.size())]);
                if (pick == Pick::random && below(4) == 0) s += "\xC3\xA9";  // UTF-8 e-acute
                set.add(row.tag, s);
                input[name] = s;
                return;
            }
            case klv::Kind::enumeration: {
                const std::size_t n = row.names.size();
                const std::size_t i = pick == Pick::low ? 0 : pick == Pick::high ? n - 1 : below(n);
                set.add(row.tag, std::string(row.names[i]));
                input[name] = std::string(row.names[i]);
                return;
            }
            case klv::Kind::flags:
            case klv::Kind::nibbles: {
                const std::uint64_t top = (1ull << (8 * row.length)) - 1;
                const std::uint64_t v = pick == Pick::low    ? 0
                                        : pick == Pick::high ? top
                                                             : below(top + 1);
                set.add(row.tag, v);
                input[name] = v;
                return;
            }
            case klv::Kind::oid_list:
            case klv::Kind::frame_rate:
            case klv::Kind::bit_list: {
                std::vector<std::uint64_t> values;
                if (row.kind == klv::Kind::frame_rate) {
                    values.push_back(1 + below(120000));
                    if (below(2) == 0) values.push_back(1 + below(2000));
                } else if (row.kind == klv::Kind::bit_list) {
                    for (std::uint64_t id = 0; id < 40; ++id)
                        if (below(3) == 0) values.push_back(id);
                    if (values.empty()) values.push_back(0);
                } else {
                    const std::size_t n = 1 + below(4);
                    for (std::size_t i = 0; i < n; ++i)
                        values.push_back(below(1ull << (7 * (1 + below(4)))));
                }
                set.add(row.tag, values);
                input[name] = values;
                return;
            }
            case klv::Kind::raw: {
                const std::size_t copies = row.multiple ? 1 + below(2) : 1;
                for (std::size_t c = 0; c < copies; ++c) {
                    klv::Bytes b(1 + below(23));
                    for (auto& x : b) x = static_cast<std::uint8_t>(below(256));
                    set.add(row.tag, b);
                    if (row.multiple)
                        input[name].push_back(hex(b));
                    else
                        input[name] = hex(b);
                }
                return;
            }
        }
    }
};

bool write(const std::string& path, const std::string& bytes) {
    std::ofstream out(path, std::ios::binary);
    out << bytes;
    return static_cast<bool>(out);
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: klv_sample_sets OUTPUT_DIR [COUNT] [SEED]\n");
        return 2;
    }
    const std::string dir = argv[1];
    const int count = argc > 2 ? std::stoi(argv[2]) : 40;
    Maker maker{std::mt19937_64(argc > 3 ? std::stoull(argv[3]) : 20261126)};
    for (int n = 0; n < count; ++n) {
        const Pick pick = n == 0   ? Pick::low
                          : n == 1 ? Pick::high
                          : n == 2 ? Pick::reserved
                                   : Pick::random;
        klv::LocalSet set;
        json input = json::object();
        for (const klv::TagSpec& row : klv::st0601_tags) maker.add(row, pick, set, input);
        const klv::Encoded e = klv::encode(set);
        if (!e.ok()) {
            std::fprintf(stderr, "klv_sample_sets: set %d: %s\n", n, e.error().message.c_str());
            return 1;
        }
        const klv::DecodeResult r = klv::decode(e.value(), klv::Digits::exact);
        const json decoded{
            {"status", klv::to_string(r.status)}, {"reason", r.reason}, {"json", r.json}};
        const std::string base = dir + "/" + std::to_string(n);
        if (!write(base + ".klv", std::string(e.value().begin(), e.value().end())) ||
            !write(base + ".input.json", input.dump(1)) ||
            !write(base + ".decoded.json", decoded.dump(1))) {
            std::fprintf(stderr, "klv_sample_sets: cannot write %s.*\n", base.c_str());
            return 1;
        }
    }
    std::printf("klv_sample_sets: %d sets in %s\n", count, dir.c_str());
    return 0;
}
