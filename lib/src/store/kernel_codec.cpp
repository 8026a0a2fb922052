#include "kernel_codec.hpp"

#include <cinttypes>
#include <cmath>
#include <cstdio>

#include "layout.hpp"
#include "mocapdb/core/error.hpp"
#include "mocapdb/store/store_error.hpp"

namespace mocapdb::store {
namespace {

const char* const kParameters[] = {"exponent", "nugget", "sill", "range"};

double* parameter(kriging::VariogramModel& m, int k) {
    switch (k) {
        case 0: return &m.exponent;
        case 1: return &m.nugget;
        case 2: return &m.sill;
        default: return &m.range;
    }
}

std::string key_text(std::uint64_t key) {
    char buf[20];
    std::snprintf(buf, sizeof buf, "%016" PRIx64, key);
    return buf;
}

// The variogram's constraints; the violated one as text, or "" when they hold.
std::string violation(const synthesis::KernelFit& fit) {
    try {
        fit.variogram.validate();
    } catch (const InvalidArgument& e) {
        return e.what();
    }
    if (!std::isfinite(fit.variogram.exponent)) return "the exponent must be finite";
    if (!(fit.variogram.total_sill() > 0.0)) return "nugget + sill must be > 0";
    return "";
}

}  // namespace

void check_kernel_fit(const synthesis::KernelFit& fit, const std::string& who) {
    if (fit.key == 0) throw InvalidArgument(who + ": the kernel fit has no key (0)");
    const std::string v = violation(fit);
    if (!v.empty()) throw InvalidArgument(who + ": " + v);
}

void write_kernel_fit(h5::File& file, const std::string& set, const synthesis::KernelFit& fit) {
    const std::string g = kernel_path(set);
    file.create_group(g, "kernel_fit");
    file.write_string_attribute(g, "key", key_text(fit.key));
    file.write_string_attribute(g, "family", kriging::to_string(fit.variogram.family));
    kriging::VariogramModel m = fit.variogram;
    for (int k = 0; k < 4; ++k) file.write_double_attribute(g, kParameters[k], *parameter(m, k));
}

synthesis::KernelFit read_kernel_fit(const h5::File& file, const std::string& set) {
    const std::string g = kernel_path(set);
    synthesis::KernelFit fit;
    const std::string key = file.read_string_attribute(g, "key");
    bool hex = key.size() == 16;
    for (const char c : key) hex = hex && ((c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'));
    if (!hex)
        throw StoreError(file.name(), g, "attribute 'key': expected 16 lowercase hexadecimal digits, found \"" + key + "\"");
    fit.key = std::strtoull(key.c_str(), nullptr, 16);
    if (fit.key == 0) throw StoreError(file.name(), g, "attribute 'key': expected a non-zero digest, found \"" + key + "\"");
    const std::string family = file.read_string_attribute(g, "family");
    if (family == kriging::to_string(kriging::VariogramFamily::Spherical))
        fit.variogram.family = kriging::VariogramFamily::Spherical;
    else if (family == kriging::to_string(kriging::VariogramFamily::Stable))
        fit.variogram.family = kriging::VariogramFamily::Stable;
    else
        throw StoreError(file.name(), g, "attribute 'family': expected \"sph\" or \"stable\", found \"" + family + "\"");
    for (int k = 0; k < 4; ++k) *parameter(fit.variogram, k) = file.read_double_attribute(g, kParameters[k]);
    const std::string v = violation(fit);
    if (!v.empty()) throw StoreError(file.name(), g, v);
    return fit;
}

}  // namespace mocapdb::store
