// libFuzzer target for the pcapng recording reader: any bytes are read to their stop without
// reading outside the input, and the properties of record_properties.hpp hold. Any crash,
// sanitizer report or broken property aborts.
#include <cstdio>
#include <cstdlib>

#include "record_properties.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string broken = gimbal::fuzz::check_record_reader({data, size});
    if (!broken.empty()) {
        std::fprintf(stderr, "fuzz_record_reader: %s\n", broken.c_str());
        std::abort();
    }
    return 0;
}
