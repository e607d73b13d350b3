#include "record/interface_scan.hpp"

namespace gimbal::record {

bool scan_interfaces(std::span<const std::uint8_t> file,
                     const std::function<void(const RecordedInterface&)>& visit,
                     std::string& error) {
    PcapngReader reader(file);
    RecordedPacket p;
    std::size_t section = 0, seen = 0;  // interfaces of this section already visited
    auto collect = [&] {
        if (reader.sections() != section) {  // a new section declares its interfaces anew
            section = reader.sections();
            seen = 0;
        }
        const auto& interfaces = reader.interfaces();
        for (; seen < interfaces.size(); ++seen) visit(interfaces[seen]);
    };
    while (reader.next(p)) collect();
    collect();  // interfaces of a section without packets
    if (reader.sections() == 0) {
        error = reader.stop() == Stop::truncated
                    ? "empty or cut-short file (" + reader.stop_message() + ")"
                    : reader.stop_message();
        return false;
    }
    return true;
}

}  // namespace gimbal::record
