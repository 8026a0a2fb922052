#include "layout.hpp"

#include "mocapdb/core/error.hpp"

namespace mocapdb::store {

void check_link_name(const std::string& name, const char* what) {
    const std::string who = std::string(what) + " '" + name + "'";
    if (name.empty()) throw InvalidArgument(std::string(what) + " must not be empty");
    if (name == "." || name == "..") throw InvalidArgument(who + " is not allowed");
    for (const char c : name) {
        if (c == '/') throw InvalidArgument(who + " must not contain '/'");
        if (static_cast<unsigned char>(c) < 0x20) throw InvalidArgument(who + " must not contain control characters");
    }
}

h5::Shape c_order_shape(const Tensor3& tensor) {
    return {static_cast<std::uint64_t>(tensor.dimension(2)), static_cast<std::uint64_t>(tensor.dimension(1)),
            static_cast<std::uint64_t>(tensor.dimension(0))};
}

std::vector<double> to_c_order(const MatX& matrix) {
    std::vector<double> out(static_cast<std::size_t>(matrix.size()));
    Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(out.data(), matrix.rows(),
                                                                                       matrix.cols()) = matrix;
    return out;
}

MatX from_c_order(const std::vector<double>& data, Eigen::Index rows, Eigen::Index cols) {
    return Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(data.data(), rows,
                                                                                                    cols);
}

std::vector<std::string> split_path(const std::string& path) {
    std::vector<std::string> parts;
    std::size_t start = 1;
    while (start < path.size()) {
        std::size_t end = path.find('/', start);
        if (end == std::string::npos) end = path.size();
        parts.push_back(path.substr(start, end - start));
        start = end + 1;
    }
    return parts;
}

}  // namespace mocapdb::store
