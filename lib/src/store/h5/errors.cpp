#include "errors.hpp"

#include <algorithm>
#include <cctype>
#include <type_traits>
#include <vector>

#include "quiet.hpp"

#include "mocapdb/store/store_error.hpp"

namespace mocapdb::store::h5 {
namespace {

herr_t collect(unsigned /*n*/, const H5E_error2_t* err, void* data) {
    auto* out = static_cast<std::vector<std::string>*>(data);
    if (err != nullptr && err->desc != nullptr && err->desc[0] != '\0') out->emplace_back(err->desc);
    return 0;
}

bool mentions_checksum(const std::string& text) {
    std::string lower(text);
    std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
    return lower.find("fletcher32") != std::string::npos || lower.find("checksum") != std::string::npos;
}

}  // namespace

static_assert(std::is_same_v<H5E_auto2_t, QuietScope::Handler>, "QuietScope stores an H5E_auto2_t");

QuietScope::QuietScope() {
    if (H5Eget_auto2(H5E_DEFAULT, &old_func_, &old_data_) >= 0) saved_ = true;
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
}

QuietScope::~QuietScope() {
    if (saved_) H5Eset_auto2(H5E_DEFAULT, old_func_, old_data_);
}

std::string take_error_stack() {
    std::vector<std::string> messages;
    H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, collect, &messages);
    H5Eclear2(H5E_DEFAULT);
    // Most specific first; drop repeats, keep it to one readable line.
    std::string out;
    std::vector<std::string> seen;
    for (const std::string& m : messages) {
        if (std::find(seen.begin(), seen.end(), m) != seen.end()) continue;
        seen.push_back(m);
        if (seen.size() > 3) break;
        if (!out.empty()) out += "; ";
        out += m;
    }
    return out;
}

void fail_call(const std::string& file, const std::string& path, const std::string& what) {
    const std::string stack = take_error_stack();
    if (mentions_checksum(stack))
        throw ChecksumError(
            file, path,
            "checksum mismatch in dataset " + path + " (the stored bytes are corrupted; HDF5: " + stack + ")");
    throw StoreError(file, path, stack.empty() ? what : what + " (HDF5: " + stack + ")");
}

void fail(const std::string& file, const std::string& path, const std::string& message) {
    throw StoreError(file, path, message);
}

}  // namespace mocapdb::store::h5
