#include "mocapdb/io/clip_file.hpp"

#include <algorithm>
#include <cctype>

#include "mocapdb/core/error.hpp"
#include "mocapdb/io/asf_amc.hpp"
#include "mocapdb/io/bvh.hpp"

namespace mocapdb {

std::optional<ClipFormat> clip_format_of(const std::filesystem::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    if (ext == ".bvh") return ClipFormat::Bvh;
    if (ext == ".amc") return ClipFormat::Amc;
    return std::nullopt;
}

Clip read_clip(const std::filesystem::path& path, const ClipReadOptions& options, Warnings* out_warnings) {
    const auto format = clip_format_of(path);
    if (!format)
        throw InvalidArgument(path.string() + ": unsupported file type '" + path.extension().string() +
                              "' (expected .bvh or .amc)");
    if (*format == ClipFormat::Bvh) {
        BvhReadOptions o;
        o.strict = options.strict;
        o.frame_rate = options.frame_rate;
        o.position_channels = options.bvh_positions;
        return read_bvh(path, o, out_warnings);
    }
    std::filesystem::path asf = options.asf;
    if (asf.empty()) {
        const auto found = find_asf_for_amc(path);
        if (!found)
            throw InvalidArgument(path.string() +
                                  ": no skeleton given and none found beside it by the CMU naming "
                                  "(NN_MM.amc -> NN.asf); pass the ASF file");
        asf = *found;
    }
    AmcReadOptions o;
    o.strict = options.strict;
    if (options.frame_rate) o.frame_rate = *options.frame_rate;
    return read_amc(path, read_asf(asf), o, out_warnings);
}

}  // namespace mocapdb
