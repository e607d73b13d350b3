#include "signing_state.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <nlohmann/json.hpp>

#include <stdexcept>
#include "regular_file.hpp"

namespace gimbald {

using nlohmann::json;

std::optional<std::string> signing_state_path(const std::optional<std::string>& configured,
                                              const char* state_directory) {
    if (configured) return configured;
    if (state_directory == nullptr || *state_directory == '\0') return std::nullopt;
    std::string dir(state_directory);
    dir = dir.substr(0, dir.find(':'));  // StateDirectory=a b gives "/var/lib/a:/var/lib/b"
    if (dir.empty()) return std::nullopt;
    return dir + "/mavlink-signing.json";
}

SigningState load_signing_state(const std::string& path) {
    // At most 256 streams of a few dozen bytes: 1 MiB is far more than a real file; a FIFO or
    // a device in its place is refused instead of hanging the start.
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0 && errno == ENOENT) return {};  // nothing saved yet
    const auto text = gimbal::daemon::read_regular_file(path, 1024 * 1024);
    if (!text) throw std::runtime_error(text.error().message);
    const json j = json::parse(*text, nullptr, false);
    const auto bad = [&path](const std::string& what) {
        return std::runtime_error(path + ": not a MAVLink signing state (" + what + ")");
    };
    if (!j.is_object() || !j.contains("streams") || !j["streams"].is_array())
        throw bad("no \"streams\" array");
    SigningState state;
    if (const auto it = j.find("local_timestamp"); it != j.end()) {
        if (!it->is_number_unsigned()) throw bad("local_timestamp");
        state.local_timestamp = it->get<std::uint64_t>();
    }
    for (const json& s : j["streams"]) {
        const auto byte = [&](const char* key) {
            if (!s.is_object() || !s.contains(key) || !s[key].is_number_unsigned() ||
                s[key].get<std::uint64_t>() > 255)
                throw bad(std::string("stream ") + key);
            return static_cast<std::uint8_t>(s[key].get<std::uint64_t>());
        };
        gimbal::mavlink::SigningStreams::Stream stream{byte("sysid"), byte("compid"),
                                                       byte("link_id"), 0};
        if (!s.contains("timestamp") || !s["timestamp"].is_number_unsigned())
            throw bad("stream timestamp");
        stream.timestamp = s["timestamp"].get<std::uint64_t>();
        state.streams.push_back(stream);
    }
    return state;
}

std::string save_signing_state(const std::string& path, const SigningState& state) {
    json streams = json::array();
    for (const auto& s : state.streams)
        streams.push_back({{"sysid", s.sysid},
                           {"compid", s.compid},
                           {"link_id", s.link_id},
                           {"timestamp", s.timestamp}});
    const std::string text =
        json{{"local_timestamp", state.local_timestamp}, {"streams", std::move(streams)}}.dump() +
        "\n";
    // A crash mid-write must leave the previous state, not half a file: write, then rename.
    const std::string tmp = path + ".tmp";
    const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
    if (fd < 0) return tmp + ": " + std::strerror(errno);
    std::size_t done = 0;
    while (done < text.size()) {
        const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            const std::string error = tmp + ": " + std::strerror(errno);
            ::close(fd);
            ::unlink(tmp.c_str());
            return error;
        }
        done += static_cast<std::size_t>(n);
    }
    ::close(fd);
    if (::rename(tmp.c_str(), path.c_str()) != 0) {
        const std::string error = path + ": " + std::strerror(errno);
        ::unlink(tmp.c_str());
        return error;
    }
    return {};
}

}  // namespace gimbald
