// The configuration reader (contract section 3; every section's fields() through the generic
// reader of lib/config) under arbitrary text. parse_config never throws; a configuration it
// accepts is written back whole by to_json and reads again to the same configuration, so
// every section's reading and writing agree.
//
// The first byte chooses the gimbals mode (the file's gimbals, or --sim's, where only their
// video sections count); the rest is the file's text.
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "config.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size == 0) return 0;
    using namespace gimbal::daemon;
    const auto mode = (data[0] & 1) != 0 ? GimbalsSection::ignored : GimbalsSection::required;
    const std::string_view text(reinterpret_cast<const char*>(data + 1), size - 1);
    const ConfigResult read = parse_config(text, mode);
    if (!read.ok()) {
        for (const auto& problem : read.problems)
            if (problem.message.empty()) std::abort();  // every problem says what is wrong
        return 0;
    }
    const auto written = to_json(read.config, true).dump();
    const ConfigResult again = parse_config(written, mode);
    if (!again.ok() || !(again.config == read.config)) std::abort();
    return 0;
}
