#pragma once
// What a caller can change to lift a refusal. The library's messages say what is wrong; a front end
// (the CLI, the Python module) catches the error, reads its Remedy and appends the flag or keyword of
// its own that fixes it. Thrown as Refused<E>: still an E for every catch site (E derives from Error).
#include <utility>

namespace mocapdb {

enum class Remedy {
    Overwrite,         ///< an output exists: allow replacing it
    ReplaceFile,       ///< the file is not a mocapdb database: replace it with a new one
    NameSkeletonFile,  ///< an AMC without a skeleton found beside it: name the ASF file
    PackFirst,         ///< the database has no packed tier: pack it
    CompressFirst,     ///< the set has no compressed model: compress it
    AlignFirst,        ///< the set is not aligned: align it
    GiveParameters,    ///< the set has no control parameters: create it with a table or extractors
    Ranks,             ///< requested Tucker ranks out of range: change them
    Segmentation,      ///< too few samples: select more clips or segment finer
    Feet,              ///< foot joints not found by name: name them
};

/// The remedy carried by an error; front ends find it with dynamic_cast<const Remediable*>.
class Remediable {
public:
    explicit Remediable(Remedy remedy) noexcept : remedy_(remedy) {}
    virtual ~Remediable() = default;
    Remedy remedy() const noexcept { return remedy_; }

private:
    Remedy remedy_;
};

/// An error E (IoError, InvalidArgument, StoreError, ...) with a remedy: throw Refused<E>(remedy, E's arguments).
template <class E>
class Refused : public E, public Remediable {
public:
    template <class... Args>
    explicit Refused(Remedy remedy, Args&&... args) : E(std::forward<Args>(args)...), Remediable(remedy) {}
};

}  // namespace mocapdb
