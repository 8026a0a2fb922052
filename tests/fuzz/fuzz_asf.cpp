// libFuzzer target: the ASF reader must throw ParseError (or succeed) on any input, never crash.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "mocapdb/core/error.hpp"
#include "mocapdb/io/asf_amc.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    try {
        (void)mocapdb::parse_asf(text, "fuzz.asf");
    } catch (const mocapdb::Error&) {
    }
    return 0;
}
