// advise_huge_pages (core/huge_pages.hpp) is advice only: the values of the advised memory, written before
// or after, are unchanged, whatever the range (unaligned, under 2 MB, empty, null).
#include <catch2/catch.hpp>

#include <Eigen/Core>

#include "mocapdb/core/huge_pages.hpp"

using namespace mocapdb;

TEST_CASE("advise_huge_pages keeps the values of any range", "[core]") {
    Eigen::VectorXd big(3 << 20);  // 24 MB: several 2 MB pages
    for (Eigen::Index i = 0; i < big.size(); ++i) big(i) = static_cast<double>(i) * 0.5;
    advise_huge_pages(big);                                       // touched memory
    advise_huge_pages(big.data() + 3, 5 * 1024 * 1024 + 7);       // unaligned start and length
    advise_huge_pages(nullptr, 1 << 22);                          // nothing to advise
    advise_huge_pages(big.data(), 0);
    bool same = true;
    for (Eigen::Index i = 0; i < big.size(); ++i) same = same && big(i) == static_cast<double>(i) * 0.5;
    CHECK(same);
    Eigen::MatrixXd fresh(1500, 1500);  // advised before the first write, as the library does
    advise_huge_pages(fresh);
    fresh.setConstant(2.0);
    CHECK(fresh.sum() == 2.0 * 1500.0 * 1500.0);
}
