#include <catch2/catch.hpp>

#include "mocapdb/core/error.hpp"
#include "mocapdb/tensor/hosvd.hpp"
#include "mocapdb/tensor/streamed_tucker.hpp"
#include "tensor_fixtures.hpp"

using namespace mocapdb;
using namespace mocapdb::tensor;
using mocapdb::test::low_rank_tensor;
using mocapdb::test::random_tensor;

namespace {

// Serves the slices of an in-memory tensor and counts the reads.
struct CountingSource {
    const Tensor3& a;
    int reads = 0;
    void operator()(Eigen::Index n, Eigen::Ref<MatX> out) {
        ++reads;
        out = Eigen::Map<const MatX>(a.data() + n * a.dimension(0) * a.dimension(1), a.dimension(0), a.dimension(1));
    }
};

double max_abs(const Tensor3& x) {
    double m = 0.0;
    for (Eigen::Index i = 0; i < x.size(); ++i) m = std::max(m, std::abs(x.data()[i]));
    return m;
}

Tensor3 difference(const Tensor3& a, const Tensor3& b) {
    Tensor3 d = a;
    for (Eigen::Index i = 0; i < d.size(); ++i) d.data()[i] -= b.data()[i];
    return d;
}

}  // namespace

TEST_CASE("streamed Tucker: full ranks exact, error = bound identity, two passes", "[tensor][stream]") {
    const Tensor3 a = random_tensor(9, 11, 14, 5);
    CountingSource source{a};
    const TuckerModel full = streamed_tucker(std::ref(source), dims_of(a), {9, 11, 14});
    CHECK(source.reads == 2 * 14);
    CHECK(max_abs(difference(full.reconstruct(), a)) <= 1e-10 * max_abs(a));

    for (const Ranks ranks : {Ranks{4, 5, 3}, Ranks{9, 11, 2}, Ranks{2, 2, 7}}) {
        CountingSource s{a};
        const TuckerModel m = streamed_tucker(std::ref(s), dims_of(a), ranks);
        const double error = absolute_error(a, m);
        INFO("ranks " << ranks[0] << "x" << ranks[1] << "x" << ranks[2] << ": error " << error << ", bound "
                      << m.error_bound);
        CHECK(error <= m.error_bound * (1 + 1e-10));
        CHECK(m.relative_error_estimate() == Approx(relative_error(a, m)).margin(1e-9));
        for (int k = 0; k < 3; ++k)
            CHECK((m.U[static_cast<std::size_t>(k)].transpose() * m.U[static_cast<std::size_t>(k)] -
                   MatX::Identity(ranks[static_cast<std::size_t>(k)], ranks[static_cast<std::size_t>(k)]))
                      .cwiseAbs()
                      .maxCoeff() <= 1e-10);
    }
}

TEST_CASE("streamed Tucker equals HOSVD when only the sample mode is truncated", "[tensor][stream]") {
    // With U_dof and U_time complete, the projected sample Gram is the HOSVD's sample Gram.
    const Tensor3 a = low_rank_tensor({10, 12, 30}, {4, 5, 6}, 0.01, 9);
    CountingSource s{a};
    const TuckerModel streamed = streamed_tucker(std::ref(s), dims_of(a), {10, 12, 6});
    const TuckerModel reference = hosvd(a, {10, 12, 6});
    CHECK(max_abs(difference(streamed.reconstruct(), reference.reconstruct())) <= 1e-9 * max_abs(a));
    // More samples than projected values (N > R1 R2): the small Gram path.
    CountingSource s2{a};
    const TuckerModel narrow = streamed_tucker(std::ref(s2), dims_of(a), {2, 2, 4});
    CHECK(absolute_error(a, narrow) <= narrow.error_bound * (1 + 1e-10));
}

TEST_CASE("streamed Tucker refuses bad ranks and non-finite slices", "[tensor][stream]") {
    const Tensor3 a = random_tensor(4, 5, 6, 3);
    CountingSource s{a};
    CHECK_THROWS_AS(streamed_tucker(std::ref(s), dims_of(a), {5, 5, 6}), InvalidArgument);
    const SliceSource bad = [](Eigen::Index, Eigen::Ref<MatX> out) { out.setConstant(std::nan("")); };
    CHECK_THROWS_AS(streamed_tucker(bad, {4, 5, 6}, {2, 2, 2}), InvalidArgument);
}
