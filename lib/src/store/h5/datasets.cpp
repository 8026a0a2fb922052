// Datasets: C-order n-dimensional arrays with `dims` and `units` attributes, chunked and filtered
// (shuffle + deflate + fletcher32); reads that check dtype and rank before touching the data.
#include <hdf5.h>

#include <algorithm>
#include <cstring>
#include <numeric>

#include "access.hpp"
#include "errors.hpp"
#include "file.hpp"
#include "filtered_chunks.hpp"
#include "handle.hpp"
#include "types.hpp"
#include "mocapdb/core/parallel_tasks.hpp"

namespace mocapdb::store::h5 {
namespace {

template <class T>
struct Traits;
template <>
struct Traits<double> {
    static hid_t file() { return H5T_IEEE_F64LE; }
    static hid_t memory() { return H5T_NATIVE_DOUBLE; }
    static constexpr const char* name = "float64";
};
template <>
struct Traits<std::int64_t> {
    static hid_t file() { return H5T_STD_I64LE; }
    static hid_t memory() { return H5T_NATIVE_INT64; }
    static constexpr const char* name = "int64";
};
template <>
struct Traits<std::int32_t> {
    static hid_t file() { return H5T_STD_I32LE; }
    static hid_t memory() { return H5T_NATIVE_INT32; }
    static constexpr const char* name = "int32";
};
template <>
struct Traits<std::uint8_t> {
    static hid_t file() { return H5T_STD_U8LE; }
    static hid_t memory() { return H5T_NATIVE_UINT8; }
    static constexpr const char* name = "uint8";
};

constexpr std::uint64_t kChunkBytes = 256 * 1024;
constexpr unsigned kDeflateLevel = 4;
// Deflated datasets from this size on have their chunks filtered on the machine's cores
// (filtered_chunks.hpp), this many chunks at a time (a few MB of buffers).
constexpr std::uint64_t kParallelFilterBytes = 4 * 1024 * 1024;
constexpr std::size_t kChunksPerBatch = 32;
// A dataset whose first kProbeChunks chunks deflate to more than kWorthDeflatingPercent of their bytes
// has its other chunks stored (deflate level 0, still a deflate stream that every reader inflates).
// Float64 noise, such as a Tucker model's bases, deflates to about 88 % at about 40 MB/s per core
// whatever the level: 5 s of a 383 MB model's store for 11 % of its bytes.
constexpr std::size_t kProbeChunks = 4;
constexpr std::uint64_t kWorthDeflatingPercent = 80;

// Writes `data` (C order, `extent`, elements of `element_size` bytes in the file's representation)
// chunk by chunk through H5Dwrite_chunk: each chunk (rows [c chunk[0], ...), whole trailing axes,
// zero-padded at the edge as HDF5 pads it) shuffled, deflated and checksummed as the dataset's
// filters would, the chunks of a batch on the machine's cores and written in order. After the first
// kProbeChunks, a dataset that deflates poorly (kWorthDeflatingPercent) is stored at level 0.
void write_filtered_chunks(hid_t d, const std::vector<hsize_t>& extent, const std::vector<hsize_t>& chunk,
                           std::size_t element_size, const void* data, bool shuffle, const std::string& file,
                           const std::string& path) {
    std::uint64_t row_bytes = element_size;
    for (std::size_t i = 1; i < extent.size(); ++i) row_bytes *= extent[i];
    const std::uint64_t chunk_bytes = chunk[0] * row_bytes;
    const std::size_t chunks = static_cast<std::size_t>((extent[0] + chunk[0] - 1) / chunk[0]);
    const auto* bytes = static_cast<const std::uint8_t*>(data);
    std::vector<std::vector<std::uint8_t>> encoded(kChunksPerBatch);
    int level = static_cast<int>(kDeflateLevel);
    for (std::size_t first = 0, batch = 0; first < chunks; first += batch) {
        batch = std::min(first == 0 ? kProbeChunks : kChunksPerBatch, chunks - first);
        run_parallel_tasks(batch, [&](std::size_t i) {
            const std::size_t c = first + i;
            const std::uint64_t rows = std::min<std::uint64_t>(chunk[0], extent[0] - c * chunk[0]);
            const std::uint8_t* begin = bytes + c * chunk_bytes;
            if (rows == chunk[0]) {
                encoded[i] = encode_filtered_chunk(begin, chunk_bytes, element_size, shuffle, level);
            } else {
                std::vector<std::uint8_t> padded(chunk_bytes, 0);
                std::copy(begin, begin + rows * row_bytes, padded.begin());
                encoded[i] = encode_filtered_chunk(padded.data(), chunk_bytes, element_size, shuffle, level);
            }
        });
        std::uint64_t stored = 0;
        for (std::size_t i = 0; i < batch; ++i) {
            if (encoded[i].empty()) fail_call(file, path, "cannot deflate chunk " + std::to_string(first + i));
            stored += encoded[i].size();
            std::vector<hsize_t> offset(extent.size(), 0);
            offset[0] = (first + i) * chunk[0];
            if (H5Dwrite_chunk(d, H5P_DEFAULT, 0, offset.data(), encoded[i].size(), encoded[i].data()) < 0)
                fail_call(file, path, "cannot write chunk " + std::to_string(first + i));
        }
        if (first == 0 && 100 * stored > kWorthDeflatingPercent * batch * chunk_bytes) level = 0;
    }
}

std::uint64_t element_count(const Shape& shape) {
    return std::accumulate(shape.begin(), shape.end(), std::uint64_t{1}, std::multiplies<>());
}

std::string filter_name(H5Z_filter_t id) {
    switch (id) {
        case H5Z_FILTER_DEFLATE: return "deflate";
        case H5Z_FILTER_SHUFFLE: return "shuffle";
        case H5Z_FILTER_FLETCHER32: return "fletcher32";
        case H5Z_FILTER_SZIP: return "szip";
        case H5Z_FILTER_NBIT: return "nbit";
        case H5Z_FILTER_SCALEOFFSET: return "scaleoffset";
        default: return "filter " + std::to_string(id);
    }
}

}  // namespace

File::Id File::open_dataset(const std::string& path) const {
    const ObjectType t = type_of(path);
    if (t != ObjectType::Dataset)
        fail(name_, path,
             std::string("expected a dataset, found ") +
                 (t == ObjectType::None ? "nothing" : "a group or other object"));
    const hid_t id = H5Dopen2(id_, path.c_str(), dataset_access());
    if (id < 0) fail_call(name_, path, "cannot open the dataset");
    return id;
}

DatasetInfo File::dataset_info(const std::string& path) const {
    Handle d(open_dataset(path), H5Dclose);
    Handle type(check(H5Dget_type(d.get()), name_, path, "cannot read the dataset type"), H5Tclose);
    Handle space(check(H5Dget_space(d.get()), name_, path, "cannot read the dataset shape"), H5Sclose);
    Handle dcpl(check(H5Dget_create_plist(d.get()), name_, path, "cannot read the dataset properties"), H5Pclose);
    DatasetInfo info;
    info.dtype = dtype_name(type.get());
    if (H5Sget_simple_extent_type(space.get()) == H5S_NULL) info.dtype = "null";
    const int rank = H5Sget_simple_extent_ndims(space.get());
    if (rank > 0) {
        std::vector<hsize_t> dims(static_cast<std::size_t>(rank));
        H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
        info.shape.assign(dims.begin(), dims.end());
    }
    info.chunked = H5Pget_layout(dcpl.get()) == H5D_CHUNKED;
    if (info.chunked && rank > 0) {
        std::vector<hsize_t> chunk(static_cast<std::size_t>(rank));
        check(H5Pget_chunk(dcpl.get(), rank, chunk.data()), name_, path, "cannot read the chunk shape");
        info.chunk.assign(chunk.begin(), chunk.end());
    }
    const int nfilters = H5Pget_nfilters(dcpl.get());
    for (int i = 0; i < nfilters; ++i) {
        unsigned flags = 0, config = 0;
        std::size_t nelements = 0;
        char fname[64];
        const H5Z_filter_t id = H5Pget_filter2(dcpl.get(), static_cast<unsigned>(i), &flags, &nelements, nullptr,
                                               sizeof fname, fname, &config);
        info.filters.push_back(filter_name(id));
    }
    info.stored_bytes = H5Dget_storage_size(d.get());
    return info;
}

void File::write_raw(const std::string& path, hid_t file_type, hid_t mem_type, const Shape& shape, const void* data,
                     Filters filters, const std::vector<std::string>& dims, const std::string& units) {
    const std::vector<hsize_t> extent(shape.begin(), shape.end());
    Handle space(shape.empty() ? H5Screate(H5S_SCALAR)
                               : H5Screate_simple(static_cast<int>(extent.size()), extent.data(), nullptr),
                 H5Sclose);
    if (!space.valid()) fail_call(name_, path, "cannot create the dataspace " + shape_text(shape));
    Handle dcpl(check(H5Pcreate(H5P_DATASET_CREATE), name_, path, "cannot create dataset properties"), H5Pclose);
    check(H5Pset_obj_track_times(dcpl.get(), 0), name_, path, "cannot disable time tracking");
    const std::uint64_t count = element_count(shape);
    const std::size_t element_size = H5Tget_size(file_type);
    std::vector<hsize_t> chunk(extent);
    if (!shape.empty() && count > 0) {
        // Whole trailing axes per chunk; the first axis split so that a chunk is about kChunkBytes.
        const std::uint64_t row_bytes = count / extent[0] * element_size;
        chunk[0] = std::clamp<hsize_t>(kChunkBytes / std::max<std::uint64_t>(row_bytes, 1), 1, extent[0]);
        if (filters == Filters::ChecksumOnly) {
            // Unfiltered edge chunks are stored whole: split evenly so that the padding is < 1 row per chunk.
            const hsize_t count_of_chunks = (extent[0] + chunk[0] - 1) / chunk[0];
            chunk[0] = (extent[0] + count_of_chunks - 1) / count_of_chunks;
        }
        check(H5Pset_chunk(dcpl.get(), static_cast<int>(chunk.size()), chunk.data()), name_, path,
              "cannot set the chunk shape");
        if (filters == Filters::ShuffleDeflate)
            check(H5Pset_shuffle(dcpl.get()), name_, path, "cannot enable the shuffle filter");
        if (filters != Filters::ChecksumOnly)
            check(H5Pset_deflate(dcpl.get(), kDeflateLevel), name_, path, "cannot enable the deflate filter");
        check(H5Pset_fletcher32(dcpl.get()), name_, path, "cannot enable the fletcher32 filter");
    }
    Handle d(H5Dcreate2(id_, path.c_str(), file_type, space.get(), H5P_DEFAULT, dcpl.get(), H5P_DEFAULT), H5Dclose);
    if (!d.valid()) fail_call(name_, path, "cannot create the dataset");
    const bool parallel = !shape.empty() && filters != Filters::ChecksumOnly && H5Tequal(file_type, mem_type) > 0 &&
                          count * element_size >= kParallelFilterBytes;
    if (parallel) {
        write_filtered_chunks(d.get(), extent, chunk, element_size, data, filters == Filters::ShuffleDeflate, name_,
                              path);
    } else if (count > 0) {
        check(H5Dwrite(d.get(), mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), name_, path,
              "cannot write the dataset");
    }
    d.reset();
    write_strings_attribute(path, "dims", dims);
    write_string_attribute(path, "units", units);
}

template <class T>
void File::write_array(const std::string& path, const T* data, const Shape& shape, const std::vector<std::string>& dims,
                       const std::string& units) {
    write_raw(path, Traits<T>::file(), Traits<T>::memory(), shape, data,
              sizeof(T) > 1 ? Filters::ShuffleDeflate : Filters::Deflate, dims, units);
}

template <class T>
void File::write_array_checksum_only(const std::string& path, const T* data, const Shape& shape,
                                     const std::vector<std::string>& dims, const std::string& units) {
    write_raw(path, Traits<T>::file(), Traits<T>::memory(), shape, data, Filters::ChecksumOnly, dims, units);
}

void File::write_compressed_bytes(const std::string& path, const std::vector<std::uint8_t>& bytes,
                                  const std::string& dim, const std::string& units) {
    write_raw(path, H5T_STD_U8LE, H5T_NATIVE_UINT8, {bytes.size()}, bytes.data(), Filters::ChecksumOnly, {dim}, units);
}

void File::write_strings(const std::string& path, const std::vector<std::string>& values, const std::string& dim,
                         const std::string& units) {
    // Fixed-length (null-padded, UTF-8) so that the filters, and so the checksum, apply: HDF5 cannot
    // filter variable-length data.
    std::size_t width = 1;
    for (const std::string& v : values) width = std::max(width, v.size());
    Handle t(H5Tcopy(H5T_C_S1), H5Tclose);
    if (!t.valid() || H5Tset_size(t.get(), width) < 0 || H5Tset_strpad(t.get(), H5T_STR_NULLPAD) < 0 ||
        H5Tset_cset(t.get(), H5T_CSET_UTF8) < 0)
        fail_call(name_, path, "cannot make a string datatype");
    std::vector<char> buffer(values.size() * width, '\0');
    for (std::size_t i = 0; i < values.size(); ++i)
        std::copy(values[i].begin(), values[i].end(), buffer.begin() + static_cast<std::ptrdiff_t>(i * width));
    write_raw(path, t.get(), t.get(), {values.size()}, buffer.data(), Filters::Deflate, {dim}, units);
}

void File::check_type(const std::string& path, hid_t type, const std::string& expected) const {
    const std::string found = dtype_name(type);
    if (found != expected) fail(name_, path, "expected dtype " + expected + ", found " + found);
}

template <class T>
Shape File::read_array_into(const std::string& path, std::size_t rank,
                            const std::function<T*(const Shape&)>& destination) const {
    Handle d(open_dataset(path), H5Dclose);
    Handle type(check(H5Dget_type(d.get()), name_, path, "cannot read the dataset type"), H5Tclose);
    check_type(path, type.get(), Traits<T>::name);
    Handle space(check(H5Dget_space(d.get()), name_, path, "cannot read the dataset shape"), H5Sclose);
    Shape shape;
    const int r = H5Sget_simple_extent_ndims(space.get());
    if (r > 0) {
        std::vector<hsize_t> dims(static_cast<std::size_t>(r));
        H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
        shape.assign(dims.begin(), dims.end());
    }
    if (H5Sget_simple_extent_type(space.get()) != H5S_SIMPLE || shape.size() != rank)
        fail(name_, path, "expected " + std::to_string(rank) + " dimensions, found shape " + shape_text(shape));
    T* out = destination(shape);
    if (element_count(shape) > 0)
        check(H5Dread(d.get(), Traits<T>::memory(), H5S_ALL, H5S_ALL, H5P_DEFAULT, out), name_, path,
              "cannot read the dataset");
    return shape;
}

template <class T>
Array<T> File::read_array(const std::string& path, std::size_t rank) const {
    Array<T> out;
    out.shape = read_array_into<T>(path, rank, [&out](const Shape& shape) {
        out.data.resize(static_cast<std::size_t>(element_count(shape)));
        return out.data.data();
    });
    return out;
}

std::vector<std::string> File::read_strings(const std::string& path) const {
    Handle d(open_dataset(path), H5Dclose);
    Handle type(check(H5Dget_type(d.get()), name_, path, "cannot read the dataset type"), H5Tclose);
    if (H5Tget_class(type.get()) != H5T_STRING)
        fail(name_, path, "expected dtype fixed-string, found " + dtype_name(type.get()));
    Handle space(check(H5Dget_space(d.get()), name_, path, "cannot read the dataset shape"), H5Sclose);
    const int r = H5Sget_simple_extent_ndims(space.get());
    if (r != 1 || H5Sget_simple_extent_type(space.get()) != H5S_SIMPLE) {
        Shape shape;
        if (r > 0) {
            std::vector<hsize_t> dims(static_cast<std::size_t>(r));
            H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
            shape.assign(dims.begin(), dims.end());
        }
        fail(name_, path, "expected 1 dimension, found shape " + shape_text(shape));
    }
    hsize_t n = 0;
    H5Sget_simple_extent_dims(space.get(), &n, nullptr);
    std::vector<std::string> out;
    if (n == 0) return out;
    out.reserve(static_cast<std::size_t>(n));
    if (H5Tis_variable_str(type.get()) > 0) {  // accepted on read (h5py writes these)
        std::vector<char*> buffer(static_cast<std::size_t>(n), nullptr);
        Handle mtype = vlen_string_type(H5Tget_cset(type.get()));
        check(H5Dread(d.get(), mtype.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, buffer.data()), name_, path,
              "cannot read the dataset");
        for (char* s : buffer) out.emplace_back(s != nullptr ? s : "");
        H5Dvlen_reclaim(mtype.get(), space.get(), H5P_DEFAULT, buffer.data());
        return out;
    }
    const std::size_t width = H5Tget_size(type.get());
    Handle mtype(H5Tcopy(type.get()), H5Tclose);
    std::vector<char> buffer(static_cast<std::size_t>(n) * width);
    check(H5Dread(d.get(), mtype.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, buffer.data()), name_, path,
          "cannot read the dataset");
    const bool space_padded = H5Tget_strpad(type.get()) == H5T_STR_SPACEPAD;
    for (std::size_t i = 0; i < n; ++i) {
        std::string v(buffer.data() + i * width, width);
        const std::size_t nul = v.find('\0');
        if (nul != std::string::npos) v.resize(nul);
        if (space_padded) v.erase(v.find_last_not_of(' ') + 1);
        out.push_back(std::move(v));
    }
    return out;
}

void File::read_and_discard(const std::string& path) const {
    Handle d(open_dataset(path), H5Dclose);
    Handle type(check(H5Dget_type(d.get()), name_, path, "cannot read the dataset type"), H5Tclose);
    if (H5Tget_class(type.get()) == H5T_STRING && H5Tis_variable_str(type.get()) > 0) {
        read_strings(path);
        return;
    }
    if (H5Tdetect_class(type.get(), H5T_VLEN) > 0 || H5Tget_class(type.get()) == H5T_REFERENCE)
        fail(name_, path, "unsupported dtype " + dtype_name(type.get()));
    Handle space(check(H5Dget_space(d.get()), name_, path, "cannot read the dataset shape"), H5Sclose);
    const hssize_t n = H5Sget_select_npoints(space.get());
    if (n <= 0) return;
    std::vector<unsigned char> buffer(static_cast<std::size_t>(n) * H5Tget_size(type.get()));
    check(H5Dread(d.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, buffer.data()), name_, path,
          "cannot read the dataset");
}

std::vector<ByteExtent> File::extents(const std::string& path) const {
    Handle d(open_dataset(path), H5Dclose);
    Handle dcpl(check(H5Dget_create_plist(d.get()), name_, path, "cannot read the dataset properties"), H5Pclose);
    std::vector<ByteExtent> out;
    const std::filesystem::path holder = file_holding(path);
    const H5D_layout_t layout = H5Pget_layout(dcpl.get());
    if (layout == H5D_CHUNKED) {
        hsize_t n = 0;
        Handle space(check(H5Dget_space(d.get()), name_, path, "cannot read the dataset shape"), H5Sclose);
        check(H5Dget_num_chunks(d.get(), space.get(), &n), name_, path, "cannot count the chunks");
        std::vector<hsize_t> coords(static_cast<std::size_t>(std::max(1, H5Sget_simple_extent_ndims(space.get()))));
        for (hsize_t i = 0; i < n; ++i) {
            unsigned mask = 0;
            haddr_t addr = 0;
            hsize_t size = 0;
            check(H5Dget_chunk_info(d.get(), space.get(), i, coords.data(), &mask, &addr, &size), name_, path,
                  "cannot locate a chunk");
            out.push_back({static_cast<std::uint64_t>(addr), static_cast<std::uint64_t>(size), holder});
        }
    } else if (layout == H5D_CONTIGUOUS) {
        const haddr_t addr = H5Dget_offset(d.get());
        if (addr != HADDR_UNDEF)
            out.push_back({static_cast<std::uint64_t>(addr), H5Dget_storage_size(d.get()), holder});
    }
    return out;
}

template void File::write_array<double>(const std::string&, const double*, const Shape&,
                                        const std::vector<std::string>&, const std::string&);
template void File::write_array<std::int64_t>(const std::string&, const std::int64_t*, const Shape&,
                                              const std::vector<std::string>&, const std::string&);
template void File::write_array<std::int32_t>(const std::string&, const std::int32_t*, const Shape&,
                                              const std::vector<std::string>&, const std::string&);
template void File::write_array<std::uint8_t>(const std::string&, const std::uint8_t*, const Shape&,
                                              const std::vector<std::string>&, const std::string&);
template void File::write_array_checksum_only<double>(const std::string&, const double*, const Shape&,
                                                      const std::vector<std::string>&, const std::string&);
template Array<double> File::read_array<double>(const std::string&, std::size_t) const;
template Shape File::read_array_into<double>(const std::string&, std::size_t,
                                             const std::function<double*(const Shape&)>&) const;
template Array<std::int64_t> File::read_array<std::int64_t>(const std::string&, std::size_t) const;
template Array<std::int32_t> File::read_array<std::int32_t>(const std::string&, std::size_t) const;
template Array<std::uint8_t> File::read_array<std::uint8_t>(const std::string&, std::size_t) const;

}  // namespace mocapdb::store::h5
