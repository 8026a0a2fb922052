#pragma once
// The motion database (HDF5, format "mocapdb" version 4, specified in schemas/format-v4.md; files
// of versions 1 to 3 are read too): a read view `Database`, and an atomic edit session `DatabaseWriter`.
//
// Details: docs/headers/store.md (mocapdb/store/database.hpp).
#include <array>
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "mocapdb/compression/set_model.hpp"
#include "mocapdb/dataset/aligned_set.hpp"
#include "mocapdb/dataset/aligned_timing.hpp"
#include "mocapdb/dataset/motion_set.hpp"
#include "mocapdb/motion/clip.hpp"
#include "mocapdb/store/clip_record.hpp"
#include "mocapdb/store/store_error.hpp"
#include "mocapdb/synthesis/kernel_fit.hpp"

namespace mocapdb {

namespace packing {
class GroupDecoder;
}

/// The file format version this library writes. It reads every version from 1 to this one (a version
/// only adds optional objects); a writing session on an older file upgrades its format_version.
constexpr int kDatabaseFormatVersion = 4;

/// How long a DatabaseWriter waits by default for another writing session on its target.
constexpr double kWriterWaitSeconds = 600.0;

/// One motion set as listed by Database::sets().
struct SetRecord {
    std::string name;
    std::size_t samples = 0;
    std::vector<std::string> parameter_names;
    std::string parameter_source;
    bool aligned = false;
    /// (samples, time, dofs) of the aligned tensor, as stored (C order); zeros when not aligned.
    std::array<std::size_t, 3> tensor_shape{};
    std::uint64_t tensor_stored_bytes = 0;     ///< compressed size of the tensor in the file
    bool model = false;                        ///< a Tucker model is stored (/sets/{set}/model)
    std::array<std::size_t, 3> model_ranks{};  ///< (R1, R2, R3); zeros without a model
    std::uint64_t model_stored_bytes = 0;      ///< storage size of the model's datasets in the file
};

/// Errors of a stored model, measured against the aligned tensor when the model was stored
/// (eval/joint_error.hpp defines them).
struct ModelFigures {
    double dof_rmse = 0.0;
    double rmse_cm = 0.0;
    double mean_cm = 0.0;
    double max_cm = 0.0;
    double p99_cm = 0.0;
};

/// A set's compressed model as stored in /sets/{set}/model.
struct StoredModel {
    compression::SetModel model;
    ModelFigures figures;
};

/// One clip of the packed tier (/packed/{group}, schemas/format-v3.md §9).
struct PackedClipRecord {
    std::string id;  ///< clip id (the clip under /clips it was packed from)
    std::size_t frames = 0;
    std::uint64_t payload_bytes = 0;  ///< its windows' coded bytes (the group's header and tables are shared)
    double max_cm = 0.0;              ///< FK joint-position errors against the source clip, every frame
    double p99_cm = 0.0;
    double rmse_cm = 0.0;
};

/// One group of the packed tier: clips of one skeleton topology and frame rate packed together.
struct PackedGroupRecord {
    std::string name;                ///< link name under /packed ("g0", "g1", ...)
    std::string skeleton;            ///< skeleton id of its first clip
    double frame_rate = 0.0;         ///< Hz
    std::uint64_t bytes = 0;         ///< the packed bytes: everything the decoder needs
    std::uint64_t stored_bytes = 0;  ///< storage of the group's datasets in the file
    std::size_t frames = 0;
    double max_cm = 0.0, p99_cm = 0.0, rmse_cm = 0.0;
    std::vector<PackedClipRecord> clips;  ///< in packing order (the decoder's clip index)
};

/// The packed tier (/packed): every clip packed at the time with FK error <= max_error_cm.
struct PackedTierRecord {
    double max_error_cm = 0.0;  ///< E, the bound
    std::uint64_t bytes = 0;    ///< sum of the groups' bytes
    std::size_t clips = 0;
    std::size_t frames = 0;
    double max_cm = 0.0, p99_cm = 0.0, rmse_cm = 0.0;  ///< over the whole collection
    std::vector<PackedGroupRecord> groups;

