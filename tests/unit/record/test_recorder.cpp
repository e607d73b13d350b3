// The daemon's recorder: the inbound splitter (frames + junk, every byte once, whatever the
// chunking), the file rotation and the size cap. Files are read back with a small pcapng
// walker written here.
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>
#include <boost/asio/io_context.hpp>

#include <csignal>

#include <algorithm>
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "protocols/orion/codec/framing.hpp"
#include "record/record_files.hpp"
#include "record/recorder.hpp"
#include "record/recording_link.hpp"

namespace fs = std::filesystem;
using gimbal::record::Bytes;

namespace {

struct Record {
    std::uint32_t iface = 0;
    std::uint32_t flags = 0;
    std::string dissector;
    Bytes pdu;
};

std::uint32_t u32le(const Bytes& b, std::size_t at) {
    return static_cast<std::uint32_t>(b[at] | (b[at + 1] << 8) | (b[at + 2] << 16) |
                                      (static_cast<std::uint32_t>(b[at + 3]) << 24));
}

Bytes read_file(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return Bytes(std::istreambuf_iterator<char>(in), {});
}

// Every EPB of a file; also checks the blocks are whole and counts the IDBs.
std::vector<Record> read_records(const fs::path& path, std::size_t* interfaces = nullptr) {
    const Bytes b = read_file(path);
    std::vector<Record> out;
    std::size_t at = 0, idbs = 0;
    REQUIRE(b.size() >= 12);
    REQUIRE(u32le(b, 0) == gimbal::record::shb_block_type);
    while (at < b.size()) {
        const std::uint32_t type = u32le(b, at), len = u32le(b, at + 4);
        REQUIRE(len % 4 == 0);
        REQUIRE(at + len <= b.size());
        if (type == gimbal::record::idb_block_type) ++idbs;
        if (type == gimbal::record::epb_block_type) {
            Record r;
            r.iface = u32le(b, at + 8);
            const std::uint32_t caplen = u32le(b, at + 20);
            const std::size_t data = at + 28;
            std::size_t tlv = data;
            for (;;) {
                const unsigned tag = (b[tlv] << 8) | b[tlv + 1];
                const unsigned tlen = (b[tlv + 2] << 8) | b[tlv + 3];
                if (tag == 12) {
                    r.dissector.assign(b.begin() + static_cast<long>(tlv + 4),
                                       b.begin() + static_cast<long>(tlv + 4 + tlen));
                    while (!r.dissector.empty() && r.dissector.back() == '\0')
                        r.dissector.pop_back();
                }
                tlv += 4 + tlen;
                if (tag == 0) break;
            }
            r.pdu.assign(b.begin() + static_cast<long>(tlv),
                         b.begin() + static_cast<long>(data + caplen));
            r.flags = u32le(b, data + gimbal::record::padded4(caplen) + 4);
            out.push_back(std::move(r));
        }
        at += len;
    }
    if (interfaces) *interfaces = idbs;
    return out;
}

std::vector<fs::path> recordings(const fs::path& dir) {
    std::vector<fs::path> files;
    for (const auto& e : fs::directory_iterator(dir)) files.push_back(e.path());
    std::sort(files.begin(), files.end());
    return files;
}

struct TempDir {
    fs::path path;
    TempDir() {
        path = fs::temp_directory_path() / ("gimbald-unit-record-" + std::to_string(::getpid()) +
                                            "-" + std::to_string(counter++));
        fs::remove_all(path);
        fs::create_directories(path);
    }
    ~TempDir() { fs::remove_all(path); }
    static inline int counter = 0;
};

gimbald::record::RecorderOptions options_for(const fs::path& dir) {
    gimbald::record::RecorderOptions o;
    o.dir = dir.string();
    o.interfaces = {{"gimbal:main", "orion test"}, {"json", "json"}};
    return o;
}

}  // namespace

