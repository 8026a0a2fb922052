#pragma once
// One open HDF5 file and the checked operations the store needs on it: groups, attributes, and
// n-dimensional datasets written in C order with `dims` and `units` attributes, chunked, shuffled,
// deflated and fletcher32-checksummed. Every failure throws StoreError naming the file and path.
// This header does not include HDF5's: the codecs above it see no HDF5 types (identifiers are the
// int64 values HDF5 1.10 uses for hid_t, checked in file.cpp).
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "mocapdb/store/storage_extents.hpp"

namespace mocapdb::store::h5 {

using Shape = std::vector<std::uint64_t>;

/// "(3, 62)"; "scalar" for rank 0.
std::string shape_text(const Shape& shape);

template <class T>
struct Array {
    Shape shape;
    std::vector<T> data;  ///< C order
};

struct DatasetInfo {
    std::string dtype;
    Shape shape;
    bool chunked = false;
    Shape chunk;
    std::vector<std::string> filters;  ///< "shuffle", "deflate", "fletcher32", ... in pipeline order
    std::uint64_t stored_bytes = 0;
};

struct AttributeInfo {
    std::string dtype;
    Shape shape;  ///< empty for a scalar
};

enum class ObjectType { None, Group, Dataset, Other };

/// Every attribute of one object, read with the object opened once (a clip record's dozen
/// attributes cost one path lookup instead of a dozen): scalar strings, one-dimensional string
/// lists, scalar int64 and float64 values; `info` holds every attribute's dtype and shape (the
/// other kinds are described there and not read).
struct Attributes {
    std::string path;  ///< the object's path
    ObjectType type = ObjectType::None;
    std::vector<std::pair<std::string, AttributeInfo>> info;
    std::vector<std::pair<std::string, std::string>> strings;
    std::vector<std::pair<std::string, std::vector<std::string>>> string_lists;
    std::vector<std::pair<std::string, std::int64_t>> ints;
    std::vector<std::pair<std::string, double>> doubles;

    bool has(const std::string& name) const;
    const AttributeInfo* find_info(const std::string& name) const;
};

class File {
public:
    /// Opens an existing file (read-only or read-write).
    static File open(const std::filesystem::path& path, bool writable);
    /// Creates a new file; fails when it exists.
    static File create(const std::filesystem::path& path);

    File() = default;
    ~File();
    File(File&& other) noexcept;
    File& operator=(File&& other) noexcept;
    File(const File&) = delete;
    File& operator=(const File&) = delete;

    /// The file name that errors about this file give (the path it was opened with, unless renamed).
    const std::string& name() const noexcept { return name_; }
    /// Errors name `name` from now on: a writing session's temporary copy reports its target, the
    /// file the user named.
    void set_name_in_errors(std::string name) { name_ = std::move(name); }
    bool is_open() const noexcept { return id_ >= 0; }
    bool writable() const noexcept { return writable_; }
    /// Flushes and closes; throws on failure.
    void close();
    std::uint64_t size() const;

    // Objects. Paths are absolute ("/clips/16_15"); names never contain '/'.
    ObjectType type_of(const std::string& path) const;
    bool exists(const std::string& path) const { return type_of(path) != ObjectType::None; }
    /// Whether the last link of `path` exists, without following it (cheaper than exists() when it is
    /// an external link: its segment is not opened).
    bool link_exists(const std::string& path) const;
    /// Creates a group with attribute kind = `kind`.
    void create_group(const std::string& path, const std::string& kind);
    void unlink(const std::string& path);
    /// Names of the links in a group, sorted.
    std::vector<std::string> children(const std::string& group) const;
    /// Copies the object at `path` (recursively) into `destination` at the same path. External links
    /// inside it are copied as links.
    void copy_to(File& destination, const std::string& path) const;
    /// The same without the objects at the paths in `skipped` (absolute, below `path`): the groups
    /// above them are made anew in `destination` with their attributes and the rest of their
    /// members. For an object about to be replaced: it is never copied only to be unlinked.
    void copy_to_except(File& destination, const std::string& path, const std::vector<std::string>& skipped) const;
    /// Creates an external link at `path` to object `target` of file `file` (a path relative to this
    /// file's folder, resolved by HDF5 from there).
    void link_external(const std::string& path, const std::string& file, const std::string& target);
    /// The (file, object path) an external link at `path` points to; nullopt when the link at `path`
    /// is not external (or absent).
    std::optional<std::pair<std::string, std::string>> external_target(const std::string& path) const;
    /// The file that holds the object at `path` (this file, or the target of an external link on the way).
    std::filesystem::path file_holding(const std::string& path) const;
    /// Bytes the object at `path` takes in the file holding it, its members not included: its object
    /// header (compact attributes in it), its link index and heap (groups), attribute index and heap,
    /// chunk index and stored data (datasets), and the global-heap objects of its variable-length
    /// string attributes (16 bytes each plus the text rounded up to 8).
    std::uint64_t object_file_bytes(const std::string& path) const;

