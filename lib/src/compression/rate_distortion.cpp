#include "mocapdb/core/stopwatch.hpp"
#include "mocapdb/core/float32.hpp"
#include "mocapdb/compression/rate_distortion.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>

#include "mocapdb/compression/codecs/deflate.hpp"
#include "mocapdb/compression/codecs/pca_baseline.hpp"
#include "mocapdb/compression/codecs/quantize.hpp"
#include "mocapdb/compression/codecs/residual_layer.hpp"
#include "mocapdb/compression/codecs/zfp_codec.hpp"
#include "mocapdb/compression/byte_accounting.hpp"
#include "mocapdb/compression/dof_weights.hpp"
#include "mocapdb/compression/rank_search.hpp"
#include "mocapdb/core/error.hpp"
#include "mocapdb/tensor/rank_selection.hpp"

namespace mocapdb::compression {
namespace {

using Clock = std::chrono::steady_clock;

// The model as a float32 file would hold it.
tensor::TuckerModel rounded_to_float32(tensor::TuckerModel m) {
    m.core = compression::codecs::round_to_float32(m.core);
    for (MatX& u : m.U) round_entries_to_float32(u);
    return m;
}

Tensor3 add(const Tensor3& a, const Tensor3& b) {
    Tensor3 out = a;
    for (Eigen::Index i = 0; i < out.size(); ++i) out.data()[i] += b.data()[i];
    return out;
}

Tensor3 subtract(const Tensor3& a, const Tensor3& b) {
    Tensor3 out = a;
    for (Eigen::Index i = 0; i < out.size(); ++i) out.data()[i] -= b.data()[i];
    return out;
}

// Decoding time per pose of a whole-set decoder, median of 3.
template <class Decode>
double stream_us_per_pose(Decode decode, Eigen::Index poses) {
    std::vector<double> runs;
    for (int i = 0; i < 3; ++i) {
        const auto start = Clock::now();
        decode();
        runs.push_back(seconds_since(start) * 1e6 / static_cast<double>(poses));
    }
    std::sort(runs.begin(), runs.end());
    return runs[1];
}

struct Context {
    const Tensor3& poses;
    const PreparedSet& prepared;
    const compression::JointErrorMeter& meter;
    std::uint64_t raw_bytes;
    std::uint64_t side_bytes;
    std::uint64_t mean_weight_bytes;  // float32 mean and weight per dof
    Eigen::Index pose_count;

