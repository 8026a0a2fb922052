// Attributes: scalar strings, string lists, int64 and float64 scalars and lists.
#include <hdf5.h>

#include <cstring>
#include <memory>

#include "access.hpp"
#include "errors.hpp"
#include "file.hpp"
#include "handle.hpp"
#include "types.hpp"

namespace mocapdb::store::h5 {
namespace {

herr_t collect_name(hid_t /*loc*/, const char* name, const H5A_info_t* /*info*/, void* data) {
    static_cast<std::vector<std::string>*>(data)->emplace_back(name);
    return 0;
}

Shape space_shape(hid_t space) {
    const int rank = H5Sget_simple_extent_ndims(space);
    if (rank <= 0) return {};
    std::vector<hsize_t> dims(static_cast<std::size_t>(rank));
    H5Sget_simple_extent_dims(space, dims.data(), nullptr);
    return Shape(dims.begin(), dims.end());
}

struct ReadAll {
    Attributes* out;
    std::string error;
};

herr_t read_one_or_throw(hid_t loc, const char* name, ReadAll* r);

// H5Aiterate callback: no exception may cross HDF5's C frames, so they end the iteration as an error.
herr_t read_one(hid_t loc, const char* name, const H5A_info_t* /*info*/, void* data) noexcept {
    auto* r = static_cast<ReadAll*>(data);
    try {
        return read_one_or_throw(loc, name, r);
    } catch (const std::exception& e) {
        r->error = std::string("cannot read attribute '") + name + "': " + e.what();
    } catch (...) {
        r->error = std::string("cannot read attribute '") + name + "'";
    }
    return -1;
}

herr_t read_one_or_throw(hid_t loc, const char* name, ReadAll* r) {
    Attributes& out = *r->out;
    Handle a(H5Aopen(loc, name, H5P_DEFAULT), H5Aclose);
    if (!a.valid()) {
        r->error = std::string("cannot open attribute '") + name + "'";
        return -1;
    }
    Handle type(H5Aget_type(a.get()), H5Tclose);
    Handle space(H5Aget_space(a.get()), H5Sclose);
    if (!type.valid() || !space.valid()) {
        r->error = std::string("cannot read the type of attribute '") + name + "'";
        return -1;
    }
    AttributeInfo info;
    info.dtype = dtype_name(type.get());
    info.shape = space_shape(space.get());
    if (H5Sget_simple_extent_type(space.get()) == H5S_NULL) info.dtype = "null";
    out.info.emplace_back(name, info);
    herr_t status = 0;
    if (info.dtype == "string" && info.shape.size() <= 1) {
        Handle mtype = vlen_string_type(H5Tget_cset(type.get()));
        std::vector<char*> buffer(info.shape.empty() ? 1 : static_cast<std::size_t>(info.shape[0]), nullptr);
        if (!buffer.empty()) status = H5Aread(a.get(), mtype.get(), buffer.data());
        if (status >= 0) {
            std::vector<std::string> values;
            values.reserve(buffer.size());
            for (char* c : buffer) values.emplace_back(c != nullptr ? c : "");
            if (!buffer.empty()) H5Dvlen_reclaim(mtype.get(), space.get(), H5P_DEFAULT, buffer.data());
            if (info.shape.empty()) out.strings.emplace_back(name, values.front());
            else out.string_lists.emplace_back(name, std::move(values));
        }
    } else if (info.dtype == "int64" && info.shape.empty()) {
        std::int64_t v = 0;
        status = H5Aread(a.get(), H5T_NATIVE_INT64, &v);
        if (status >= 0) out.ints.emplace_back(name, v);
    } else if (info.dtype == "float64" && info.shape.empty()) {
        double v = 0;
        status = H5Aread(a.get(), H5T_NATIVE_DOUBLE, &v);
        if (status >= 0) out.doubles.emplace_back(name, v);
    }
    if (status < 0) {
        r->error = std::string("cannot read attribute '") + name + "'";
        return -1;
    }
    return 0;
}

template <class V>
const V* find_value(const std::vector<std::pair<std::string, V>>& values, const std::string& name) {
    for (const auto& [n, v] : values)
        if (n == name) return &v;
    return nullptr;
}

}  // namespace

bool Attributes::has(const std::string& name) const { return find_info(name) != nullptr; }

const AttributeInfo* Attributes::find_info(const std::string& name) const { return find_value(info, name); }

Attributes File::read_attributes(const std::string& path) const {
    Attributes out;
    out.path = path;
    Handle obj(open_object(path), H5Oclose);
    switch (H5Iget_type(obj.get())) {
        case H5I_GROUP: out.type = ObjectType::Group; break;
        case H5I_DATASET: out.type = ObjectType::Dataset; break;
        default: out.type = ObjectType::Other; break;
    }
    ReadAll r{&out, {}};
    hsize_t idx = 0;
    if (H5Aiterate2(obj.get(), H5_INDEX_NAME, H5_ITER_INC, &idx, read_one, &r) < 0)
        fail_call(name_, path, r.error.empty() ? std::string("cannot list the attributes") : r.error);
    return out;
}

std::string File::string_attribute(const Attributes& a, const std::string& name) const {
    if (const std::string* v = find_value(a.strings, name)) return *v;
    const AttributeInfo* info = a.find_info(name);
    if (info == nullptr) fail(name_, a.path, "missing attribute '" + name + "'");
    fail(name_, a.path,
         "attribute '" + name + "': expected a scalar string, found " + info->dtype + " " + shape_text(info->shape));
}

std::vector<std::string> File::strings_attribute(const Attributes& a, const std::string& name) const {
    if (const auto* v = find_value(a.string_lists, name)) return *v;
    const AttributeInfo* info = a.find_info(name);
    if (info == nullptr) fail(name_, a.path, "missing attribute '" + name + "'");
    fail(name_, a.path,
         "attribute '" + name + "': expected a one-dimensional string array, found " + info->dtype + " " +
             shape_text(info->shape));
}

std::int64_t File::int_attribute(const Attributes& a, const std::string& name) const {
    if (const std::int64_t* v = find_value(a.ints, name)) return *v;
    const AttributeInfo* info = a.find_info(name);
    if (info == nullptr) fail(name_, a.path, "missing attribute '" + name + "'");
    fail(name_, a.path,
         "attribute '" + name + "': expected a scalar int64, found " + info->dtype + " " + shape_text(info->shape));
}

double File::double_attribute(const Attributes& a, const std::string& name) const {
    if (const double* v = find_value(a.doubles, name)) return *v;
    const AttributeInfo* info = a.find_info(name);
    if (info == nullptr) fail(name_, a.path, "missing attribute '" + name + "'");
    fail(name_, a.path,
         "attribute '" + name + "': expected a scalar float64, found " + info->dtype + " " + shape_text(info->shape));
}

std::vector<std::string> File::attribute_names(const std::string& path) const {
    Handle obj(open_object(path), H5Oclose);
    std::vector<std::string> names;
    hsize_t idx = 0;
    check(H5Aiterate2(obj.get(), H5_INDEX_NAME, H5_ITER_INC, &idx, collect_name, &names), name_, path,
          "cannot list the attributes");
    return names;
}

bool File::has_attribute(const std::string& path, const std::string& name) const {
    const htri_t e = H5Aexists_by_name(id_, path.c_str(), name.c_str(), link_access());
    if (e < 0) fail_call(name_, path, "cannot look up attribute '" + name + "'");
    return e > 0;
}

File::Id File::open_attribute(const std::string& path, const std::string& name) const {
    // One lookup in the common case; the existence check only to word the error. The object is
    // opened first: HDF5 1.10 reads an empty variable-length string from an attribute that
    // H5Aopen_by_name opened through an external link (the segments of format 4).
    const hid_t obj = H5Oopen(id_, path.c_str(), link_access());
    if (obj >= 0) {
        const hid_t id = H5Aopen(obj, name.c_str(), H5P_DEFAULT);
        H5Oclose(obj);
        if (id >= 0) return id;
    }
    H5Eclear2(H5E_DEFAULT);
    if (!has_attribute(path, name)) fail(name_, path, "missing attribute '" + name + "'");
    fail_call(name_, path, "cannot open attribute '" + name + "'");
}

namespace {

AttributeInfo info_of(hid_t a, const std::string& file, const std::string& path) {
    Handle type(check(H5Aget_type(a), file, path, "cannot read an attribute type"), H5Tclose);
    Handle space(check(H5Aget_space(a), file, path, "cannot read an attribute shape"), H5Sclose);
    AttributeInfo info;
    info.dtype = dtype_name(type.get());
    info.shape = space_shape(space.get());
    if (H5Sget_simple_extent_type(space.get()) == H5S_NULL) info.dtype = "null";
    return info;
}

}  // namespace

AttributeInfo File::attribute_info(const std::string& path, const std::string& name) const {
    Handle a(open_attribute(path, name), H5Aclose);
    return info_of(a.get(), name_, path);
}

std::string File::read_string_attribute(const std::string& path, const std::string& name) const {
    Handle a(open_attribute(path, name), H5Aclose);
    const AttributeInfo info = info_of(a.get(), name_, path);
    if (info.dtype != "string" || !info.shape.empty())
        fail(name_, path,
             "attribute '" + name + "': expected a scalar string, found " + info.dtype + " " + shape_text(info.shape));
    Handle ftype(H5Aget_type(a.get()), H5Tclose);
    Handle mtype = vlen_string_type(H5Tget_cset(ftype.get()));
    char* value = nullptr;
    check(H5Aread(a.get(), mtype.get(), &value), name_, path, ("cannot read attribute '" + name + "'").c_str());
    std::string out = value != nullptr ? value : "";
    Handle space(H5Aget_space(a.get()), H5Sclose);
    H5Dvlen_reclaim(mtype.get(), space.get(), H5P_DEFAULT, &value);
    return out;
}

std::vector<std::string> File::read_strings_attribute(const std::string& path, const std::string& name) const {
    Handle a(open_attribute(path, name), H5Aclose);
    const AttributeInfo info = info_of(a.get(), name_, path);
    if (info.dtype != "string" || info.shape.size() != 1)
        fail(name_, path,
             "attribute '" + name + "': expected a one-dimensional string array, found " + info.dtype + " " +
                 shape_text(info.shape));
    Handle ftype(H5Aget_type(a.get()), H5Tclose);
    Handle mtype = vlen_string_type(H5Tget_cset(ftype.get()));
    std::vector<char*> buffer(static_cast<std::size_t>(info.shape[0]), nullptr);
    if (buffer.empty()) return {};
    check(H5Aread(a.get(), mtype.get(), buffer.data()), name_, path, ("cannot read attribute '" + name + "'").c_str());
    std::vector<std::string> out;
    out.reserve(buffer.size());
    for (char* s : buffer) out.emplace_back(s != nullptr ? s : "");
    Handle space(H5Aget_space(a.get()), H5Sclose);
    H5Dvlen_reclaim(mtype.get(), space.get(), H5P_DEFAULT, buffer.data());
    return out;
}

std::int64_t File::read_int_attribute(const std::string& path, const std::string& name) const {
    Handle a(open_attribute(path, name), H5Aclose);
    const AttributeInfo info = info_of(a.get(), name_, path);
    if (info.dtype != "int64" || !info.shape.empty())
        fail(name_, path,
             "attribute '" + name + "': expected a scalar int64, found " + info.dtype + " " + shape_text(info.shape));
    std::int64_t v = 0;
    check(H5Aread(a.get(), H5T_NATIVE_INT64, &v), name_, path, ("cannot read attribute '" + name + "'").c_str());
    return v;
}

double File::read_double_attribute(const std::string& path, const std::string& name) const {
    Handle a(open_attribute(path, name), H5Aclose);
    const AttributeInfo info = info_of(a.get(), name_, path);
    if (info.dtype != "float64" || !info.shape.empty())
        fail(name_, path,
             "attribute '" + name + "': expected a scalar float64, found " + info.dtype + " " + shape_text(info.shape));
    double v = 0;
    check(H5Aread(a.get(), H5T_NATIVE_DOUBLE, &v), name_, path, ("cannot read attribute '" + name + "'").c_str());
    return v;
}

template <class T>
std::vector<T> File::read_vector_attribute(const std::string& path, const std::string& name, const char* dtype,
                                           Id mem_type) const {
    Handle a(open_attribute(path, name), H5Aclose);
    const AttributeInfo info = info_of(a.get(), name_, path);
    if (info.dtype != dtype || info.shape.size() != 1)
        fail(name_, path,
             "attribute '" + name + "': expected a one-dimensional " + dtype + " array, found " + info.dtype + " " +
                 shape_text(info.shape));
    std::vector<T> v(static_cast<std::size_t>(info.shape[0]));
    if (!v.empty())
        check(H5Aread(a.get(), mem_type, v.data()), name_, path, ("cannot read attribute '" + name + "'").c_str());
    return v;
}

std::vector<double> File::read_doubles_attribute(const std::string& path, const std::string& name) const {
    return read_vector_attribute<double>(path, name, "float64", H5T_NATIVE_DOUBLE);
}

std::vector<std::int64_t> File::read_ints_attribute(const std::string& path, const std::string& name) const {
    return read_vector_attribute<std::int64_t>(path, name, "int64", H5T_NATIVE_INT64);
}

void File::write_attribute(const std::string& path, const std::string& name, hid_t file_type, hid_t mem_type,
                           const Shape& shape, const void* data) {
    if (has_attribute(path, name))
        check(H5Adelete_by_name(id_, path.c_str(), name.c_str(), H5P_DEFAULT), name_, path,
              ("cannot replace attribute '" + name + "'").c_str());
    Handle space;
    if (shape.empty()) {
        space = Handle(H5Screate(H5S_SCALAR), H5Sclose);
    } else {
        const std::vector<hsize_t> dims(shape.begin(), shape.end());
        space = Handle(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), H5Sclose);
    }
    if (!space.valid()) fail_call(name_, path, "cannot create a dataspace");
    Handle a(H5Acreate_by_name(id_, path.c_str(), name.c_str(), file_type, space.get(), H5P_DEFAULT, H5P_DEFAULT,
                               H5P_DEFAULT),
             H5Aclose);
    if (!a.valid()) fail_call(name_, path, "cannot create attribute '" + name + "'");
    check(H5Awrite(a.get(), mem_type, data), name_, path, ("cannot write attribute '" + name + "'").c_str());
}

