#pragma once
// Training data from a database: random windows of L consecutive source frames, B per
// batch, as pose vectors or joint positions, decoded from the packed tier where the database has one
// for every selected clip (else from the lossless clips). Each clip drawn is decoded once into a
// per-clip cache (its memory: docs); windows are written into the caller's float or double array.
// Not thread-safe (one sampler per thread); `db` must outlive it and not be written meanwhile.
// Errors: NotFoundError for a named clip not stored; InvalidArgument for bad options.
//
// Details: docs/headers/workflow.md (mocapdb/workflow/window_sampler.hpp).
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace mocapdb {
class Database;
}

namespace mocapdb::workflow {

enum class WindowValues { PoseVectors, JointPositions };
/// The element type of the decoded clip cache (either can be written to float and double arrays).
enum class WindowDType { Float32, Float64 };
enum class WindowSource {
    Auto,      ///< the packed tier when it holds every selected clip, else the lossless clips
    Packed,    ///< the packed tier (InvalidArgument when a selected clip is not in it)
    Lossless,  ///< the lossless clips (Database::load_clip)
};

struct WindowSamplerOptions {
    std::size_t length = 64;  ///< L, frames per window
    std::size_t batch = 32;   ///< B, windows per batch
    std::uint64_t seed = 0;
    std::vector<std::string> clips;  ///< clip ids or fnmatch patterns; empty: every clip
    WindowValues values = WindowValues::PoseVectors;
    WindowSource source = WindowSource::Auto;
    std::size_t cache_clips = 256;             ///< clips kept decoded (least recently used evicted; at least batch)
    WindowDType dtype = WindowDType::Float64;  ///< the decoded clips' element type
    bool pad = false;                          ///< clips shorter than L give one window, padded with their last frame
};

/// Where a drawn window comes from.
struct WindowRef {
    std::size_t clip = 0;   ///< index into WindowSampler::clip_ids()
    std::size_t begin = 0;  ///< its first source frame
};

/// The generator seed of stream (seed, epoch, worker): `seed` itself for (0, 0), else a SplitMix64
/// mix of the three.
std::uint64_t stream_seed(std::uint64_t seed, std::uint64_t epoch, std::uint64_t worker);

class WindowSampler {
public:
    WindowSampler(const Database& db, const WindowSamplerOptions& options);
    ~WindowSampler();
    WindowSampler(WindowSampler&&) noexcept;
    WindowSampler& operator=(WindowSampler&&) noexcept;

    const WindowSamplerOptions& options() const;
    /// V: values per frame (D or 3 J).
    std::size_t values_per_frame() const;
    /// The selected clips that offer at least one window, in selection order.
    const std::vector<std::string>& clip_ids() const;
    /// The selected clips shorter than L frames (they give no windows, or with pad one), in selection order.
    const std::vector<std::string>& short_clip_ids() const;
    /// Windows each of clip_ids() offers: F - L + 1 (1 for a padded short clip).
    std::vector<std::uint64_t> window_counts() const;
    /// Windows to draw from: sum over clips of F - L + 1.
    std::uint64_t window_count() const;
    /// The first selected clip's rate (the others are within 0.01 % of it).
    double frame_rate() const;
    /// True when the windows are decoded from the packed tier.
    bool from_packed() const;
    /// Bytes held by the decoded clips now.
    std::size_t cache_bytes() const;
    /// Joint names (Skeleton::joints() order) of the rig: JointPositions' j-th triple.
    const std::vector<std::string>& joint_names() const;

    /// The next batch: out holds B x L x V values (window, frame, value; C order); refs, when not null,
    /// B entries. draw() then fill().
    void next(double* out, WindowRef* refs = nullptr);
    void next(float* out, WindowRef* refs = nullptr);
    /// One given window (L x V values into out); InvalidArgument when it lies outside its clip.
    void window(const WindowRef& ref, double* out);
    void window(const WindowRef& ref, float* out);

    /// Restarts the draw on the stream of (options().seed, epoch, worker); (0, 0) is the stream a new
    /// sampler draws.
    void set_stream(std::uint64_t epoch, std::uint64_t worker);
    /// The draw's exact position (the generator's state as text) and its restoration: a copy made
    /// elsewhere from the same options continues with the same batches. InvalidArgument for bad text.
    std::string stream_state() const;
    void set_stream_state(const std::string& state);

    /// Draws the next batch's B windows into refs and decodes the clips they need (reads the database).
    void draw(WindowRef* refs);
    /// Decodes the clips of `count` <= max(B, cache_clips) given windows (reads the database), for fill();
    /// InvalidArgument for a window outside its clip.
    void load(const WindowRef* refs, std::size_t count);
    /// Writes windows whose clips are decoded (those of the last draw() or load()) into out (count x L x V
    /// values), from the decoded clips only: no file access, no allocation. InvalidArgument otherwise.
    void fill(const WindowRef* refs, std::size_t count, double* out) const;
    void fill(const WindowRef* refs, std::size_t count, float* out) const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace mocapdb::workflow
