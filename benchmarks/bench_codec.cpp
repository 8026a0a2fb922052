// Codec baselines on subject 16's walks (shared CMU, DTW-aligned to 100 frames): bytes at equal max
// joint-position error, and encode/decode speed. Prints one `key value` line per figure.
//   bench_codec [repeats]
// Error in cm: compression::JointErrorMeter (FK of every joint, frame and sample). Per-dof tolerances for
// a guaranteed E cm: eps_d = E / w_d with w = compression::position_error_weights(skeleton).
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "bench_timing.hpp"
#include "mocapdb/compression/codecs/deflate.hpp"
#include "mocapdb/compression/codecs/pca_baseline.hpp"
#include "mocapdb/compression/codecs/residual_layer.hpp"
#include "mocapdb/compression/codecs/zfp_codec.hpp"
#include "mocapdb/compression/dof_weights.hpp"
#include "mocapdb/dataset/alignment.hpp"
#include "mocapdb/compression/joint_error.hpp"
#include "mocapdb/io/clip_file.hpp"

using namespace mocapdb;
using namespace mocapdb::compression::codecs;
using bench::best_of;

namespace {
Tensor3 add(const Tensor3& a, const Tensor3& b, double sign) {
    Tensor3 c = a;
    for (Eigen::Index i = 0; i < c.size(); ++i) c.data()[i] += sign * b.data()[i];
    return c;
}
}  // namespace

