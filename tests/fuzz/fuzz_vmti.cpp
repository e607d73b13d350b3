// libFuzzer target for lib/klv/vmti (MISB ST 0903 VMTI local set, ST 0601 tag 74): any bytes
// are decoded as a VMTI set, and as the value of tag 74 in an ST 0601 set. Properties:
//  - decode_vmti() either refuses with a "VMTI: " reason or gives a set whose JSON can be
//    written;
//  - a decoded set encodes, and decodes again to the same set (decoded -> encode -> decode is
//    stable), byte for byte on a second round;
//  - ST 0601 decode() shows tag 74 either as "vmti" or as "vmti_local_set" with "vmti_error".
// Any crash, sanitizer report or broken property aborts.
#include <cstdio>
#include <cstdlib>

#include "klv/local_set.hpp"
#include "klv/vmti.hpp"

namespace klv = gimbal::klv;

namespace {

[[noreturn]] void fail(const char* what) {
    std::fprintf(stderr, "fuzz_vmti: %s\n", what);
    std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::span<const std::uint8_t> input(data, size);
    const auto decoded = klv::decode_vmti(input);
    if (!decoded.ok()) {
        if (decoded.error().message.rfind("VMTI: ", 0) != 0) fail("a refusal without its reason");
    } else {
        (void)klv::vmti_json(*decoded).dump();
        const auto encoded = klv::encode_vmti(*decoded);
        if (!encoded.ok()) fail("a decoded set does not encode");
        const auto again = klv::decode_vmti(*encoded);
        if (!again.ok()) fail("an encoded set does not decode");
        if (!(*again == *decoded)) fail("a set decodes to other values after a round trip");
        const auto twice = klv::encode_vmti(*again);
        if (!twice.ok() || *twice != *encoded) fail("a second round trip changes the bytes");
    }
    if (size <= 1024) {
        klv::LocalSet set;
        set.add(74, klv::Bytes(input.begin(), input.end()));
        const klv::Encoded e = klv::encode(set);
        if (!e.ok()) fail("an ST 0601 set with tag 74 does not encode");
        const klv::DecodeResult r = klv::decode(e.value());
        if (!r.ok()) fail("an ST 0601 set with tag 74 does not decode");
        (void)r.json.dump();
        const bool as_vmti = r.json.contains("vmti");
        const bool as_hex = r.json.contains("vmti_local_set") && r.json.contains("vmti_error");
        if (as_vmti == as_hex) fail("tag 74 is neither decoded nor kept as hex");
        if (as_vmti != (decoded.ok() || size == 0)) fail("tag 74 decodes unlike decode_vmti");
    }
    return 0;
}