    /// The group and index of a clip; nullopt when the clip is not in the tier.
    std::optional<std::pair<std::size_t, std::size_t>> find(const std::string& clip) const;
};

/// Outcome of DatabaseWriter::add_clip.
struct AddClipResult {
    std::string id;      ///< the new clip's id, or the id of the identical clip already stored
    bool added = false;  ///< false when skipped as a duplicate
    /// "added as ID" or "skipped: duplicate sha256 of clip ID".
    std::string message;
};

/// True when `path` is an HDF5 file (any HDF5 file, not necessarily a mocapdb database).
bool is_hdf5_file(const std::filesystem::path& path);

/// Read view of a database file. Opening checks the root attributes (format = "mocapdb",
/// format_version 1 or 2) and throws StoreError naming the file, the HDF5 path and the expected and
/// found values for a file that is not HDF5, truncated, foreign, or of another version. Every load
/// checks dtypes, shapes and checksums of what it reads, and that floating-point values are finite
/// (clip channels, skeleton offsets, set parameters, aligned forms, models), and throws StoreError /
/// ChecksumError naming the offending object. Not thread-safe (HDF5's serial build is not).
class Database {
public:
    /// Opens `path` read-only.
    explicit Database(const std::filesystem::path& path);
    ~Database();
    Database(Database&&) noexcept;
    Database& operator=(Database&&) noexcept;
    Database(const Database&) = delete;
    Database& operator=(const Database&) = delete;

    /// The file this view reads (for a writer's view: its temporary file).
    const std::filesystem::path& path() const noexcept;
    /// The file's format_version (1 to 3; a writer's view: kDatabaseFormatVersion).
    int format_version() const noexcept;

    /// Every clip, sorted by id (reads only metadata).
    std::vector<ClipRecord> clips() const;
    /// How many clips are stored (without reading their records).
    std::size_t clip_count() const;
    /// The clip's record; nullopt when there is no such clip.
    std::optional<ClipRecord> find_clip(const std::string& id) const;
    bool has_clip(const std::string& id) const;
    /// Id of the clip whose source file had this SHA-256; nullopt when none.
    std::optional<std::string> find_sha256(const std::string& sha256) const;
    /// Loads a clip (channels in cm and radians). Its skeleton is shared with every other clip of
    /// the same skeleton loaded through this view. StoreError when there is no such clip. A clip
    /// whose lossless channels were dropped (ClipRecord::lossless false) is decoded from the packed
    /// tier (every joint within its max_error_cm, plus the float32 rounding of the packed offsets,
    /// below 1e-4 cm), with the clip's stored skeleton.
    Clip load_clip(const std::string& id) const;

    /// The packed tier's records (no bytes read); nullopt when the file has no /packed.
    std::optional<PackedTierRecord> packed() const;
    /// Decodes frames [begin, min(end, frames)) of a clip from the packed tier alone (every joint
    /// and end site within the tier's max_error_cm of the source, FK positions). The clip's skeleton
    /// is the packed one (offsets rounded to float32; names, channels and source units as stored).
    /// StoreError when the clip is not in the packed tier or the group is malformed, ChecksumError
    /// when its bytes are corrupted, InvalidArgument when begin >= the clip's frames.
    Clip load_clip_packed(const std::string& id, std::size_t begin = 0,
                          std::size_t end = static_cast<std::size_t>(-1)) const;

    /// The decoder of one packed group (PackedGroupRecord::name, "g0", ...), its bytes read and parsed
    /// once and kept until another group is asked for. The decoder does not refer to the database:
    /// hold the pointer to keep it. Its clip k is the group record's clips[k]. StoreError when there is
    /// no such group or its bytes are malformed (naming the dataset), ChecksumError when corrupted.
    std::shared_ptr<const packing::GroupDecoder> packed_group_decoder(const std::string& group) const;

    /// Skeleton ids, sorted.
    std::vector<std::string> skeletons() const;
    /// The skeleton (SourceUnits and forward included), cached per id.
    std::shared_ptr<const Skeleton> load_skeleton(const std::string& id) const;
    /// The file name the skeleton was first read from ("16.asf", "02_01_60fps.bvh").
    std::string skeleton_source(const std::string& id) const;

