// run_on_workers / run_parallel_tasks: an exception on any worker thread reaches
// the caller, as on one thread (the lowest task index that threw), never std::terminate.
#include <catch2/catch.hpp>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "mocapdb/core/parallel_tasks.hpp"

using namespace mocapdb;

namespace {

/// Task 0 holds its worker until task 1 has run on the other worker (or 20 s have passed).
void wait_for(const std::atomic<bool>& flag) {
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    while (!flag.load() && std::chrono::steady_clock::now() < until) std::this_thread::yield();
}

}  // namespace

TEST_CASE("run_on_workers: every task once, worker indices in range, per-worker state", "[core][threads]") {
    for (std::size_t workers : {1u, 2u, 3u}) {
        std::vector<std::atomic<int>> runs(100);
        std::vector<std::size_t> per_worker(workers, 0);  // each worker writes only its own entry
        run_on_workers(workers, runs.size(), [&](std::size_t i, std::size_t w) {
            REQUIRE(w < workers);
            ++runs[i];
            ++per_worker[w];
        });
        std::size_t total = 0;
        for (std::size_t n : per_worker) total += n;
        CHECK(total == runs.size());
        for (const auto& r : runs) CHECK(r.load() == 1);
    }
    run_on_workers(2, 0, [](std::size_t, std::size_t) { FAIL("no task"); });
}

TEST_CASE("run_on_workers: an exception on the second worker is the caller's", "[core][threads]") {
    std::atomic<bool> second_ran{false};
    std::atomic<std::size_t> first_worker{99}, second_worker{99};
    const auto task = [&](std::size_t i, std::size_t w) {
        if (i == 0) {
            first_worker = w;
            wait_for(second_ran);
            return;
        }
        if (i == 1) {
            second_worker = w;
            second_ran = true;
            throw std::runtime_error("task 1 failed");
        }
    };
    CHECK_THROWS_WITH(run_on_workers(2, 50, task), "task 1 failed");
    // Task 1 ran on the other worker (whichever took task 0 was held there; which one that is
    // depends on which thread started first).
    CHECK(second_worker.load() < 2);
    CHECK(second_worker.load() != first_worker.load());
}

TEST_CASE("run_on_workers: of several failures, the lowest task index is rethrown (as one thread reports it)",
          "[core][threads]") {
    std::atomic<bool> second_ran{false};
    const auto task = [&](std::size_t i, std::size_t) {
        if (i == 0) {
            wait_for(second_ran);  // fails after task 1 did
            throw std::invalid_argument("task 0 failed");
        }
        if (i == 1) {
            second_ran = true;
            throw std::runtime_error("task 1 failed");
        }
    };
    CHECK_THROWS_WITH(run_on_workers(2, 10, task), "task 0 failed");
    CHECK_THROWS_WITH(run_on_workers(1, 10, task), "task 0 failed");
    // run_parallel_tasks (the machine's cores) carries a worker's exception the same way.
    CHECK_THROWS_WITH(run_parallel_tasks(64, [](std::size_t i) {
                          if (i % 2 == 1) throw std::runtime_error("odd task " + std::to_string(i));
                      }),
                      "odd task 1");
}
