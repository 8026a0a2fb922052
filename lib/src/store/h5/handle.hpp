#pragma once
// RAII ownership of one HDF5 identifier (file, group, dataset, dataspace, datatype, property list,
// attribute): closed exactly once with the matching H5*close function.
#include <hdf5.h>

#include <utility>

namespace mocapdb::store::h5 {

class Handle {
public:
    using Closer = herr_t (*)(hid_t);

    Handle() = default;
    Handle(hid_t id, Closer close) noexcept : id_(id), close_(close) {}
    ~Handle() { reset(); }
    Handle(Handle&& other) noexcept : id_(std::exchange(other.id_, H5I_INVALID_HID)), close_(other.close_) {}
    Handle& operator=(Handle&& other) noexcept {
        if (this != &other) {
            reset();
            id_ = std::exchange(other.id_, H5I_INVALID_HID);
            close_ = other.close_;
        }
        return *this;
    }
    Handle(const Handle&) = delete;
    Handle& operator=(const Handle&) = delete;

    hid_t get() const noexcept { return id_; }
    bool valid() const noexcept { return id_ >= 0; }
    /// Closes now; returns false when HDF5 reported a failure.
    bool reset() noexcept {
        bool ok = true;
        if (id_ >= 0 && close_ != nullptr) ok = close_(id_) >= 0;
        id_ = H5I_INVALID_HID;
        return ok;
    }

private:
    hid_t id_ = H5I_INVALID_HID;
    Closer close_ = nullptr;
};

}  // namespace mocapdb::store::h5