int main(int argc, char** argv) {
    const int repeats = argc > 1 ? std::max(1, std::atoi(argv[1])) : 5;
    const std::string dir = std::string(MOCAPDB_SHARED_DIR) + "/datasets/cmu-asfamc/";
    std::vector<Clip> clips;
    for (int t = 11; t <= 34; ++t) clips.push_back(read_clip(dir + "16_" + std::to_string(t) + ".amc"));
    clips.push_back(read_clip(dir + "16_47.amc"));
    const AlignedSet aligned = align_samples(clips, AlignOptions{});
    const Tensor3& a = aligned.tensor;
    const Eigen::Index D = a.dimension(0), T = a.dimension(1), N = a.dimension(2);
    const compression::JointErrorMeter meter(clips[0].skeleton, a);
    const VecX w = compression::position_error_weights(*clips[0].skeleton);
    auto max_cm = [&](const Tensor3& x) { return meter.measure(x).max_cm; };
    const std::size_t raw = static_cast<std::size_t>(4 * a.size());
    std::printf("set subject16_walks_dtw\ndims %ld %ld %ld\nraw_float32_bytes %zu\n", static_cast<long>(D),
                static_cast<long>(T), static_cast<long>(N), raw);

    for (bool shuffle : {false, true}) {
        Float32DeflateOptions o;
        o.shuffle = shuffle;
        EncodedStream s;
        const double enc = best_of(repeats, [&] { s = encode_float32_deflate(a, o); });
        Tensor3 back;
        const double dec = best_of(repeats, [&] { back = decode_float32_deflate(s.bytes); });
        std::printf("lossless_float32%s bytes %zu ratio %.3f max_cm %.2e encode_ms %.2f decode_ms %.2f\n",
                    shuffle ? "_shuffled" : "", s.payload_bytes(), double(raw) / double(s.payload_bytes()), max_cm(back),
                    1e3 * enc, 1e3 * dec);
    }

    const SamplePca pca(a);
    std::vector<double> pca_max(static_cast<std::size_t>(pca.max_components() + 1));
    for (Eigen::Index k = 0; k <= pca.max_components(); ++k) pca_max[static_cast<std::size_t>(k)] = max_cm(pca.reconstruct(k));
    const double pca_fit = best_of(repeats, [&] { SamplePca p(a); bench::g_sink = p.singular_values()[0]; });
    std::printf("pca fit_ms %.2f\n", 1e3 * pca_fit);

    for (double target : {5.0, 1.0, 0.1}) {
        std::printf("# target max error %.2f cm\n", target);
        const VecX eps = VecX::Constant(D, target).cwiseQuotient(w);
        // zfp, per-dof tolerances from the weights: guaranteed.
        {
            EncodedStream s;
            const double enc = best_of(repeats, [&] { s = zfp_encode(a, eps); });
            Tensor3 back;
            const double dec = best_of(repeats, [&] { back = zfp_decode(s.bytes); });
            std::printf("zfp_weighted_guaranteed E %.2f bytes %zu ratio %.2f max_cm %.4f encode_ms %.2f decode_ms %.2f\n", target,
                        s.payload_bytes(), double(raw) / double(s.payload_bytes()), max_cm(back), 1e3 * enc, 1e3 * dec);
        }
        // zfp, per-dof tolerances scaled up by 2^(j/4) while the measured max stays <= target.
        {
            std::size_t best_bytes = 0;
            double best_err = 0, best_scale = 0;
            for (int j = 0; j <= 60; ++j) {
                const double s = std::pow(2.0, j / 4.0);
                const EncodedStream z = zfp_encode(a, VecX(eps * s));
                const double err = max_cm(zfp_decode(z.bytes));
                if (err > target) break;
                best_bytes = z.payload_bytes(), best_err = err, best_scale = s;
            }
            std::printf("zfp_weighted_measured E %.2f bytes %zu ratio %.2f max_cm %.4f eps_scale %.2f\n", target, best_bytes,
                        double(raw) / double(best_bytes), best_err, best_scale);
        }
        // zfp, one tolerance for every dof (plain zfp), searched over powers of two.
        {
            std::size_t best_bytes = 0;
            double best_err = 0, best_tol = 0;
            for (int j = -30; j <= 10; ++j) {
                const double tol = std::ldexp(1.0, j);
                const EncodedStream z = zfp_encode(a, tol);
                const double err = max_cm(zfp_decode(z.bytes));
                if (err > target) break;
                best_bytes = z.payload_bytes(), best_err = err, best_tol = tol;
            }
            std::printf("zfp_uniform_measured E %.2f bytes %zu ratio %.2f max_cm %.4f tolerance %.3g\n", target, best_bytes,
                        double(raw) / double(best_bytes), best_err, best_tol);
        }
        // PCA alone: the smallest k whose measured max is within the target.
        {
            Eigen::Index k = 0;
            while (k < pca.max_components() && pca_max[static_cast<std::size_t>(k)] > target) ++k;
            const bool met = pca_max[static_cast<std::size_t>(k)] <= target;
            std::printf("pca_measured E %.2f k %ld bytes %zu ratio %.2f max_cm %.4f%s\n", target, static_cast<long>(k),
                        pca.stored_bytes(k), double(raw) / double(pca.stored_bytes(k)), pca_max[static_cast<std::size_t>(k)],
                        met ? "" : " (not met at any k)");
        }
        // PCA + residual layer (guaranteed): best k.
        {
            std::size_t best_total = std::numeric_limits<std::size_t>::max();
            Eigen::Index best_k = 0;
            std::size_t best_res = 0;
            double best_err = 0;
            for (Eigen::Index k = 0; k <= std::min<Eigen::Index>(N - 1, pca.max_components()); ++k) {
                const Tensor3 lossy = pca.reconstruct(k);
                const ResidualEncoding r = encode_residual(add(a, lossy, -1.0), eps);
                const std::size_t total = pca.stored_bytes(k) + r.stream.payload_bytes();
                if (total < best_total) {
                    best_total = total, best_k = k, best_res = r.stream.payload_bytes();
                    best_err = max_cm(add(lossy, r.decoded, 1.0));
                }
            }
            std::printf("pca_plus_residual_guaranteed E %.2f k %ld bytes %zu (pca %zu + residual %zu) ratio %.2f max_cm %.4f\n",
                        target, static_cast<long>(best_k), best_total, pca.stored_bytes(best_k), best_res,
                        double(raw) / double(best_total), best_err);
        }
        // Residual layer alone on the per-dof mean (how much the layer costs with a poor lossy stage),
        // in both code orders, and its speed.
        {
            Tensor3 mean(D, T, N);
            for (Eigen::Index i = 0; i < mean.size(); ++i) mean.data()[i] = aligned.mean[i % D];
            const Tensor3 r = add(a, mean, -1.0);
            for (ResidualOrder order : {ResidualOrder::DofMajor, ResidualOrder::Storage}) {
                ResidualOptions o;
                o.order = order;
                ResidualEncoding e;
                const double enc = best_of(repeats, [&] { e = encode_residual(r, eps, o); });
                Tensor3 back;
                const double dec = best_of(repeats, [&] { back = decode_residual(e.stream.bytes); });
                std::printf("residual_on_dof_mean_%s E %.2f bytes %zu nonzero %ld encode_ms %.2f decode_ms %.2f\n",
                            order == ResidualOrder::DofMajor ? "dofmajor" : "storage", target, e.stream.payload_bytes(),
                            static_cast<long>(e.nonzero), 1e3 * enc, 1e3 * dec);
            }
        }
    }
    return 0;
}
