#pragma once
// Running independent tasks on the machine's cores (issue #16: the compress rank search's forward
// kinematics and projections over 10 000 samples). Plain std::thread workers that take the next
// task index in order; no pool lives between calls.
#include <cstddef>
#include <functional>

namespace mocapdb {

/// Worker threads for `tasks` tasks: min(tasks, std::thread::hardware_concurrency()), at least 1.
std::size_t worker_count(std::size_t tasks);

/// Calls task(i) once for every i in [0, tasks), from worker_count(tasks) threads (the calling thread
/// is one of them); returns when every call has returned. Tasks start in increasing i; they must be
/// safe to run concurrently. The first exception a task throws is rethrown here after the workers
/// stop (tasks not yet started are skipped).
void run_parallel_tasks(std::size_t tasks, const std::function<void(std::size_t)>& task);

}  // namespace mocapdb
