// mocapdb: command-line front end. The library returns values and throws mocapdb::Error; this layer
// formats results and turns errors into one line on stderr and a non-zero exit code.
#include <exception>
#include <string>
#include <iostream>
#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include "commands.hpp"
#include "mocapdb/core/error.hpp"
#include "mocapdb/core/remedy.hpp"
#include "mocapdb/core/version.hpp"

namespace {

// The library says what is wrong; the command line adds the flag or command that fixes it.
std::string hint(const mocapdb::Error& e) {
    const auto* r = dynamic_cast<const mocapdb::Remediable*>(&e);
    if (r == nullptr) return {};
    switch (r->remedy()) {
        case mocapdb::Remedy::Overwrite: return "; pass --force to overwrite it";
        case mocapdb::Remedy::ReplaceFile: return "; --force replaces the file with a new one";
        case mocapdb::Remedy::NameSkeletonFile: return "; pass --asf FILE";
        case mocapdb::Remedy::PackFirst: return "; run: mocapdb pack DB --max-error-cm E";
        case mocapdb::Remedy::CompressFirst: return "; run: mocapdb compress DB --set SET";
        case mocapdb::Remedy::AlignFirst: return "; run: mocapdb align DB --set SET";
        case mocapdb::Remedy::GiveParameters: return "; create the set with --extract or --params";
        case mocapdb::Remedy::Ranks: return " (--ranks)";
        case mocapdb::Remedy::Segmentation: return " (--segment)";
        case mocapdb::Remedy::Feet: return " (--feet LEFT,RIGHT)";
    }
    return {};
}

}  // namespace

int main(int argc, char** argv) {
#if defined(__GLIBC__)
    // A command is one short process that allocates, frees and allocates again buffers of tens of MB
    // (loading a stored model: its 22 MB core at 645 samples, the core slices, the kriging matrices).
    // By default glibc hands such buffers back to the system (mmap, heap trimming) and every new one
    // page-faults all its pages afresh: a third of `synth`'s load (benchmarks/RESULTS.md). Keep
    // buffers up to 32 MB (glibc's largest mmap threshold) in the heap and do not trim it, so freed
    // memory is reused; the process ends soon anyway.
    mallopt(M_MMAP_THRESHOLD, 32 * 1024 * 1024);
    mallopt(M_TRIM_THRESHOLD, 512 * 1024 * 1024);
#endif
    CLI::App app{"mocapdb: store, compress and synthesize motion capture"};
    app.require_subcommand(1);
    app.set_version_flag("--version", mocapdb::creator_string);

    mocapdb::cli::setup_info(app);
    mocapdb::cli::setup_convert(app);
    mocapdb::cli::setup_import(app);
    mocapdb::cli::setup_pack(app);
    mocapdb::cli::setup_validate(app);
    mocapdb::cli::setup_export(app);
    mocapdb::cli::setup_variogram(app);
    mocapdb::cli::setup_krige(app);
    mocapdb::cli::setup_set(app);
    mocapdb::cli::setup_align(app);
    mocapdb::cli::setup_generate(app);
    mocapdb::cli::setup_compress(app);
    mocapdb::cli::setup_report(app);
    mocapdb::cli::setup_gp(app);
    mocapdb::cli::setup_synth(app);
    mocapdb::cli::setup_query(app);
    mocapdb::cli::setup_reliability(app);
    mocapdb::cli::setup_reduce(app);
    mocapdb::cli::setup_demo(app);
    mocapdb::cli::setup_eval(app);
    mocapdb::cli::setup_serve(app);

    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e);
    } catch (const mocapdb::Error& e) {
        std::cerr << "mocapdb: error: " << e.what() << hint(e) << "\n";
        return 1;
    } catch (const std::exception& e) {
        std::cerr << "mocapdb: internal error: " << e.what() << "\n";
        return 2;
    }
    return 0;
}