    RateRow row(const std::string& method, double target, std::uint64_t payload) const {
        RateRow r;
        r.method = method;
        r.target_cm = target;
        r.bytes = payload + side_bytes;
        r.ratio = static_cast<double>(raw_bytes) / static_cast<double>(r.bytes);
        return r;
    }
    Tensor3 poses_of(const Tensor3& x) const { return from_weighted_centred(x, prepared.mean, prepared.weight); }
};

RateRow tucker_row(const Context& c, double target) {
    const RankSearchResult found = search_ranks_for_max_error(c.prepared, c.meter, target);
    const auto start = Clock::now();
    SetModel m = hosvd_model(c.prepared, found.model.tucker.ranks);
    const double precompute = seconds_since(start);
    m.tucker = rounded_to_float32(m.tucker);
    RateRow r = c.row("tucker", target,
                      kFloat32 * static_cast<std::uint64_t>(m.tucker.parameter_count()) + c.mean_weight_bytes);
    r.ranks = {m.tucker.ranks[0], m.tucker.ranks[1], m.tucker.ranks[2]};
    r.stats = c.meter.measure(m.reconstruct());
    r.target_met = r.stats.max_cm <= target;
    r.precompute_s = precompute;
    r.us_per_pose = time_pose_evaluation(m.tucker);
    r.access = "pose";
    return r;
}

// The "tucker" row's ranks with core and bases quantized and deflated (no residual): what
// quantization alone saves, and what it costs in error.
RateRow quantized_row(const Context& c, const RateRow& tucker, int bits) {
    compression::codecs::QuantizeTuckerOptions q;
    q.core_bits = q.basis_bits = bits;
    const auto start = Clock::now();
    SetModel m = hosvd_model(c.prepared, {tucker.ranks[0], tucker.ranks[1], tucker.ranks[2]});
    const compression::codecs::QuantizedTucker quantized = compression::codecs::quantize_tucker(m.tucker, q);
    const double precompute = seconds_since(start);
    m.tucker = quantized.model;
    RateRow r =
        c.row("tucker-q" + std::to_string(bits), tucker.target_cm, quantized.best_bytes() + c.mean_weight_bytes);
    r.ranks = tucker.ranks;
    r.setting = bits;
    r.stats = c.meter.measure(m.reconstruct());
    r.target_met = r.stats.max_cm <= tucker.target_cm;
    r.precompute_s = precompute;
    r.us_per_pose = time_pose_evaluation(m.tucker);
    r.access = "pose";
    return r;
}

RateRow hooi_row(const Context& c, const RateRow& tucker, int iterations) {
    const tensor::Ranks ranks{tucker.ranks[0], tucker.ranks[1], tucker.ranks[2]};
    tensor::HooiOptions options;
    options.max_iterations = iterations;
    const auto start = Clock::now();
    SetModel m;
    m.mean = c.prepared.mean;
    m.weight = c.prepared.weight;
    m.tucker = tensor::hooi(c.prepared.x, ranks, options);
    const double precompute = seconds_since(start);
    m.tucker = rounded_to_float32(m.tucker);
    RateRow r = c.row("tucker-hooi", tucker.target_cm, tucker.bytes - c.side_bytes);
    r.ranks = tucker.ranks;
    r.setting = m.tucker.iterations;
    r.stats = c.meter.measure(m.reconstruct());
    r.target_met = r.stats.max_cm <= tucker.target_cm;
    r.precompute_s = precompute;
    r.us_per_pose = time_pose_evaluation(m.tucker);
    r.access = "pose";
    return r;
}

// A lossy reconstruction of X that the residual layer completes.
struct LossyCandidate {
    std::vector<long long> ranks;
    Tensor3 x_hat;              // what the lossy part's decoder gives
    std::uint64_t payload = 0;  // its stored bytes
    double fit_seconds = 0.0;
    std::function<Tensor3()> decode;  // the lossy decoder, for timing
};

// The cheapest candidate + residual whose measured max error meets the target. A residual step of
// 2·target in X bounds every joint by target (dof_weights.hpp); measured errors are far below that
// bound, so the largest multiple s ∈ [1, 64] of it that still meets the target is searched.
RateRow best_with_residual(const Context& c, const std::string& method, double target,
                           const std::vector<LossyCandidate>& candidates) {
    RateRow best;
    for (const LossyCandidate& cand : candidates) {
        const Tensor3 residual = subtract(c.prepared.x, cand.x_hat);
        double lo = 0.0, hi = std::log(64.0);
        for (int i = 0; i < 8; ++i) {
            const double s = i == 0 ? 1.0 : std::exp(0.5 * (lo + hi));
            const auto encode_start = Clock::now();
            const compression::codecs::ResidualEncoding enc =
                compression::codecs::encode_residual(residual, s * target);
            const double encode_seconds = seconds_since(encode_start);
            const compression::JointErrorStats stats = c.meter.measure(c.poses_of(add(cand.x_hat, enc.decoded)));
            const bool ok = stats.max_cm <= target;
            if (i == 0 && !ok) break;  // even the bounded step failed (channel projection): skip the candidate
            if (i > 0) (ok ? lo : hi) = 0.5 * (lo + hi);
            if (!ok) continue;
            const std::uint64_t payload = cand.payload + enc.stream.payload_bytes() + c.mean_weight_bytes;
            if (best.bytes != 0 && payload + c.side_bytes >= best.bytes) continue;
            best = c.row(method, target, payload);
            best.ranks = cand.ranks;
            best.setting = s * target;
            best.stats = stats;
            best.precompute_s = cand.fit_seconds + encode_seconds;
            best.access = "stream";
            best.us_per_pose = stream_us_per_pose(
                [&] {
                    if (add(cand.decode(), compression::codecs::decode_residual(enc.stream.bytes)).size() == 0)
                        throw Error("empty decode");
                },
                c.pose_count);
        }
    }
    if (best.bytes == 0) {
        best = c.row(method, target, c.raw_bytes);
        best.target_met = false;
        best.access = "stream";
    }
    return best;
}

RateRow tucker_residual_row(const Context& c, double target, int bits) {
    compression::codecs::QuantizeTuckerOptions q;
    q.core_bits = q.basis_bits = bits;
    // Rungs of the rank ladder: the fewest-parameter ranks for each relative bound.
    std::vector<tensor::Ranks> rungs;
    for (double e : {0.4, 0.25, 0.15, 0.1, 0.06, 0.04, 0.025, 0.015}) {
        const tensor::Ranks r = tensor::ranks_for_error_bound(c.prepared.bases.spectra, e);
        if (std::find(rungs.begin(), rungs.end(), r) == rungs.end()) rungs.push_back(r);
    }
    std::vector<LossyCandidate> candidates;
    for (const tensor::Ranks& ranks : rungs) {
        const auto start = Clock::now();
        const compression::codecs::QuantizedTucker quantized =
            compression::codecs::quantize_tucker(hosvd_model(c.prepared, ranks).tucker, q);
        LossyCandidate cand;
        cand.ranks = {ranks[0], ranks[1], ranks[2]};
        cand.x_hat = quantized.model.reconstruct();
        cand.fit_seconds = seconds_since(start);
        cand.payload = quantized.best_bytes();
        const compression::codecs::Bytes stream = quantized.deflated.bytes;
        cand.decode = [stream] { return compression::codecs::decode_quantized_tucker(stream).reconstruct(); };
        candidates.push_back(std::move(cand));
    }
    RateRow r = best_with_residual(c, "tucker+residual", target, candidates);
    return r;
}

RateRow pca_residual_row(const Context& c, const compression::codecs::SamplePca& pca, double target) {
    std::vector<LossyCandidate> candidates;
    for (Eigen::Index k = 0; k <= pca.max_components(); k = k == 0 ? 1 : 2 * k) {
        LossyCandidate cand;
        cand.ranks = {static_cast<long long>(k)};
        cand.x_hat = pca.reconstruct(k);
        cand.payload = pca.stored_bytes(k);
        cand.decode = [&pca, k] { return pca.reconstruct(k); };
        candidates.push_back(std::move(cand));
    }
    return best_with_residual(c, "pca+residual", target, candidates);
}

RateRow pca_row(const Context& c, const compression::codecs::SamplePca& pca, double target) {
    // Linear scan: with float32 storage the error need not fall monotonically with k.
    RateRow best;
    for (Eigen::Index k = 0; k <= pca.max_components(); ++k) {
        const compression::JointErrorStats s = c.meter.measure(c.poses_of(pca.reconstruct(k)));
        if (s.max_cm > target && k < pca.max_components()) continue;
        best = c.row("pca", target, pca.stored_bytes(k));
        best.ranks = {static_cast<long long>(k)};
        best.stats = s;
        best.target_met = s.max_cm <= target;
        break;
    }
    const auto k = static_cast<Eigen::Index>(best.ranks[0]);
    best.access = "stream";
    best.us_per_pose = stream_us_per_pose([&] { (void)pca.reconstruct(k); }, c.pose_count);
    return best;
}

RateRow zfp_row(const Context& c, double target) {
    double lo = std::log(target * 1e-3), hi = std::log(target * 256.0);
    RateRow best;
    bool found = false;
    for (int i = 0; i < 14; ++i) {
        const double tol = std::exp(0.5 * (lo + hi));
        const auto start = Clock::now();
        const compression::codecs::EncodedStream s = compression::codecs::zfp_encode(c.prepared.x, tol);
        const double seconds = seconds_since(start);
        const compression::JointErrorStats stats =
            c.meter.measure(c.poses_of(compression::codecs::zfp_decode(s.bytes)));
        if (stats.max_cm <= target) {
            lo = 0.5 * (lo + hi);
            if (!found || s.payload_bytes() + c.mean_weight_bytes + c.side_bytes < best.bytes) {
                best = c.row("zfp", target, s.payload_bytes() + c.mean_weight_bytes);
                best.setting = tol;
                best.stats = stats;
                best.precompute_s = seconds;
                best.access = "stream";
                best.us_per_pose =
                    stream_us_per_pose([&] { (void)compression::codecs::zfp_decode(s.bytes); }, c.pose_count);
                found = true;
            }
        } else {
            hi = 0.5 * (lo + hi);
        }
    }
    if (!found) {
        best = c.row("zfp", target, c.raw_bytes);
        best.target_met = false;
        best.access = "stream";
    }
    return best;
}

}  // namespace

double time_pose_evaluation(const tensor::TuckerModel& model) {
    const tensor::PoseEvaluator evaluator(model);
    tensor::PoseEvaluator::Workspace ws;
    VecX pose(evaluator.dofs());
    const Eigen::Index frames = model.U[1].rows(), samples = model.U[2].rows();
    const int per_round = 20000;
    double sink = 0.0;
    std::vector<double> rounds;
    const double round_limit_s = 0.1;
    for (int round = 0; round < 5; ++round) {
        const auto start = Clock::now();
        int done = 0;
        for (int i = 0; i < per_round; ++i) {
            evaluator.evaluate(model.U[1].row(i % frames), model.U[2].row((i / frames) % samples), pose, ws);
            sink += pose[0];
            ++done;
            if ((i & 15) == 15 && seconds_since(start) > round_limit_s) break;
        }
        rounds.push_back(seconds_since(start) * 1e6 / done);
    }
    std::sort(rounds.begin(), rounds.end());
    return std::isfinite(sink) ? rounds[2] : rounds[2] + 0.0;  // sink keeps the loop alive
}

RateReport rate_distortion(const Tensor3& poses, std::shared_ptr<const Skeleton> skeleton, const RateOptions& options) {
    for (double t : options.max_cm)
        if (!(t > 0.0) || !std::isfinite(t))
            throw InvalidArgument("rate_distortion: every max-error target must be a finite number of cm > 0");
    RateReport report;
    report.dims = tensor::dims_of(poses);
    report.raw_bytes = aligned_float32_bytes(poses);
    report.side_bytes = side_info_bytes(poses.dimension(1), poses.dimension(2), options.parameters);

    const VecX weight = position_error_weights(*skeleton);
    const compression::JointErrorMeter meter(skeleton, poses);
    const PreparedSet prepared = prepare_set(poses, weight);
    const Context c{poses,
                    prepared,
                    meter,
                    report.raw_bytes,
                    report.side_bytes,
                    2 * kFloat32 * static_cast<std::uint64_t>(poses.dimension(0)),
                    poses.dimension(1) * poses.dimension(2)};

    const std::uint64_t total = 2 + options.max_cm.size() * (options.hooi ? 7 : 6);
    const auto emit = [&](const RateRow& r) {
        report.rows.push_back(r);
        if (options.progress) options.progress({report.rows.size(), total, r.method});
    };
    {  // the paper's "full" row: the aligned poses as float32
        RateRow r = c.row("raw-float32", 0.0, report.raw_bytes);
        r.stats = meter.measure(compression::codecs::round_to_float32(poses));
        r.access = "pose";
        emit(r);
    }
    {  // lossless float32 deflate of the poses
        const auto start = Clock::now();
        const compression::codecs::EncodedStream s = compression::codecs::encode_float32_deflate(poses);
        RateRow r = c.row("deflate", 0.0, s.payload_bytes());
        r.precompute_s = seconds_since(start);
        r.stats = meter.measure(compression::codecs::decode_float32_deflate(s.bytes));
        r.access = "stream";
        r.us_per_pose =
            stream_us_per_pose([&] { (void)compression::codecs::decode_float32_deflate(s.bytes); }, c.pose_count);
        emit(r);
    }
    const auto pca_start = Clock::now();
    const compression::codecs::SamplePca pca(prepared.x);
    const double pca_seconds = seconds_since(pca_start);
    for (double target : options.max_cm) {
        const RateRow tucker = tucker_row(c, target);
        emit(tucker);
        if (options.hooi) emit(hooi_row(c, tucker, options.hooi_iterations));
        emit(quantized_row(c, tucker, options.quantization_bits));
        emit(tucker_residual_row(c, target, options.quantization_bits));
        RateRow p = pca_row(c, pca, target);
        p.precompute_s = pca_seconds;
        emit(p);
        RateRow pr = pca_residual_row(c, pca, target);
        pr.precompute_s += pca_seconds;
        emit(pr);
        emit(zfp_row(c, target));
    }
    return report;
}

}  // namespace mocapdb::compression
