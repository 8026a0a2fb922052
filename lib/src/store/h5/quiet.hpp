#pragma once
// A scope in which HDF5 prints nothing: its automatic error printing is switched off and the
// previous handler restored at the end (nests). Every public store entry point holds one, so HDF5's
// failures reach the user only as our errors, with the HDF5 path. No HDF5 header needed here.
#include <cstdint>

namespace mocapdb::store::h5 {

class QuietScope {
public:
    using Handler = int (*)(std::int64_t, void*);  // H5E_auto2_t, checked in errors.cpp

    QuietScope();
    ~QuietScope();
    QuietScope(const QuietScope&) = delete;
    QuietScope& operator=(const QuietScope&) = delete;

private:
    Handler old_func_ = nullptr;
    void* old_data_ = nullptr;
    bool saved_ = false;
};

}  // namespace mocapdb::store::h5