void File::write_string_attribute(const std::string& path, const std::string& name, const std::string& value) {
    Handle t = vlen_string_type();
    const char* p = value.c_str();
    write_attribute(path, name, t.get(), t.get(), {}, &p);
}

void File::write_strings_attribute(const std::string& path, const std::string& name,
                                   const std::vector<std::string>& values) {
    Handle t = vlen_string_type();
    std::vector<const char*> p;
    p.reserve(values.size());
    for (const std::string& v : values) p.push_back(v.c_str());
    write_attribute(path, name, t.get(), t.get(), {values.size()}, p.data());
}

void File::write_int_attribute(const std::string& path, const std::string& name, std::int64_t value) {
    write_attribute(path, name, H5T_STD_I64LE, H5T_NATIVE_INT64, {}, &value);
}

void File::write_double_attribute(const std::string& path, const std::string& name, double value) {
    write_attribute(path, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, {}, &value);
}

void File::write_doubles_attribute(const std::string& path, const std::string& name,
                                   const std::vector<double>& values) {
    write_attribute(path, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, {values.size()}, values.data());
}

void File::write_ints_attribute(const std::string& path, const std::string& name,
                                const std::vector<std::int64_t>& values) {
    write_attribute(path, name, H5T_STD_I64LE, H5T_NATIVE_INT64, {values.size()}, values.data());
}

}  // namespace mocapdb::store::h5