    /// Motion set names, sorted.
    std::vector<std::string> set_names() const;
    bool has_set(const std::string& name) const;
    std::vector<SetRecord> sets() const;
    MotionSet load_set(const std::string& name) const;
    /// The set's aligned form, or nullopt when the set has not been aligned. StoreError when there
    /// is no such set.
    std::optional<AlignedSet> load_aligned(const std::string& set) const;
    /// The aligned form's timing and shape (the warps, checked as load_aligned checks them, and the
    /// tensor's D from its header) without reading the tensor's values, mean, scale or
    /// canonicalizations: what the compressed synthesis model needs. nullopt when the set has not been
    /// aligned; StoreError when there is no such set.
    std::optional<AlignedTiming> load_aligned_timing(const std::string& set) const;
    /// The set's Tucker model, or nullopt when none is stored. StoreError when there is no such set
    /// or the model is malformed (shapes disagreeing with the aligned tensor, non-finite values).
    std::optional<StoredModel> load_model(const std::string& set) const;
    /// The model's precomputed coefficient kernel (/sets/{set}/model/kernel, synthesis/kernel_fit.hpp),
    /// or nullopt when there is no model or it was stored without one. StoreError, naming the object,
    /// when there is no such set or the group is malformed (bad key, family, non-finite or out-of-range
    /// variogram parameters, fit_status without residual_variance...). exponent_loo_mse: empty (not stored).
    std::optional<synthesis::KernelFit> load_kernel_fit(const std::string& set) const;

    /// Bytes of the database: its index file plus the segments the index links to (format 4), or
    /// the one file (older formats).
    std::uint64_t file_size() const;
    /// Bytes the database's files spend on its clips: for every clip its group and datasets (object
    /// headers with their attributes, link and chunk indexes, heaps, stored chunks, the global-heap
    /// text of string attributes), plus the /clips groups that link to them (in the index and in each
    /// segment holding clips). What a lossless figure must count besides the channel data
    /// (ClipRecord::stored_bytes), about 7 kB a clip. Not counted: the files' fixed parts (superblock,
    /// root group) and unused space.
    std::uint64_t clips_file_bytes() const;

private:
    friend class DatabaseWriter;
    struct Impl;
    explicit Database(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> impl_;
};

/// Bytes a database occupies on disk: the file plus every file of its segment folder ("DB.h5.d",
/// format 4), including segments that no longer hold live objects and wait to be removed. 0 when absent.
std::uint64_t database_disk_bytes(const std::filesystem::path& path);

/// Copies a database to `to` (a path that must not exist): its file and, for format 4, the segments
/// it links to, into "to.d/" (a copy of the file alone would still read the original's segments).
/// StoreError when `from` is not a database; IoError when a file cannot be copied.
void copy_database(const std::filesystem::path& from, const std::filesystem::path& to);

/// An atomic edit session on a database file (see the header comment for the guarantees).
/// Damage is refused where it is read: the constructor loads every skeleton, view() loads and the
/// put_* calls check what they read as Database does, and their errors name the target (not the
/// temporary copy) and the object's path; the caller then drops the session, so nothing is
/// published. Objects the session never reads are copied as they are, unchecked (validate_database
/// reads everything): a write costs what it touches, not the whole file.
class DatabaseWriter {
public:
    enum class Mode {
        OpenOrCreate,  ///< edit the existing database, or start a new one when the target is absent
        Create,        ///< start a new, empty database; commit() replaces whatever the target was
    };

    /// Starts a session. Throws StoreError when the target exists but is not a database of a version
    /// this library reads (OpenOrCreate), IoError when the temporary file cannot be made. An older
    /// file's format_version is set to kDatabaseFormatVersion in the session's file (the target
    /// changes only at commit()).
    /// `wait_seconds`: how long to wait for another session on the same target to end (StoreError
    /// "another mocapdb session is writing this database" after that).
    explicit DatabaseWriter(const std::filesystem::path& target, Mode mode = Mode::OpenOrCreate,
                            double wait_seconds = kWriterWaitSeconds);
    /// Without commit(): closes and removes the temporary file; the target is untouched.
    ~DatabaseWriter();
    DatabaseWriter(const DatabaseWriter&) = delete;
    DatabaseWriter& operator=(const DatabaseWriter&) = delete;

