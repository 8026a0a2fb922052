#include "root.hpp"

#include "layout.hpp"
#include "mocapdb/core/version.hpp"
#include "mocapdb/store/database.hpp"
#include "mocapdb/store/store_error.hpp"

namespace mocapdb::store {

void write_root_attributes(h5::File& file) {
    file.write_string_attribute("/", "format", "mocapdb");
    file.write_int_attribute("/", "format_version", kDatabaseFormatVersion);
    file.write_string_attribute("/", "kind", "database");
    file.write_string_attribute("/", "creator", creator_string);
}

void write_root(h5::File& file) {
    write_root_attributes(file);
    file.create_group(kSkeletons, "skeletons");
    file.create_group(kClips, "clips");
    file.create_group(kSets, "sets");
}

void write_segment_root(h5::File& file) {
    file.write_string_attribute("/", "format", "mocapdb");
    file.write_int_attribute("/", "format_version", kDatabaseFormatVersion);
    file.write_string_attribute("/", "kind", "segment");
    file.write_string_attribute("/", "creator", creator_string);
    file.create_group(kSkeletons, "skeletons");
    file.create_group(kClips, "clips");
    file.create_group(kSets, "sets");
}

void upgrade_root(h5::File& file) { file.write_int_attribute("/", "format_version", kDatabaseFormatVersion); }

int check_root(const h5::File& file) {
    const std::string& f = file.name();
    if (!file.has_attribute("/", "format"))
        throw StoreError(f, "/", "not a mocapdb database: root attribute 'format' is missing (expected \"mocapdb\")");
    const h5::AttributeInfo info = file.attribute_info("/", "format");
    if (info.dtype != "string" || !info.shape.empty())
        throw StoreError(f, "/",
                         "not a mocapdb database: root attribute 'format' is " + info.dtype + " " +
                             h5::shape_text(info.shape) + " (expected the string \"mocapdb\")");
    const std::string format = file.read_string_attribute("/", "format");
    if (format != "mocapdb")
        throw StoreError(
            f, "/", "not a mocapdb database: root attribute 'format' is \"" + format + "\" (expected \"mocapdb\")");
    if (!file.has_attribute("/", "format_version"))
        throw StoreError(f, "/",
                         "root attribute 'format_version' is missing (expected the integer " +
                             std::to_string(kDatabaseFormatVersion) + ")");
    const std::int64_t version = file.read_int_attribute("/", "format_version");
    if (version > kDatabaseFormatVersion)
        throw StoreError(f, "/",
                         "format_version is " + std::to_string(version) + ", newer than the version " +
                             std::to_string(kDatabaseFormatVersion) + " this mocapdb reads (a newer mocapdb wrote it)");
    if (version < kOldestDatabaseFormatVersion)
        throw StoreError(f, "/",
                         "format_version is " + std::to_string(version) + " (expected " +
                             std::to_string(kOldestDatabaseFormatVersion) + " to " +
                             std::to_string(kDatabaseFormatVersion) + ")");
    for (const auto& [path, kind] :
         {std::pair{kSkeletons, "skeletons"}, std::pair{kClips, "clips"}, std::pair{kSets, "sets"}}) {
        if (file.type_of(path) != h5::ObjectType::Group)
            throw StoreError(f, path, std::string("missing group (expected a group of kind '") + kind + "')");
    }
    return static_cast<int>(version);
}

}  // namespace mocapdb::store
