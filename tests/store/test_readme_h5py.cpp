// The h5py snippet of docs/database.md decodes a packed clip (schemas/format-v3.md §5.1) to the
// library's values bit for bit (same sha256 of the float64 bytes), reads the tensor, the parameters
// and the model of a database, and its reconstruction formula of the model (§8) gives back the
// aligned tensor of the reference file (whose model is exact); it lists the packed tier's groups. It runs on the reference file with
// Debian's python3-h5py and python3-zstandard when installed; otherwise the same values are read
// with h5dump.
#include <catch2/catch.hpp>

#include <cstdlib>
#include <fstream>

#include "mocapdb/store/sha256.hpp"
#include "reference_database.hpp"
#include "shared_data.hpp"
#include "store_test_support.hpp"

using namespace mocapdb::test;

TEST_CASE("docs/database.md: the h5py snippet reads the tensor and the control parameters", "[store][readme]") {
    const std::string readme = file_bytes(test_data_dir().parent_path().parent_path() / "docs" / "database.md");
    const std::string begin = "<!-- h5py-snippet:begin -->\n```python\n";
    const auto b = readme.find(begin);
    REQUIRE(b != std::string::npos);
    const auto e = readme.find("```\n<!-- h5py-snippet:end -->", b);
    REQUIRE(e != std::string::npos);
    const std::string snippet = readme.substr(b + begin.size(), e - b - begin.size());
    const auto reference = test_data_dir() / "reference-v3.h5";

    if (run_command("/usr/bin/python3 -c 'import h5py, zstandard'").exit_code == 0) {
        TempDir dir("readme");
        std::ofstream(dir / "snippet.py") << snippet;
        const CommandResult r = run_command("/usr/bin/python3 " + quoted((dir / "snippet.py").string()) + " " +
                                            quoted(reference.string()) + " tiny_set");
        INFO(r.output);
        REQUIRE(r.exit_code == 0);
        CHECK(r.output.find("parameters {'speed': 'cm/s'} (2, 1) samples ['tiny_walk', 'tiny_walk']") != std::string::npos);
        const ReferenceContent content = reference_content();
        const mocapdb::FrameMatrix& x = content.clip.channels;  // C order (row-major), little-endian here
        const std::string bytes(reinterpret_cast<const char*>(x.data()), static_cast<std::size_t>(x.size()) * sizeof(double));
        CHECK(r.output.find("clip tiny_walk (frames, channels) = (4, 9) sha256 " + mocapdb::sha256_hex(bytes)) !=
              std::string::npos);
        CHECK(r.output.find("tensor (sample, time, dof) = (2, 3, 9) A(d=5, t=2, s=1) = 125.0") != std::string::npos);
        // The packed tier's layout (the reference file has one at kReferencePackedErrorCm).
        CHECK(r.output.find("packed E 0.1 bytes ") != std::string::npos);
        CHECK(r.output.find("/packed/g0 tiny_walk 30.0 Hz ") != std::string::npos);
        CHECK(r.output.find("mocapdb-packed-group-2 {'tiny_walk': ") != std::string::npos);
        const std::string model = "model ranks (1, 2, 2) max |A - A_hat| = ";
        const auto m = r.output.find(model);
        REQUIRE(m != std::string::npos);
        const double error = std::strtod(r.output.c_str() + m + model.size(), nullptr);
        CHECK(error < 1e-9);
        CHECK(r.output.find("rmse_cm", m) != std::string::npos);
    } else {
        WARN("python3-h5py or python3-zstandard is not installed: checking the same read with h5dump");
        const CommandResult t = run_command("h5dump -d /sets/tiny_set/aligned/tensor -s 1,2,5 -c 1,1,1 " +
                                            quoted(reference.string()));
        CHECK(t.output.find("(1,2,5): 125") != std::string::npos);
        const CommandResult p = run_command("h5dump -d /sets/tiny_set/parameters " + quoted(reference.string()));
        CHECK(p.output.find("(0,0): 10,") != std::string::npos);
        const CommandResult d = run_command("h5dump -a /sets/tiny_set/aligned/tensor/dims " + quoted(reference.string()));
        CHECK(d.output.find("\"sample\", \"time\", \"dof\"") != std::string::npos);
        const CommandResult c = run_command("h5dump -H -d /sets/tiny_set/model/core " + quoted(reference.string()));
        CHECK(c.output.find("( 2, 2, 1 )") != std::string::npos);
    }
}