    const std::filesystem::path& target() const noexcept;
    const std::filesystem::path& temp_path() const noexcept;

    /// Reads the session's current content (including what this session added).
    const Database& view() const;
    /// Id of the stored clip whose source file had this SHA-256 (indexed: constant time).
    std::optional<std::string> find_sha256(const std::string& sha256) const;

    /// Stores a clip losslessly (float64 channels in cm and radians, with its skeleton's SourceUnits).
    /// A clip whose source.sha256 is already stored is skipped. The id is the stem of
    /// source.file_name, made unique with "-2", "-3", ... Its skeleton is stored once per structure:
    /// an existing skeleton is reused when Skeleton::same_structure (1e-9) holds and the source units
    /// and forward direction are equal. InvalidArgument for an invalid clip or source.
    AddClipResult add_clip(const Clip& clip, const ClipSource& source);

    /// Stores a motion set. Every sample must name a stored clip, lie within its frames, and all
    /// clips must share one skeleton structure (Skeleton::same_structure; InvalidArgument otherwise). An existing set of the same name is
    /// an InvalidArgument unless `replace`; replacing drops the old set's aligned form and model too.
    void put_set(const MotionSet& set, bool replace);
    /// Removes a set (and its aligned form and model). StoreError when there is no such set.
    void remove_set(const std::string& name);
    /// Stores (replaces) the aligned form of an existing set, dropping a stored model (it described the
    /// old tensor). InvalidArgument unless validate(aligned)
    /// holds, N equals the set's samples, D the pose-vector length (PoseLayout) of the set's skeleton,
    /// and every warp column lies within its sample's frames [0, frame_count − 1] (1e-9 slack).
    void put_aligned(const std::string& set, const AlignedSet& aligned);
    /// Stores (replaces) the Tucker model of an aligned set. InvalidArgument unless the set is
    /// aligned and the model's D, T, N equal the aligned tensor's and compression::check holds
    /// (and fit, error_bound, data_norm and the figures are finite; error_bound, data_norm and the
    /// figures >= 0).
    /// put_aligned and put_set(replace) drop a stored model (it described the old tensor).
    void put_model(const std::string& set, const compression::SetModel& model, const ModelFigures& figures);
    /// Stores (replaces) the precomputed coefficient kernel of the set's stored model
    /// (synthesis::fit_kernel of that model). InvalidArgument when the set has no model, the key is 0,
    /// or the variogram is invalid (or nugget + sill = 0); stores assessed_status, not exponent_loo_mse. It goes
    /// with the model: put_model, put_aligned and put_set(replace) drop it.
    void put_kernel_fit(const std::string& set, const synthesis::KernelFit& fit);

    /// Stores (replaces) the packed tier /packed: `tier` gives E, the collection's figures and per
    /// group its skeleton, frame rate, figures and clips (name, bytes and stored_bytes are set here:
    /// groups are named g0, g1, ... in order); `group_bytes[i]` is group i's packed bytes
    /// (packing::pack_group). InvalidArgument unless the sizes agree, E and every figure are finite
    /// (E > 0, figures >= 0), every clip is stored with the frames given and appears once, and each
    /// group's bytes parse (packing::GroupDecoder) with the same clip count, frame counts and rate.
    /// StoreError when an existing tier is the only copy of some clips (drop_lossless).
    void put_packed(const PackedTierRecord& tier, const std::vector<std::vector<std::uint8_t>>& group_bytes);
    /// Removes the packed tier. StoreError when there is none, or when it is the only copy of some
    /// clips (drop_lossless).
    void remove_packed();
    /// Removes the lossless channels of every clip in the packed tier (clips imported after the
    /// tier was written keep theirs): the file then holds those clips only as packed, within the
    /// tier's max_error_cm, and the tier can no longer be replaced or removed. Returns how many
    /// clips were dropped now. StoreError when there is no packed tier. Irreversible once committed.
    std::size_t drop_lossless();

    /// Closes the temporary file, makes it durable and renames it over the target. Space freed by
    /// replaced sets is reclaimed here (the file is rewritten compactly). The session is finished
    /// afterwards: every other call throws.
    void commit();

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace mocapdb
