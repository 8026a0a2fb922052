#pragma once
// The page's own files, compiled into the binary from serve/web/ (cmake/embed_assets.cmake), so that
// `mocapdb serve` needs nothing beside it but Debian's three.js.
#include <cstddef>
#include <vector>

namespace mocapdb::serve {

struct EmbeddedAsset {
    const char* name;  ///< file name under serve/web/ ("index.html")
    const char* content_type;
    const char* data;
    std::size_t size;
};

const std::vector<EmbeddedAsset>& embedded_assets();

}  // namespace mocapdb::serve
