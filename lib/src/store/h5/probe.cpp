// Public helpers that look at a file with HDF5 directly: is it HDF5, where are a dataset's bytes.
#include <hdf5.h>

#include "errors.hpp"
#include "file.hpp"
#include "mocapdb/core/error.hpp"
#include "mocapdb/store/database.hpp"
#include "mocapdb/store/storage_extents.hpp"
#include "quiet.hpp"

namespace mocapdb {

bool is_hdf5_file(const std::filesystem::path& path) {
    store::h5::QuietScope quiet;
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) return false;
    const htri_t r = H5Fis_hdf5(path.c_str());
    H5Eclear2(H5E_DEFAULT);
    return r > 0;
}

std::vector<ByteExtent> dataset_extents(const std::filesystem::path& file, const std::string& dataset_path) {
    store::h5::QuietScope quiet;
    std::error_code ec;
    if (!std::filesystem::exists(file, ec)) throw IoError(file.string() + ": no such file");
    const store::h5::File f = store::h5::File::open(file, false);
    return f.extents(dataset_path);
}

}  // namespace mocapdb
