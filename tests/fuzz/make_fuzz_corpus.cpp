// Writes small seed inputs for the Orion fuzz targets from the packet declarations:
//   make_fuzz_corpus <dir>   ->   <dir>/orion_decode/*, <dir>/orion_json/*, <dir>/orion_framer/*
// Deterministic (fixed seed), so re-running it after adding packets only adds files.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include "orion_properties.hpp"

namespace {

namespace fs = std::filesystem;
using gimbal::fuzz::Bytes;
namespace orion = gimbal::orion;

void write(const fs::path& file, const Bytes& bytes) {
    fs::create_directories(file.parent_path());
    std::ofstream out(file, std::ios::binary);
    out.write(reinterpret_cast<const char*>(bytes.data()),
              static_cast<std::streamsize>(bytes.size()));
}

Bytes with_prefix(std::uint8_t first, const Bytes& rest) {
    Bytes out{first};
    out.insert(out.end(), rest.begin(), rest.end());
    return out;
}

// A full-length packet of type P with varied content.
template <class P>
P sample(std::mt19937& rng) {
    Bytes data(P::max_length);
    for (auto& b : data) b = static_cast<std::uint8_t>(rng());
    P packet{};
    if (auto d = orion::decode<P>(data)) packet = d.value;
    return packet;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: make_fuzz_corpus <corpus dir>\n");
        return 2;
    }
    const fs::path dir = argv[1];
    std::mt19937 rng(20240611);
    Bytes stream;  // every sample, back to back, for the framer
    std::size_t index = 0;
    orion::for_each_packet([&]<class P>() {
        const std::string name(P::name);
        const P full = sample<P>(rng);
        const Bytes full_data = gimbal::fuzz::bytes_of(orion::encode(full));
        write(dir / "orion_decode" / (name + "_full"), with_prefix(P::id, full_data));
        write(dir / "orion_decode" / (name + "_default"),
              with_prefix(P::id, gimbal::fuzz::bytes_of(orion::encode(P{}))));
        const std::string text = orion::to_json(full).dump();
        write(dir / "orion_json" / name,
              with_prefix(static_cast<std::uint8_t>(index), Bytes(text.begin(), text.end())));
        const Bytes wire = orion::frame_bytes(P::id, full_data);
        stream.insert(stream.end(), wire.begin(), wire.end());
        ++index;
    });

    // Framer inputs: [number of chunk sizes][chunk sizes...][stream]
    write(dir / "orion_framer" / "all_packets", with_prefix(0, stream));
    write(dir / "orion_framer" / "all_packets_chunked", with_prefix(3, [&] {
              Bytes b{0, 6, 144};
              b.insert(b.end(), stream.begin(), stream.end());
              return b;
          }()));
    Bytes junky{2, 0, 9};
    for (std::size_t i = 0; i < stream.size() && i < 1500; ++i) {
        if (rng() % 16 == 0) {
            junky.push_back(orion::sync0);
            if (rng() % 2) junky.push_back(orion::sync1);
            if (rng() % 2) junky.push_back(static_cast<std::uint8_t>(rng()));
        }
        junky.push_back(stream[i]);
    }
    write(dir / "orion_framer" / "junk_and_false_syncs", junky);
    const Bytes cut = with_prefix(0, {0xD0, 0x0D, 0xD4, 0x59, 0xD0, 0x0D, 0xD4, 0x2E});
    write(dir / "orion_framer" / "cut_off_header", cut);
    return 0;
}
