// Opens a mocapdb database and lists what it holds: clips, motion sets and the packed tier.
//   example_open_database DB.h5
#include <cstdio>
#include <exception>

#include "mocapdb/store/database.hpp"

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: %s DB.h5\n", argv[0]);
        return 2;
    }
    try {
        const mocapdb::Database db(argv[1]);
        const auto clips = db.clips();
        std::printf("%s: format version %d, %zu clips, %zu skeletons\n", argv[1], db.format_version(), clips.size(),
                    db.skeletons().size());
        for (std::size_t i = 0; i < clips.size() && i < 5; ++i)
            std::printf("  clip %-10s %5zu frames at %g Hz (%.2f s), skeleton %s\n", clips[i].id.c_str(), clips[i].frames,
                        clips[i].frame_rate, clips[i].duration(), clips[i].skeleton.c_str());
        for (const mocapdb::SetRecord& s : db.sets()) {
            std::printf("  set %s: %zu samples, parameters", s.name.c_str(), s.samples);
            for (const auto& p : s.parameter_names) std::printf(" %s", p.c_str());
            std::printf("%s%s\n", s.aligned ? ", aligned" : "", s.model ? ", Tucker model" : "");
        }
        if (const auto tier = db.packed())
            std::printf("  packed tier: %zu clips in %llu bytes, max error %.3f cm (bound %.3f cm)\n", tier->clips,
                        static_cast<unsigned long long>(tier->bytes), tier->max_cm, tier->max_error_cm);
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "example_open_database: %s\n", e.what());
        return 1;
    }
}
