// Opening, creating and closing files; groups and links.
#include "file.hpp"

#include <hdf5.h>

#include <cstring>
#include <type_traits>
#include <utility>
#include <vector>

#include "access.hpp"
#include "errors.hpp"
#include "handle.hpp"

namespace mocapdb::store::h5 {

static_assert(std::is_same_v<hid_t, std::int64_t>, "file.hpp stores hid_t values as std::int64_t");

namespace {

// Format: superblock 2 and object header 2 (metadata checksums; readable by HDF5 1.8 and later).
Handle file_access(const std::string& file) {
    Handle fapl(check(H5Pcreate(H5P_FILE_ACCESS), file, "", "cannot create a file access property list"), H5Pclose);
    check(H5Pset_libver_bounds(fapl.get(), H5F_LIBVER_V18, H5F_LIBVER_V18), file, "", "cannot set format bounds");
    // Weak: HDF5 opens the target of an external link (a segment) with the weak close degree and
    // refuses to open a file twice with different degrees, and one file can be both (a writing
    // session's segment; an older file adopted as a segment while it is still the target). Every
    // identifier is closed by its Handle, and close() flushes before closing.
    check(H5Pset_fclose_degree(fapl.get(), H5F_CLOSE_WEAK), file, "", "cannot set the close degree");
    // Segments reached through external links stay open until the index closes (each attribute read
    // would otherwise open and close its segment).
    check(H5Pset_elink_file_cache_size(fapl.get(), 64), file, "", "cannot set the external file cache");
    return fapl;
}

hid_t make_access(hid_t cls) {
    const hid_t id = H5Pcreate(cls);
    if (id < 0 || H5Pset_elink_acc_flags(id, H5F_ACC_RDONLY) < 0)
        fail_call("", "", "cannot create a link access property list");
    return id;
}

std::vector<std::string> split_path(const std::string& path) {
    std::vector<std::string> parts;
    std::size_t start = 0;
    while (start < path.size()) {
        std::size_t end = path.find('/', start);
        if (end == std::string::npos) end = path.size();
        if (end > start) parts.push_back(path.substr(start, end - start));
        start = end + 1;
    }
    return parts;
}

}  // namespace

hid_t link_access() {
    static const hid_t id = make_access(H5P_LINK_ACCESS);
    return id;
}
hid_t dataset_access() {
    static const hid_t id = make_access(H5P_DATASET_ACCESS);
    return id;
}
hid_t group_access() {
    static const hid_t id = make_access(H5P_GROUP_ACCESS);
    return id;
}

File::~File() {
    if (id_ >= 0) H5Fclose(id_);
}

File::File(File&& other) noexcept
    : id_(std::exchange(other.id_, -1)), name_(std::move(other.name_)), writable_(other.writable_) {}

File& File::operator=(File&& other) noexcept {
    if (this != &other) {
        if (id_ >= 0) H5Fclose(id_);
        id_ = std::exchange(other.id_, -1);
        name_ = std::move(other.name_);
        writable_ = other.writable_;
    }
    return *this;
}

File File::open(const std::filesystem::path& path, bool writable) {
    File f;
    f.name_ = path.string();
    f.writable_ = writable;
    Handle fapl = file_access(f.name_);
    const hid_t id = H5Fopen(f.name_.c_str(), writable ? H5F_ACC_RDWR : H5F_ACC_RDONLY, fapl.get());
    if (id < 0) fail_call(f.name_, "", "cannot open as an HDF5 file");
    f.id_ = id;
    return f;
}

File File::create(const std::filesystem::path& path) {
    File f;
    f.name_ = path.string();
    f.writable_ = true;
    Handle fapl = file_access(f.name_);
    const hid_t id = H5Fcreate(f.name_.c_str(), H5F_ACC_EXCL, H5P_DEFAULT, fapl.get());
    if (id < 0) fail_call(f.name_, "", "cannot create the HDF5 file");
    f.id_ = id;
    return f;
}

void File::close() {
    if (id_ < 0) return;
    if (writable_) check(H5Fflush(id_, H5F_SCOPE_LOCAL), name_, "", "cannot flush the file");
    const herr_t closed = H5Fclose(std::exchange(id_, -1));
    if (closed < 0) fail_call(name_, "", "cannot close the file");
}

std::uint64_t File::size() const {
    hsize_t bytes = 0;
    check(H5Fget_filesize(id_, &bytes), name_, "", "cannot get the file size");
    return bytes;
}

namespace {

herr_t collect_link_name(hid_t /*group*/, const char* name, const H5L_info_t* /*info*/, void* data) {
    static_cast<std::vector<std::string>*>(data)->emplace_back(name);
    return 0;
}

}  // namespace

ObjectType File::type_of(const std::string& path) const {
    if (path == "/") return ObjectType::Group;
    std::string prefix;
    for (const std::string& part : split_path(path)) {
        prefix += "/" + part;
        const htri_t e = H5Lexists(id_, prefix.c_str(), link_access());
        if (e < 0) fail_call(name_, prefix, "cannot look up the link");
        if (e == 0) return ObjectType::None;
    }
    // A dangling soft link exists as a link but not as an object.
    const htri_t target = H5Oexists_by_name(id_, path.c_str(), link_access());
    if (target <= 0) {
        H5Eclear2(H5E_DEFAULT);
        return ObjectType::Other;
    }
    Handle obj(open_object(path), H5Oclose);
    switch (H5Iget_type(obj.get())) {
        case H5I_GROUP: return ObjectType::Group;
        case H5I_DATASET: return ObjectType::Dataset;
        default: return ObjectType::Other;
    }
}

bool File::link_exists(const std::string& path) const {
    std::string prefix;
    for (const std::string& part : split_path(path)) {
        prefix += "/" + part;
        const htri_t e = H5Lexists(id_, prefix.c_str(), link_access());
        if (e < 0) fail_call(name_, prefix, "cannot look up the link");
        if (e == 0) return false;
    }
    return true;
}

File::Id File::open_object(const std::string& path) const {
    const hid_t id = H5Oopen(id_, path.c_str(), link_access());
    if (id < 0) fail_call(name_, path, "cannot open the object");
    return id;
}

namespace {

// How the store creates groups. Keep attributes in the object header (compact) up to 32 of them
// instead of HDF5's default 8: H5Ocopy (copy_to, used to compact the file at commit) of a group whose
// variable-length string attributes are in dense storage crashes in HDF5 1.10 (H5T__conv_vlen). A
// model group has 12.
Handle group_creation(const std::string& file, const std::string& path) {
    Handle gcpl(check(H5Pcreate(H5P_GROUP_CREATE), file, path, "cannot create a group property list"), H5Pclose);
    check(H5Pset_obj_track_times(gcpl.get(), 0), file, path, "cannot disable time tracking");
    check(H5Pset_attr_phase_change(gcpl.get(), 32, 24), file, path, "cannot set the attribute storage");
    return gcpl;
}

}  // namespace

void File::create_group(const std::string& path, const std::string& kind) {
    const Handle gcpl = group_creation(name_, path);
    Handle g(check(H5Gcreate2(id_, path.c_str(), H5P_DEFAULT, gcpl.get(), H5P_DEFAULT), name_, path,
                   "cannot create the group"),
             H5Gclose);
    g.reset();
    write_string_attribute(path, "kind", kind);
}

void File::unlink(const std::string& path) {
    check(H5Ldelete(id_, path.c_str(), H5P_DEFAULT), name_, path, "cannot remove the link");
}

std::vector<std::string> File::children(const std::string& group) const {
    Handle g(check(H5Gopen2(id_, group.c_str(), group_access()), name_, group, "cannot open the group"), H5Gclose);
    H5G_info_t info;
    check(H5Gget_info(g.get(), &info), name_, group, "cannot read the group's links");
    std::vector<std::string> names;
    names.reserve(info.nlinks);
    // One iteration: H5Lget_name_by_idx on a group with dense link storage (more than 8 links) builds
    // and sorts the whole link table on every call, O(n^2 log n) for n links (3 000 clips: seconds).
    hsize_t idx = 0;
    check(H5Literate(g.get(), H5_INDEX_NAME, H5_ITER_INC, &idx, collect_link_name, &names), name_, group,
          "cannot read the group's link names");
    return names;
}

void File::copy_to(File& destination, const std::string& path) const {
    // Opened first, so that an object in a segment is reached read-only (link_access); H5Ocopy's own
    // lookup would open the segment with this file's intent.
    Handle obj(open_object(path), H5Oclose);
    check(H5Ocopy(obj.get(), ".", destination.id_, path.c_str(), H5P_DEFAULT, H5P_DEFAULT), name_, path,
          ("cannot copy the object to " + destination.name_).c_str());
}

namespace {

// Copies one attribute (any type, variable-length strings included) of the object `loc` to the
// object `destination`; -1 when HDF5 fails.
herr_t copy_attribute_or_throw(hid_t loc, const char* name, hid_t destination) {
    Handle a(H5Aopen(loc, name, H5P_DEFAULT), H5Aclose);
    if (!a.valid()) return -1;
    Handle type(H5Aget_type(a.get()), H5Tclose);
    Handle space(H5Aget_space(a.get()), H5Sclose);
    if (!type.valid() || !space.valid()) return -1;
    const hssize_t points = H5Sget_select_npoints(space.get());
    const std::size_t size = H5Tget_size(type.get());
    if (points < 0 || size == 0) return -1;
    std::vector<unsigned char> buffer(static_cast<std::size_t>(points) * size + 1);
    if (H5Aread(a.get(), type.get(), buffer.data()) < 0) return -1;
    const bool variable = H5Tis_variable_str(type.get()) > 0 || H5Tdetect_class(type.get(), H5T_VLEN) > 0;
    Handle out(H5Acreate2(destination, name, type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
    const bool written = out.valid() && H5Awrite(out.get(), type.get(), buffer.data()) >= 0;
    if (variable) H5Dvlen_reclaim(type.get(), space.get(), H5P_DEFAULT, buffer.data());
    return written ? 0 : -1;
}

// H5Aiterate callback (`data`: the destination's identifier): no exception crosses HDF5's C frames.
herr_t copy_attribute(hid_t loc, const char* name, const H5A_info_t* /*info*/, void* data) noexcept {
    try {
        return copy_attribute_or_throw(loc, name, *static_cast<const hid_t*>(data));
    } catch (...) {
        return -1;
    }
}

}  // namespace

void File::copy_to_except(File& destination, const std::string& path, const std::vector<std::string>& skipped) const {
    bool above_skipped = false;
    for (const std::string& s : skipped) {
        if (s == path) return;
        if (s.size() > path.size() && s.compare(0, path.size(), path) == 0 && s[path.size()] == '/')
            above_skipped = true;
    }
    if (!above_skipped) {
        copy_to(destination, path);
        return;
    }
    // (Not the source's creation properties: HDF5 1.10 then fails to copy objects into the new group.)
    Handle source(check(H5Gopen2(id_, path.c_str(), group_access()), name_, path, "cannot open the group"), H5Gclose);
    const Handle gcpl = group_creation(destination.name_, path);
    Handle group(check(H5Gcreate2(destination.id_, path.c_str(), H5P_DEFAULT, gcpl.get(), H5P_DEFAULT),
                       destination.name_, path, "cannot create the group"),
                 H5Gclose);
    hsize_t idx = 0;
    hid_t target = group.get();
    check(H5Aiterate2(source.get(), H5_INDEX_NAME, H5_ITER_INC, &idx, copy_attribute, &target), name_, path,
          ("cannot copy the group's attributes to " + destination.name_).c_str());
    group.reset();
    source.reset();
    for (const std::string& child : children(path)) copy_to_except(destination, path + "/" + child, skipped);
}

}  // namespace mocapdb::store::h5

namespace mocapdb::store::h5 {

void File::link_external(const std::string& path, const std::string& file, const std::string& target) {
    check(H5Lcreate_external(file.c_str(), target.c_str(), id_, path.c_str(), H5P_DEFAULT, H5P_DEFAULT), name_, path,
          ("cannot create the external link to " + file + ":" + target).c_str());
}

std::optional<std::pair<std::string, std::string>> File::external_target(const std::string& path) const {
    const htri_t e = H5Lexists(id_, path.c_str(), link_access());
    if (e < 0) fail_call(name_, path, "cannot look up the link");
    if (e == 0) return std::nullopt;
    H5L_info_t info;
    check(H5Lget_info(id_, path.c_str(), &info, link_access()), name_, path, "cannot read the link");
    if (info.type != H5L_TYPE_EXTERNAL) return std::nullopt;
    std::vector<char> value(info.u.val_size);
    check(H5Lget_val(id_, path.c_str(), value.data(), value.size(), link_access()), name_, path,
          "cannot read the external link");
    unsigned flags = 0;
    const char* file = nullptr;
    const char* object = nullptr;
    check(H5Lunpack_elink_val(value.data(), value.size(), &flags, &file, &object), name_, path,
          "cannot decode the external link");
    return std::make_pair(std::string(file), std::string(object));
}

std::filesystem::path File::file_holding(const std::string& path) const {
    Handle obj(open_object(path), H5Oclose);
    const ssize_t n = H5Fget_name(obj.get(), nullptr, 0);
    if (n < 0) fail_call(name_, path, "cannot get the name of the file holding the object");
    std::string name(static_cast<std::size_t>(n) + 1, '\0');
    check(H5Fget_name(obj.get(), name.data(), name.size()), name_, path,
          "cannot get the name of the file holding the object");
    name.resize(static_cast<std::size_t>(n));
    return name;
}

std::uint64_t File::object_file_bytes(const std::string& path) const {
    Handle obj(open_object(path), H5Oclose);
    H5O_info_t info;
    check(H5Oget_info2(obj.get(), &info, H5O_INFO_HDR | H5O_INFO_META_SIZE), name_, path,
          "cannot read the object's storage");
    std::uint64_t bytes = info.hdr.space.total + info.meta_size.obj.index_size + info.meta_size.obj.heap_size +
                          info.meta_size.attr.index_size + info.meta_size.attr.heap_size;
    if (H5Iget_type(obj.get()) == H5I_DATASET) bytes += H5Dget_storage_size(obj.get());
    const Attributes a = read_attributes(path);
    auto heap_object = [](const std::string& text) { return 16u + (text.size() + 7u) / 8u * 8u; };
    for (const auto& [name, text] : a.strings) bytes += heap_object(text);
    for (const auto& [name, list] : a.string_lists)
        for (const std::string& text : list) bytes += heap_object(text);
    return bytes;
}

}  // namespace mocapdb::store::h5
