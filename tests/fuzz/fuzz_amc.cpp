// libFuzzer target: the AMC reader, against a fixed small skeleton, must throw ParseError (or
// succeed) on any input, never crash.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string_view>

#include "mocapdb/core/error.hpp"
#include "mocapdb/io/asf_amc.hpp"

namespace {
const char* kSkeleton =
    ":version 1.10\n:name fuzz\n:units\n  mass 1.0\n  length 0.45\n  angle deg\n"
    ":root\n  order TX TY TZ RX RY RZ\n  axis XYZ\n  position 0 0 0\n  orientation 0 0 0\n"
    ":bonedata\n"
    "  begin\n    id 1\n    name lfemur\n    direction 0 -1 0\n    length 7\n    axis 0 0 20 XYZ\n"
    "    dof rx ry rz\n    limits (-160 20)\n      (-70 70)\n      (-60 70)\n  end\n"
    "  begin\n    id 2\n    name ltibia\n    direction 0 -1 0\n    length 7\n    axis 0 0 20 XYZ\n"
    "    dof rx\n    limits (-10 170)\n  end\n"
    ":hierarchy\n  begin\n    root lfemur\n    lfemur ltibia\n  end\n";
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static const auto skeleton = std::make_shared<const mocapdb::Skeleton>(mocapdb::parse_asf(kSkeleton, "fuzz.asf"));
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    for (bool strict : {false, true}) {
        mocapdb::AmcReadOptions options;
        options.strict = strict;
        try {
            mocapdb::Warnings warnings;
            (void)mocapdb::parse_amc(text, "fuzz.amc", skeleton, options, &warnings);
        } catch (const mocapdb::Error&) {
        }
    }
    return 0;
}