TEST_CASE("inbound bytes are recorded as frames and junk, every byte once, any chunking") {
    // junk, frame, stray sync, frame, a frame with a bad checksum, frame, partial frame
    Bytes stream = {'x', 'y', 'z'};
    std::vector<Bytes> frames;
    for (const std::uint8_t id : {std::uint8_t{0xD1}, std::uint8_t{0x40}, std::uint8_t{0x07}}) {
        Bytes payload(id == 0x07 ? 0 : 12, id);
        frames.push_back(gimbal::orion::frame_bytes(id, payload));
    }
    stream.insert(stream.end(), frames[0].begin(), frames[0].end());
    stream.push_back(0xD0);
    stream.insert(stream.end(), frames[1].begin(), frames[1].end());
    Bytes corrupt = frames[1];
    corrupt.back() ^= 0xFF;
    stream.insert(stream.end(), corrupt.begin(), corrupt.end());
    stream.insert(stream.end(), frames[2].begin(), frames[2].end());
    stream.insert(stream.end(), frames[0].begin(), frames[0].begin() + 5);  // cut by a drop

    for (std::size_t chunk = 1; chunk <= stream.size(); chunk += (chunk < 8 ? 1 : 7)) {
        TempDir dir;
        boost::asio::io_context io;
        gimbald::record::Recorder recorder(io, options_for(dir.path));
        auto splitter = gimbald::record::make_inbound_splitter("orion", recorder, 0);
        for (std::size_t at = 0; at < stream.size(); at += chunk)
            splitter->push(std::span(stream).subspan(at, std::min(chunk, stream.size() - at)));
        splitter->flush();  // the link dropped: the partial frame is junk
        recorder.stop();

        const auto files = recordings(dir.path);
        REQUIRE(files.size() == 1);
        const auto records = read_records(files[0]);
        Bytes joined;
        std::vector<Bytes> orion;
        for (const auto& r : records) {
            CHECK(r.iface == 0);
            CHECK(r.flags == 1);
            joined.insert(joined.end(), r.pdu.begin(), r.pdu.end());
            if (r.dissector == "orion")
                orion.push_back(r.pdu);
            else
                CHECK(r.dissector == "data");
        }
        INFO("chunk size " << chunk);
        CHECK(joined == stream);
        CHECK(orion == frames);
    }
}

TEST_CASE("outbound records and the recorder's STATE") {
    TempDir dir;
    boost::asio::io_context io;
    gimbald::record::Recorder recorder(io, options_for(dir.path));
    const std::string request = R"({"cmd":"state","id":"a"})";
    recorder.record(1, gimbald::record::Direction::inbound, "gimbald-json", request);
    recorder.record(1, gimbald::record::Direction::outbound, "gimbald-json", "{\"ok\":true}");
    recorder.stop();
    const auto state = recorder.snapshot();
    CHECK(state["dropped"] == 0);
    CHECK(fs::path(state["file"].get<std::string>()).parent_path() == dir.path);
    CHECK(state["bytes"].get<std::uint64_t>() == fs::file_size(state["file"].get<std::string>()));
    std::size_t interfaces = 0;
    const auto records = read_records(state["file"].get<std::string>(), &interfaces);
    CHECK(interfaces == 2);
    REQUIRE(records.size() == 2);
    CHECK(std::string(records[0].pdu.begin(), records[0].pdu.end()) == request);
    CHECK(records[0].flags == 1);
    CHECK(records[1].flags == 2);
}

TEST_CASE("a full buffer drops and counts instead of blocking") {
    TempDir dir;
    boost::asio::io_context io;
    auto options = options_for(dir.path);
    options.buffer_bytes = 1000;
    gimbald::record::Recorder recorder(io, options);
    const Bytes pdu(100, 0x55);
    for (int i = 0; i < 100; ++i)
        recorder.record(0, gimbald::record::Direction::inbound, "orion", pdu);
    recorder.stop();
    const auto records = read_records(recorder.snapshot()["file"].get<std::string>());
    CHECK(recorder.dropped() > 0);
    CHECK(records.size() + recorder.dropped() == 100);
}