    // Attributes of the object at `path`.
    std::vector<std::string> attribute_names(const std::string& path) const;
    /// All attributes of the object at `path` (StoreError when there is none); see Attributes.
    Attributes read_attributes(const std::string& path) const;
    /// The checked accessors of Attributes, with the messages of read_string_attribute and friends.
    std::string string_attribute(const Attributes& a, const std::string& name) const;
    std::vector<std::string> strings_attribute(const Attributes& a, const std::string& name) const;
    std::int64_t int_attribute(const Attributes& a, const std::string& name) const;
    double double_attribute(const Attributes& a, const std::string& name) const;
    bool has_attribute(const std::string& path, const std::string& name) const;
    AttributeInfo attribute_info(const std::string& path, const std::string& name) const;
    /// Scalar variable-length string attribute.
    std::string read_string_attribute(const std::string& path, const std::string& name) const;
    /// One-dimensional variable-length string attribute.
    std::vector<std::string> read_strings_attribute(const std::string& path, const std::string& name) const;
    /// Scalar int64 attribute.
    std::int64_t read_int_attribute(const std::string& path, const std::string& name) const;
    /// Scalar float64 attribute.
    double read_double_attribute(const std::string& path, const std::string& name) const;
    /// One-dimensional float64 attribute.
    std::vector<double> read_doubles_attribute(const std::string& path, const std::string& name) const;
    /// One-dimensional int64 attribute.
    std::vector<std::int64_t> read_ints_attribute(const std::string& path, const std::string& name) const;

    void write_string_attribute(const std::string& path, const std::string& name, const std::string& value);
    void write_strings_attribute(const std::string& path, const std::string& name,
                                 const std::vector<std::string>& values);
    void write_int_attribute(const std::string& path, const std::string& name, std::int64_t value);
    void write_double_attribute(const std::string& path, const std::string& name, double value);
    void write_doubles_attribute(const std::string& path, const std::string& name, const std::vector<double>& values);
    void write_ints_attribute(const std::string& path, const std::string& name,
                              const std::vector<std::int64_t>& values);

    // Datasets.
    DatasetInfo dataset_info(const std::string& path) const;
    /// Writes a new dataset of shape `shape` (C order) with attributes dims (one name per axis) and
    /// units. Non-empty datasets are chunked with shuffle + deflate + fletcher32.
    template <class T>
    void write_array(const std::string& path, const T* data, const Shape& shape, const std::vector<std::string>& dims,
                     const std::string& units);
    /// The same with fletcher32 only: for values deflate does not shrink (float64 of full precision, such
    /// as a factorized system), which are then read without inflating them.
    template <class T>
    void write_array_checksum_only(const std::string& path, const T* data, const Shape& shape,
                                   const std::vector<std::string>& dims, const std::string& units);
    /// Writes bytes that are already compressed as a one-dimensional uint8 dataset with attributes dims
    /// = [dim] and units: chunked with fletcher32 only (shuffle and deflate would not shrink them).
    void write_compressed_bytes(const std::string& path, const std::vector<std::uint8_t>& bytes, const std::string& dim,
                                const std::string& units);
    void write_strings(const std::string& path, const std::vector<std::string>& values, const std::string& dim,
                       const std::string& units);
    /// Reads a whole dataset; StoreError unless its dtype is exactly T's and its rank is `rank`.
    template <class T>
    Array<T> read_array(const std::string& path, std::size_t rank) const;
    /// The same checks, read straight into the caller's memory (no intermediate copy of a large
    /// dataset): `destination(shape)` may check the shape (and throw), and returns a buffer of
    /// element_count(shape) values (C order). Returns the shape.
    template <class T>
    Shape read_array_into(const std::string& path, std::size_t rank,
                          const std::function<T*(const Shape&)>& destination) const;
    /// Reads a one-dimensional variable-length string dataset.
    std::vector<std::string> read_strings(const std::string& path) const;
    /// Reads every byte of a dataset (whatever its type) and discards it: verifies checksums.
    void read_and_discard(const std::string& path) const;
    std::vector<ByteExtent> extents(const std::string& path) const;

private:
    using Id = std::int64_t;  // hid_t
    /// Filter pipeline of a new non-empty dataset (fletcher32 always comes last).
    enum class Filters { Deflate, ShuffleDeflate, ChecksumOnly };
    // Each returns a new identifier the caller must close (wrapped in h5::Handle inside h5/).
    Id open_object(const std::string& path) const;
    Id open_dataset(const std::string& path) const;
    Id open_attribute(const std::string& path, const std::string& name) const;
    void write_attribute(const std::string& path, const std::string& name, Id file_type, Id mem_type,
                         const Shape& shape, const void* data);
    void write_raw(const std::string& path, Id file_type, Id mem_type, const Shape& shape, const void* data,
                   Filters filters, const std::vector<std::string>& dims, const std::string& units);
    void check_type(const std::string& path, Id type, const std::string& expected) const;
    template <class T>
    std::vector<T> read_vector_attribute(const std::string& path, const std::string& name, const char* dtype,
                                         Id mem_type) const;

    Id id_ = -1;
    std::string name_;
    bool writable_ = false;
};

}  // namespace mocapdb::store::h5
