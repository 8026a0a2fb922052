// pack_group's pass 1 (pack_stages.hpp): per window, the coarsest quantizer step whose decode meets
// the bound, found by a galloping search from the previous window's step and a bisection; then the
// tail trimmed, and the rounding (with rounding_search) whose coefficients code smallest kept.
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <sstream>

#include "mocapdb/motion/forward_kinematics.hpp"
#include "pack_stages.hpp"

namespace mocapdb::packing::detail {
namespace {

/// What every window's search of a group shares.
struct SearchSettings {
    double E = 0.0;
    int k_start = 0;        ///< the first window's step index (from E)
    std::size_t cells = 0;  ///< Da·W
    std::vector<double> roundings;
    int trim_tail = 0;
    MatX dof_inverse;  ///< the stored (rounded) bases' exact inverses
    MatX time_inverse_t;
};

/// A step that passed: its index, coefficients and distances.
struct Candidate {
    int step = -1;
    std::vector<std::int32_t> q;
    std::vector<double> dist;
};

/// The windows of one clip, searched in order (each starts from the previous window's steps).
class ClipSearch {
public:
    ClipSearch(const GroupModel& m, const Clip& clip, const ClipEntry& e, const SearchSettings& s, SearchTotals& st)
        : m_(m),
          clip_(clip),
          e_(e),
          s_(s),
          st_(st),
          skeleton_(*m.skeletons[e.skeleton].skeleton),
          x_(m.weighted_active(clip, m.skeletons[e.skeleton], e.canonical)),
          source_(joint_positions(clip)),
          q_(s.cells),
          ks_(s.roundings.size(), s.k_start),
          g_(rows_of(m), m.window),
          tmp_(rows_of(m), m.window) {}

    /// Every window of the clip into results (from the clip's first window on); returns the count.
    int run(std::vector<WindowResult>& results);

private:
    static Eigen::Index rows_of(const GroupModel& m) { return static_cast<Eigen::Index>(m.active.size()); }
    /// Where a window first misses the bound: frame (in the window), joint, distance.
    struct Miss {
        int t = 0;
        Eigen::Index j = 0;
        double d = 0.0;
    };
    void quantize_window(int w, WindowResult& r);
    bool distances(const FrameMatrix& rows, std::vector<double>& out, Miss& miss);
    bool check(int kk);
    bool probe(int kk, double rounding);
    Candidate search(double rounding, int& k);
    void trim_tail(Candidate& found);
    void store_raw(int w, WindowResult& r);