TEST_CASE("files rotate at max_file_bytes and the oldest go past max_total_bytes") {
    TempDir dir;
    gimbal::record::Interface iface{"gimbal:main", "orion test"};
    gimbald::record::RecordFilesOptions options;
    options.dir = dir.path;
    options.header = gimbal::record::file_header("gimbald test", std::span(&iface, 1));
    options.max_file_bytes = 1000;
    options.max_total_bytes = 3000;
    // A stranger's file in the directory is never deleted.
    std::ofstream(dir.path / "notes.txt") << "keep";
    gimbald::record::RecordFiles files(options);
    REQUIRE(files.open_first(1764072000).empty());
    Bytes blocks;
    const Bytes pdu(60, 0xAA);
    const std::size_t block = gimbal::record::packet_block_size("orion", pdu.size());
    for (int i = 0; i < 100; ++i)
        gimbal::record::append_packet(blocks, {0, static_cast<std::uint64_t>(i),
                                               gimbal::record::Direction::inbound, "orion", pdu});
    for (std::size_t at = 0; at < blocks.size();) {  // chunks of 10 blocks
        const std::size_t n = std::min<std::size_t>(10 * block, blocks.size() - at);
        CHECK(files.write(std::span(blocks).subspan(at, n), 1764072000) == 0);
        at += n;
    }
    files.close();
    auto all = recordings(dir.path);
    CHECK(std::find(all.begin(), all.end(), dir.path / "notes.txt") != all.end());
    all.erase(std::remove(all.begin(), all.end(), dir.path / "notes.txt"), all.end());
    std::uint64_t total = 0;
    std::size_t packets = 0;
    for (const auto& f : all) {
        CHECK(gimbald::record::is_recording_file_name(f.filename().string()));
        CHECK(fs::file_size(f) <= 1000);
        total += fs::file_size(f);
        std::size_t interfaces = 0;
        packets += read_records(f, &interfaces).size();
        CHECK(interfaces == 1);
    }
    CHECK(total <= 3000);
    CHECK(files.files_deleted() > 0);
    CHECK(all.back().filename().string().starts_with("gimbald-20251125T120000Z-"));
    CHECK(packets < 100);
    CHECK(all.size() >= 2);
}

TEST_CASE("a nearly full disk keeps every whole block that fits, and cuts none") {
    // The limit (ulimit -f, a full disk's stand-in) falls inside the sixth block of one chunk
    // of ten: the five before it are kept, the sixth is cut off, five are counted as lost.
    TempDir dir;
    gimbal::record::Interface iface{"gimbal:main", "orion test"};
    gimbald::record::RecordFilesOptions options;
    options.dir = dir.path;
    options.header = gimbal::record::file_header("gimbald test", std::span(&iface, 1));
    Bytes blocks;
    const Bytes pdu(200, 0x5A);
    const std::size_t block = gimbal::record::packet_block_size("orion", pdu.size());
    for (int i = 0; i < 10; ++i)
        gimbal::record::append_packet(blocks, {0, static_cast<std::uint64_t>(i),
                                               gimbal::record::Direction::inbound, "orion", pdu});
    const std::size_t limit = options.header.size() + 5 * block + block / 2;
    // The limit applies to a child process only, so the test runner keeps writing freely.
    const pid_t child = ::fork();
    REQUIRE(child >= 0);
    if (child == 0) {
        std::signal(SIGXFSZ, SIG_IGN);
        const rlimit rl{limit, limit};
        ::setrlimit(RLIMIT_FSIZE, &rl);
        gimbald::record::RecordFiles files(options);
        if (!files.open_first(1764072000).empty()) ::_exit(99);
        const auto lost = files.write(blocks, 1764072000);
        files.close();
        ::_exit(static_cast<int>(std::min<std::uint64_t>(lost, 98)));
    }
    int status = 0;
    REQUIRE(::waitpid(child, &status, 0) == child);
    REQUIRE(WIFEXITED(status));
    CHECK(WEXITSTATUS(status) == 5);
    const auto files = recordings(dir.path);
    REQUIRE(files.size() == 1);
    CHECK(fs::file_size(files[0]) == options.header.size() + 5 * block);
    CHECK(read_records(files[0]).size() == 5);
}

TEST_CASE("recording file names sort by time and are recognised") {
    using gimbald::record::is_recording_file_name;
    using gimbald::record::recording_file_name;
    CHECK(recording_file_name(1764072000, 1) == "gimbald-20251125T120000Z-0001.pcapng");
    CHECK(recording_file_name(1764072000, 12345) == "gimbald-20251125T120000Z-12345.pcapng");
    CHECK(recording_file_name(1764072000, 2) < recording_file_name(1764072001, 1));
    CHECK(is_recording_file_name("gimbald-20251125T120000Z-0001.pcapng"));
    CHECK_FALSE(is_recording_file_name("gimbald-20251125T120000Z-001.pcapng"));
    CHECK_FALSE(is_recording_file_name("gimbald-2025112XT120000Z-0001.pcapng"));
    CHECK_FALSE(is_recording_file_name("other.pcapng"));
}
