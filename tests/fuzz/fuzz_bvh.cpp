// libFuzzer target: the BVH reader must throw ParseError (or succeed) on any input, never crash.
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string_view>

#include "mocapdb/core/error.hpp"
#include "mocapdb/io/bvh.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    for (bool strict : {false, true}) {
        mocapdb::BvhReadOptions options;
        options.strict = strict;
        try {
            mocapdb::Warnings warnings;
            const mocapdb::Clip clip = mocapdb::parse_bvh(text, "fuzz.bvh", options, &warnings);
            // Whatever parses must also write and read back.
            std::ostringstream out;
            if (clip.frame_rate > 0 && clip.frame_rate < 1e9) {
                mocapdb::write_bvh(out, clip);
                (void)mocapdb::parse_bvh(out.str(), "fuzz-written.bvh");
            }
        } catch (const mocapdb::Error&) {
        }
    }
    return 0;
}
