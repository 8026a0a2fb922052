// HOOI refinement: never worse than its HOSVD start, non-increasing error over the sweeps.
#include <catch2/catch.hpp>

#include "mocapdb/core/error.hpp"
#include "mocapdb/tensor/hooi.hpp"
#include "tensor_fixtures.hpp"

using namespace mocapdb;
using namespace mocapdb::tensor;
using mocapdb::test::low_rank_tensor;
using mocapdb::test::random_tensor;

TEST_CASE("HOOI error <= HOSVD error at equal ranks, fit non-decreasing", "[tensor][hooi]") {
    struct Case {
        Tensor3 a;
        Ranks r;
    };
    const Case cases[] = {
        {random_tensor(12, 15, 10, 61), {4, 5, 3}},
        {low_rank_tensor({20, 25, 18}, {5, 4, 6}, 0.3, 62), {3, 3, 3}},
        {random_tensor(30, 20, 25, 63), {6, 2, 7}},
    };
    for (const Case& c : cases) {
        const TuckerModel h = hosvd(c.a, c.r);
        HooiOptions opt;
        opt.tolerance = 1e-10;
        opt.max_iterations = 200;
        const TuckerModel o = hooi(c.a, c.r, opt);
        const double eh = absolute_error(c.a, h);
        const double eo = absolute_error(c.a, o);
        INFO("HOSVD error " << eh << ", HOOI error " << eo << " after " << o.iterations << " sweeps, status "
                            << to_string(o.status) << ", bound " << o.error_bound);
        CHECK(o.method == TuckerMethod::Hooi);
        CHECK(eo <= eh * (1.0 + 1e-12));
        CHECK(eo <= o.error_bound * (1.0 + 1e-12));
        // Random tensors can converge slowly: MaxIterations is a legitimate outcome, Stalled too.
        REQUIRE(o.fit_history.size() >= 1);
        CHECK(o.fit_history.size() == static_cast<std::size_t>(o.iterations) + 1);
        CHECK(std::abs(o.fit_history.front() - h.fit) <= 1e-12);
        for (std::size_t i = 1; i < o.fit_history.size(); ++i) CHECK(o.fit_history[i] >= o.fit_history[i - 1]);
        CHECK(std::abs((1.0 - o.fit) * o.data_norm - eo) <= 1e-8 * o.data_norm);
        for (const MatX& u : o.U) {
            CHECK((u.transpose() * u - MatX::Identity(u.cols(), u.cols())).cwiseAbs().maxCoeff() < 1e-12);
        }
    }
}

TEST_CASE("HOOI stops on max_iterations and starts from any model", "[tensor][hooi]") {
    const Tensor3 a = random_tensor(12, 15, 10, 71);
    HooiOptions opt;
    opt.tolerance = 0.0;
    opt.max_iterations = 3;
    const TuckerModel o = hooi(a, {3, 4, 2}, opt);
    CHECK(o.iterations <= 3);
    CHECK((o.status == TuckerStatus::MaxIterations || o.status == TuckerStatus::Stalled));
    opt.max_iterations = 0;
    const TuckerModel z = hooi(a, {3, 4, 2}, opt);
    CHECK(z.iterations == 0);
    CHECK(relative_error(a, z) == Approx(relative_error(a, hosvd(a, {3, 4, 2}))).epsilon(1e-12));
    // From an ST-HOSVD start.
    opt.max_iterations = 50;
    opt.tolerance = 1e-9;
    const TuckerModel st = st_hosvd(a, {3, 4, 2});
    const TuckerModel f = hooi(a, st, opt);
    CHECK(absolute_error(a, f) <= absolute_error(a, st) * (1.0 + 1e-12));
}

TEST_CASE("HOOI rejects bad arguments", "[tensor][hooi]") {
    const Tensor3 a = random_tensor(4, 5, 6, 81);
    CHECK_THROWS_AS(hooi(a, Ranks{0, 1, 1}), InvalidArgument);
    CHECK_THROWS_AS(hooi(a, Ranks{1, 1, 7}), InvalidArgument);
    HooiOptions opt;
    opt.tolerance = -1.0;
    CHECK_THROWS_AS(hooi(a, Ranks{1, 1, 1}, opt), InvalidArgument);
    opt.tolerance = 1e-8;
    opt.max_iterations = -1;
    CHECK_THROWS_AS(hooi(a, Ranks{1, 1, 1}, opt), InvalidArgument);
    const TuckerModel other = hosvd(random_tensor(4, 5, 7, 82), {1, 1, 1});
    CHECK_THROWS_AS(hooi(a, other), InvalidArgument);
    CHECK_THROWS_AS(hooi(Tensor3(4, 0, 6), Ranks{1, 1, 1}), InvalidArgument);
}
