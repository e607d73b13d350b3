// libFuzzer target: see check_framer() in orion_properties.hpp for what it feeds and checks.
#include <cstdio>
#include <cstdlib>

#include "orion_properties.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string failure = gimbal::fuzz::check_framer({data, size});
    if (!failure.empty()) {
        std::fprintf(stderr, "fuzz_orion_framer: %s\n", failure.c_str());
        std::abort();
    }
    return 0;
}
