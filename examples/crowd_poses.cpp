// Synthesizes a crowd: N characters at random control parameters inside the set's parameter box, all
// posed at every aligned frame with one batched call per frame (the compressed synthesis model).
//   example_crowd_poses DB.h5 SET [N]
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <random>

#include "mocapdb/workflow/load_model.hpp"

int main(int argc, char** argv) {
    if (argc != 3 && argc != 4) {
        std::fprintf(stderr, "usage: %s DB.h5 SET [N]\n", argv[0]);
        return 2;
    }
    try {
        const mocapdb::Database db(argv[1]);
        const auto model = mocapdb::workflow::load_motion_model(db, argv[2]);
        const Eigen::Index n = argc == 4 ? std::atol(argv[3]) : 1000;
        if (n < 1) throw std::invalid_argument("N must be at least 1");
        const mocapdb::MatX& samples = model->sample_parameters();
        const Eigen::VectorXd lo = samples.colwise().minCoeff(), hi = samples.colwise().maxCoeff();
        std::mt19937 rng(1);
        std::uniform_real_distribution<double> unit(0.0, 1.0);
        mocapdb::MatX c(n, samples.cols());
        for (Eigen::Index q = 0; q < n; ++q)
            for (Eigen::Index p = 0; p < c.cols(); ++p) c(q, p) = lo(p) + unit(rng) * (hi(p) - lo(p));

        mocapdb::MatX poses(model->dofs(), n);
        mocapdb::synthesis::BatchWorkspace ws;
        const auto start = std::chrono::steady_clock::now();
        double checksum = 0.0;
        for (Eigen::Index t = 0; t < model->frames(); ++t) {
            model->poses(c, static_cast<double>(t), poses, ws);
            checksum += poses.row(1).mean();  // the root's height
        }
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        const double count = static_cast<double>(n * model->frames());
        const mocapdb::VecX rho = model->reliability_batch(c);
        std::printf("set %s: %lld characters x %lld aligned frames = %.0f poses of %lld values in %.3f s (%.2f us per pose)\n",
                    argv[2], static_cast<long long>(n), static_cast<long long>(model->frames()), count,
                    static_cast<long long>(model->dofs()), seconds, 1e6 * seconds / count);
        std::printf("mean root height %.1f cm; reliability %.2f .. %.2f\n", checksum / static_cast<double>(model->frames()),
                    rho.minCoeff(), rho.maxCoeff());
        return poses.allFinite() ? 0 : 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "example_crowd_poses: %s\n", e.what());
        return 1;
    }
}
