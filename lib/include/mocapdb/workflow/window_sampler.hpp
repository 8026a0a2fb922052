#pragma once
// Training data from a database: random windows of L consecutive source frames, B per
// batch, as pose vectors or joint positions, decoded from the packed tier where the database has one
// for every selected clip (else from the lossless clips).
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
enum class WindowSource {
    Auto,      ///< the packed tier when it holds every selected clip, else the lossless clips
    Packed,    ///< the packed tier (InvalidArgument when a selected clip is not in it)
    Lossless,  ///< the lossless clips (Database::load_clip)
};

struct WindowSamplerOptions {
    std::size_t length = 64;            ///< L, frames per window
    std::size_t batch = 32;             ///< B, windows per batch
    std::uint64_t seed = 0;
    std::vector<std::string> clips;     ///< clip ids or fnmatch patterns; empty: every clip
    WindowValues values = WindowValues::PoseVectors;
    WindowSource source = WindowSource::Auto;
    std::size_t cache_clips = 256;      ///< lossless clips kept decoded (least recently used evicted)
};

/// Where a drawn window comes from.
struct WindowRef {
    std::size_t clip = 0;   ///< index into WindowSampler::clip_ids()
    std::size_t begin = 0;  ///< its first source frame
};

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
    /// Windows to draw from: sum over clips of F - L + 1.
    std::uint64_t window_count() const;
    /// The first selected clip's rate (the others are within 0.01 % of it).
    double frame_rate() const;
    /// True when the windows are decoded from the packed tier.
    bool from_packed() const;
    /// Joint names (Skeleton::joints() order) of the rig: JointPositions' j-th triple.
    const std::vector<std::string>& joint_names() const;

    /// The next batch: out holds B x L x V values (window, frame, value; C order); refs, when not null,
    /// B entries.
    void next(double* out, WindowRef* refs = nullptr);
    /// One given window (L x V values into out); InvalidArgument when it lies outside its clip.
    void window(const WindowRef& ref, double* out);

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace mocapdb::workflow
