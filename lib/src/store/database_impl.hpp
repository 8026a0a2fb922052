#pragma once
// State shared by Database and DatabaseWriter: the open file, the skeleton cache and the decoder of
// the packed group read last (clips are usually loaded group by group).
#include <map>
#include <memory>
#include <string>

#include "h5/file.hpp"
#include "segments.hpp"
#include "mocapdb/packing/group_decoder.hpp"
#include "mocapdb/store/database.hpp"

namespace mocapdb {

struct Database::Impl {
    std::filesystem::path path;
    std::unique_ptr<store::ReaderLock> reader_lock;  // taken before the file is opened (segments.hpp)
    store::h5::File owned;                           // the file, when this view opened it itself
    store::h5::File* file = nullptr;                 // the file read (owned, or a writer's session file)
    int format_version = kDatabaseFormatVersion;     // the root attribute, as checked when opened
    mutable std::map<std::string, std::shared_ptr<const Skeleton>> skeletons;
    mutable std::string decoder_group;  // /packed/{group} of `decoder`; cleared when /packed changes
    mutable std::shared_ptr<const packing::GroupDecoder> decoder;

    const store::h5::File& f() const;
};

}  // namespace mocapdb