    const GroupModel& m_;
    const Clip& clip_;
    const ClipEntry& e_;
    const SearchSettings& s_;
    SearchTotals& st_;
    const Skeleton& skeleton_;  ///< as decoded (float32-rounded)
    const MatX x_;
    const MatX source_;
    GlobalPose pose_;
    FrameMatrix rows_;
    WindowScratch scratch_;
    std::vector<std::int32_t> q_;
    std::vector<double> dist_;
    std::vector<int> ks_;  ///< per rounding, the previous window's step
    MatX g_, tmp_;
    std::vector<std::uint8_t> classes_;
    Eigen::Index f0_ = 0;  ///< the window's first frame
    int count_ = 0;        ///< and its frames in the clip
};

int ClipSearch::run(std::vector<WindowResult>& results) {
    const auto frames = static_cast<Eigen::Index>(e_.frames);
    const int W = m_.window;
    const auto nw = static_cast<int>((frames + W - 1) / W);
    for (int w = 0; w < nw; ++w) {
        tmp_.noalias() = s_.dof_inverse * window_of(x_, w, W);
        g_.noalias() = tmp_ * s_.time_inverse_t;
        f0_ = static_cast<Eigen::Index>(w) * W;
        count_ = static_cast<int>(std::min<Eigen::Index>(W, frames - f0_));
        quantize_window(w, results[e_.first_window + static_cast<std::uint64_t>(w)]);
    }
    return nw;
}

void ClipSearch::quantize_window(int w, WindowResult& r) {
    Candidate best;
    std::size_t best_cost = 0;
    for (std::size_t c = 0; c < s_.roundings.size(); ++c) {
        Candidate found = search(s_.roundings[c], ks_[c]);
        if (found.step < 0) continue;
        if (s_.trim_tail > 0) trim_tail(found);
        std::size_t cost = 0;
        if (s_.roundings.size() > 1) {  // bytes with untrained contexts: a proxy to compare roundings
            position_classes(m_.levels, step_of(found.step), classes_);
            cost = encode_coefficients(found.q, classes_, m_.grid(), ContextSet()).size();
        }
        if (best.step < 0 || cost < best_cost) {
            best_cost = cost;
            best = std::move(found);
        }
    }
    if (best.step < 0) {
        store_raw(w, r);
        return;
    }
    for (double d : best.dist) st_.errors.add(d);
    std::size_t length = best.q.size();
    while (length > 0 && best.q[length - 1] == 0) --length;
    best.q.resize(length);
    position_classes(m_.levels, step_of(best.step), classes_);
    count_coefficients(best.q, classes_, m_.grid(), st_.counts);
    r.step = static_cast<std::uint8_t>(best.step);
    r.q = std::move(best.q);
}

// Every joint's distance (cm) to the source in the window's frames, decoded from the channel rows
// `rows`, appended to `out` in order; false at the first one not within E (`miss` then names it).
bool ClipSearch::distances(const FrameMatrix& rows, std::vector<double>& out, Miss& miss) {
    const auto J = static_cast<Eigen::Index>(skeleton_.size());
    for (int t = 0; t < count_; ++t) {
        forward_kinematics(skeleton_, rows.row(t).data(), pose_);
        for (Eigen::Index j = 0; j < J; ++j) {
            const double d =
                (pose_.positions[static_cast<std::size_t>(j)] - source_.block<3, 1>(3 * j, f0_ + t)).norm();
            if (!(d <= s_.E)) {
                miss = Miss{t, j, d};
                return false;
            }
            out.push_back(d);
        }
    }
    return true;
}

// Decodes q_ with step index kk; true when every position is within E (dist_ then holds every
// distance).
bool ClipSearch::check(int kk) {
    ++st_.probes;
    m_.reconstruct(e_, kk, q_, count_, scratch_, rows_);
    dist_.clear();
    Miss miss;
    return distances(rows_, dist_, miss);
}

// Quantizes the window with step index kk, then check.
bool ClipSearch::probe(int kk, double rounding) {
    const double inv = 1.0 / step_of(kk);
    for (std::size_t s = 0; s < s_.cells; ++s) {
        const double c = g_.data()[m_.scan[s]] * inv;
        const double a = std::abs(c);
        if (!(a < 1e9)) return false;
        const auto mag = static_cast<std::int32_t>(std::floor(a + rounding));
        q_[s] = c < 0 ? -mag : mag;
    }
    return check(kk);
}

// Galloping search from k (the previous window's step), then bisection: ends with `lo` passing and
// lo + 1 failing (or 255); the result is the last passing probe. k becomes lo, or k_start when even
// the finest step fails (the result's step is then -1: this rounding has no candidate).
Candidate ClipSearch::search(double rounding, int& k) {
    Candidate found;
    auto keep = [&](int kk) {
        found.step = kk;
        found.q = q_;
        std::swap(found.dist, dist_);
    };
    int lo = -1, hi = -1;
    if (probe(k, rounding)) {
        keep(k);
        lo = k;
        for (int stride = 1; lo < kMaxStep; stride *= 2) {
            const int cand = std::min(kMaxStep, lo + stride);
            if (!probe(cand, rounding)) {
                hi = cand;
                break;
            }
            keep(cand);
            lo = cand;
        }
    } else {
        hi = k;
        for (int stride = 1; lo < 0 && hi > 0; stride *= 2) {
            const int cand = std::max(0, hi - stride);
            if (probe(cand, rounding)) {
                keep(cand);
                lo = cand;
            } else {
                hi = cand;
            }
        }
    }
    while (hi >= 0 && hi - lo > 1) {
        const int mid = (lo + hi) / 2;
        if (probe(mid, rounding)) {
            keep(mid);
            lo = mid;
        } else {
            hi = mid;
        }
    }
    k = lo < 0 ? s_.k_start : lo;
    if (lo < 0) found.step = -1;
    return found;
}

// Drops the last t nonzero +-1 coefficients of the scan (they cost their zero run too) for the
// largest t (up to trim_tail) that still passes (bisection).
void ClipSearch::trim_tail(Candidate& found) {
    std::vector<std::size_t> tail;
    for (std::size_t s = found.q.size(); s-- > 0 && tail.size() < static_cast<std::size_t>(s_.trim_tail);) {
        if (found.q[s] == 0) continue;
        if (std::abs(found.q[s]) > 1) continue;
        tail.push_back(s);
    }
    std::size_t ok = 0, bad = tail.size() + 1;
    while (bad - ok > 1) {
        const std::size_t mid = (ok + bad) / 2;
        q_ = found.q;
        for (std::size_t t = 0; t < mid; ++t) q_[tail[t]] = 0;
        if (check(found.step)) {
            ok = mid;
            std::swap(found.dist, dist_);
        } else {
            bad = mid;
        }
    }
    for (std::size_t t = 0; t < ok; ++t) found.q[tail[t]] = 0;
}

// Escape: the window's source channel rows, stored as they are (float64). Seen only where decoded
// rotations cannot be projected back onto a joint's channels stably (docs/packing.md); checked like
// any other window.
void ClipSearch::store_raw(int w, WindowResult& r) {
    r.step = kRawStep;
    const FrameMatrix raw = clip_.channels.middleRows(f0_, count_);
    r.raw.assign(raw.data(), raw.data() + raw.size());
    std::vector<double> dist;
    Miss miss;
    if (!distances(raw, dist, miss)) {
        std::ostringstream message;  // %g-like: E may be far below 1e-6 cm
        message << "pack: clip '" << clip_.name << "' window " << w << " frame " << f0_ + miss.t
                << ": even its source rows are " << miss.d << " cm off (joint '"
                << skeleton_.joint(static_cast<std::size_t>(miss.j)).name
                << "') with the stored (float32) skeleton, over " << s_.E << " cm";
        throw PackingFailed(message.str());
    }
    for (double d : dist) st_.errors.add(d);
    ++st_.raw_windows;
}

}  // namespace

std::vector<WindowResult> quantize_windows(PackRun& run, const GroupModel& m, std::uint64_t window_total,
                                           SearchTotals& totals) {
    SearchSettings s;
    s.E = run.options.max_error_cm;
    s.k_start = std::clamp(static_cast<int>(std::lround(12.0 * (std::log2(s.E) + 14.0))), 0, 255);
    s.cells = m.active.size() * static_cast<std::size_t>(m.window);
    s.roundings = run.options.rounding_search ? std::vector<double>{0.5, 0.4, 0.3, 0.2}
                                              : std::vector<double>{run.options.rounding};
    s.trim_tail = run.options.trim_tail;
    // The stored bases are rounded: project with their exact inverses so that reconstruction is
    // exact up to the coefficients' quantization.
    s.dof_inverse = !m.active.empty() ? MatX(m.dof_basis.partialPivLu().inverse()) : MatX(0, 0);
    s.time_inverse_t = m.time_basis.partialPivLu().inverse().transpose();

    std::vector<WindowResult> results(window_total);
    std::vector<SearchTotals> states;
    for (std::size_t t = 0; t < run.threads; ++t) states.emplace_back(s.E);
    run.run(
        [&](std::size_t i, SearchTotals& st) {
            ClipSearch search(m, *run.clips[i], m.clips[i], s, st);
            run.done(*run.clips[i], search.run(results));
        },
        states);
    for (const SearchTotals& st : states) {
        totals.errors.merge(st.errors);
        for (std::size_t c = 0; c < totals.counts.n.size(); ++c) {
            totals.counts.n[c][0] += st.counts.n[c][0];
            totals.counts.n[c][1] += st.counts.n[c][1];
        }
        totals.probes += st.probes;
        totals.raw_windows += st.raw_windows;
    }
    return results;
}

}  // namespace mocapdb::packing::detail
