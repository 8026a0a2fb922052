#include "model_codec.hpp"

#include <algorithm>
#include <cmath>

#include "layout.hpp"
#include "read_checks.hpp"
#include "mocapdb/core/error.hpp"
#include "mocapdb/store/store_error.hpp"

namespace mocapdb::store {
namespace {

// The datasets of a model, in the order they are written.
const char* const kModelDatasets[] = {"core", "dof_basis", "time_basis", "sample_basis", "mean", "weight"};

struct FigureField {
    const char* name;
    double ModelFigures::*member;
};
const FigureField kFigureFields[] = {{"dof_rmse", &ModelFigures::dof_rmse},
                                     {"rmse_cm", &ModelFigures::rmse_cm},
                                     {"mean_cm", &ModelFigures::mean_cm},
                                     {"max_cm", &ModelFigures::max_cm},
                                     {"p99_cm", &ModelFigures::p99_cm}};

const tensor::TuckerMethod kMethods[] = {tensor::TuckerMethod::Hosvd, tensor::TuckerMethod::StHosvd,
                                         tensor::TuckerMethod::Hooi};
const tensor::TuckerStatus kTuckerStatuses[] = {tensor::TuckerStatus::Ok, tensor::TuckerStatus::Converged,
                                                tensor::TuckerStatus::MaxIterations, tensor::TuckerStatus::Stalled};

// The enum value whose to_string is `text`; StoreError naming the attribute otherwise.
template <class Enum, std::size_t K>
Enum parse_enum(const h5::File& file, const std::string& g, const char* attribute, const std::string& text,
                const Enum (&values)[K]) {
    std::string allowed;
    for (const Enum v : values) {
        if (text == tensor::to_string(v)) return v;
        allowed += (allowed.empty() ? "\"" : ", \"") + std::string(tensor::to_string(v)) + "\"";
    }
    throw StoreError(
        file.name(), g,
        std::string("attribute '") + attribute + "': expected one of " + allowed + ", found \"" + text + "\"");
}

double finite_attribute(const h5::File& file, const std::string& g, const char* name, bool non_negative) {
    const double v = file.read_double_attribute(g, name);
    if (!std::isfinite(v) || (non_negative && v < 0.0))
        throw StoreError(file.name(), g,
                         std::string("attribute '") + name + "': expected a finite number" +
                             (non_negative ? " >= 0" : "") + ", found " + std::to_string(v));
    return v;
}

}  // namespace

void write_model(h5::File& file, const std::string& set, const compression::SetModel& m, const ModelFigures& figures) {
    const std::string g = model_path(set);
    const tensor::TuckerModel& t = m.tucker;
    file.create_group(g, "tucker_model");
    file.write_string_attribute(g, "method", tensor::to_string(t.method));
    file.write_string_attribute(g, "status", tensor::to_string(t.status));
    file.write_int_attribute(g, "iterations", t.iterations);
    file.write_double_attribute(g, "fit", t.fit);
    file.write_double_attribute(g, "error_bound", t.error_bound);
    file.write_double_attribute(g, "data_norm", t.data_norm);
    for (const FigureField& field : kFigureFields) file.write_double_attribute(g, field.name, figures.*field.member);
    const auto r1 = static_cast<std::uint64_t>(t.ranks[0]), r2 = static_cast<std::uint64_t>(t.ranks[1]),
               r3 = static_cast<std::uint64_t>(t.ranks[2]);
    // The column-major R1×R2×R3 core IS the C-order (R3, R2, R1) array (as for the aligned tensor).
    file.write_array(g + "/core", t.core.data(), c_order_shape(t.core), {"sample_rank", "time_rank", "dof_rank"}, "cm");
    const std::vector<double> dof = to_c_order(t.U[0]), time = to_c_order(t.U[1]), sample = to_c_order(t.U[2]);
    file.write_array(g + "/dof_basis", dof.data(), {static_cast<std::uint64_t>(t.U[0].rows()), r1}, {"dof", "dof_rank"},
                     "");
    file.write_array(g + "/time_basis", time.data(), {static_cast<std::uint64_t>(t.U[1].rows()), r2},
                     {"time", "time_rank"}, "");
    file.write_array(g + "/sample_basis", sample.data(), {static_cast<std::uint64_t>(t.U[2].rows()), r3},
                     {"sample", "sample_rank"}, "");
    const auto d = static_cast<std::uint64_t>(m.mean.size());
    file.write_array(g + "/mean", m.mean.data(), {d}, {"dof"}, "pose");
    file.write_array(g + "/weight", m.weight.data(), {d}, {"dof"}, "cm/pose");
}

StoredModel read_model(const h5::File& file, const std::string& set) {
    const std::string g = model_path(set);
    const std::string a = aligned_path(set);
    if (file.type_of(a) != h5::ObjectType::Group)
        throw StoreError(file.name(), g,
                         "a model requires the aligned tensor it describes, but " + a + " does not exist");
    const h5::DatasetInfo tensor_info = file.dataset_info(a + "/tensor");
    if (tensor_info.shape.size() != 3)
        throw StoreError(file.name(), a + "/tensor",
                         "expected 3 dimensions (sample, time, dof), found shape " + h5::shape_text(tensor_info.shape));
    const std::uint64_t n = tensor_info.shape[0], t = tensor_info.shape[1], d = tensor_info.shape[2];

    StoredModel out;
    tensor::TuckerModel& tm = out.model.tucker;
    tm.method = parse_enum(file, g, "method", file.read_string_attribute(g, "method"), kMethods);
    tm.status = parse_enum(file, g, "status", file.read_string_attribute(g, "status"), kTuckerStatuses);
    const std::int64_t iterations = file.read_int_attribute(g, "iterations");
    if (iterations < 0 || iterations > 1000000000)
        throw StoreError(
            file.name(), g,
            "attribute 'iterations': expected 0 <= iterations <= 1e9, found " + std::to_string(iterations));
    tm.iterations = static_cast<int>(iterations);
    tm.fit = finite_attribute(file, g, "fit", false);
    tm.error_bound = finite_attribute(file, g, "error_bound", true);
    tm.data_norm = finite_attribute(file, g, "data_norm", true);
    tm.fit_history = {tm.fit};  // the history of a decomposition is not stored
    for (const FigureField& field : kFigureFields)
        out.figures.*field.member = finite_attribute(file, g, field.name, true);

    const std::string why_dims =
        "(the aligned tensor " + a + "/tensor is " + h5::shape_text(tensor_info.shape) + " = (N, T, D))";
    // The core (tens of MB) is read straight into the model once its shape is checked.
    std::uint64_t r1 = 0, r2 = 0, r3 = 0;
    const std::uint64_t dims[3] = {d, t, n};
    const h5::Shape core_shape = file.read_array_into<double>(g + "/core", 3, [&](const h5::Shape& shape) {
        r3 = shape[0];
        r2 = shape[1];
        r1 = shape[2];
        const std::uint64_t ranks[3] = {r1, r2, r3};
        const char* const rank_names[3] = {"R1", "R2", "R3"};
        const char* const dim_names[3] = {"D", "T", "N"};
        for (int k = 0; k < 3; ++k)
            if (ranks[k] < 1 || ranks[k] > dims[k])
                throw StoreError(file.name(), g + "/core",
                                 std::string("core shape (R3, R2, R1) = ") + h5::shape_text(shape) +
                                     ": expected 1 <= " + rank_names[k] + " <= " + dim_names[k] + " = " +
                                     std::to_string(dims[k]) + " " + why_dims);
        tm.ranks = {static_cast<Eigen::Index>(r1), static_cast<Eigen::Index>(r2), static_cast<Eigen::Index>(r3)};
        tm.core = Tensor3(tm.ranks[0], tm.ranks[1], tm.ranks[2]);  // column-major R1xR2xR3 = C-order (R3, R2, R1)
        return tm.core.data();
    });
    expect_finite(file, g + "/core", tm.core.data(), tm.core.data() + tm.core.size());
    const std::uint64_t ranks[3] = {r1, r2, r3};

    const std::string why_core =
        "(core " + g + "/core is " + h5::shape_text(core_shape) + " = (R3, R2, R1); " + why_dims.substr(1);
    const char* const bases[3] = {"dof_basis", "time_basis", "sample_basis"};
    for (int k = 0; k < 3; ++k) {
        const std::string path = g + "/" + bases[k];
        const auto basis = file.read_array<double>(path, 2);
        expect_shape(file, path, {dims[k], ranks[k]}, why_core, basis.shape);
        expect_finite(file, path, basis.data);
        tm.U[static_cast<std::size_t>(k)] =
            from_c_order(basis.data, static_cast<Eigen::Index>(dims[k]), static_cast<Eigen::Index>(ranks[k]));
    }
    const auto mean = file.read_array<double>(g + "/mean", 1);
    expect_shape(file, g + "/mean", {d}, why_dims, mean.shape);
    expect_finite(file, g + "/mean", mean.data);
    out.model.mean = Eigen::Map<const VecX>(mean.data.data(), static_cast<Eigen::Index>(d));
    const auto weight = file.read_array<double>(g + "/weight", 1);
    expect_shape(file, g + "/weight", {d}, why_dims, weight.shape);
    expect_finite(file, g + "/weight", weight.data);
    for (std::size_t i = 0; i < weight.data.size(); ++i)
        if (!(weight.data[i] > 0.0))
            throw StoreError(
                file.name(), g + "/weight",
                "expected weights > 0, found " + std::to_string(weight.data[i]) + " at element " + std::to_string(i));
    out.model.weight = Eigen::Map<const VecX>(weight.data.data(), static_cast<Eigen::Index>(d));
    try {
        compression::check(out.model, "stored model");
    } catch (const InvalidArgument& e) {
        throw StoreError(file.name(), g, e.what());
    }
    return out;
}

std::uint64_t model_stored_bytes(const h5::File& file, const std::string& set) {
    const std::string g = model_path(set);
    if (file.type_of(g) != h5::ObjectType::Group) return 0;
    std::uint64_t total = 0;
    for (const char* name : kModelDatasets) {
        const std::string path = g + "/" + name;
        if (file.type_of(path) == h5::ObjectType::Dataset) total += file.dataset_info(path).stored_bytes;
    }
    return total;
}

}  // namespace mocapdb::store
