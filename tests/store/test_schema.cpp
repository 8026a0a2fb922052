// The specifications (schemas/format-vN.md), their mirrors (schemas/format-vN.json, compiled in) and
// the validator agree, for every format version the library reads.
#include <catch2/catch.hpp>

#include <regex>
#include <set>

#include "mocapdb/core/error.hpp"
#include "mocapdb/store/database.hpp"
#include "mocapdb/store/validate.hpp"
#include "shared_data.hpp"
#include "store_test_support.hpp"

using namespace mocapdb;
using namespace mocapdb::test;

namespace {

const std::filesystem::path kSchemas = test_data_dir().parent_path().parent_path() / "schemas";

std::set<std::string> matches(const std::string& text, const std::string& pattern) {
    std::set<std::string> out;
    const std::regex re(pattern);
    for (auto it = std::sregex_iterator(text.begin(), text.end(), re); it != std::sregex_iterator(); ++it)
        out.insert((*it)[1].str());
    return out;
}

std::string mirror_name(int version) { return "format-v" + std::to_string(version) + ".json"; }

}  // namespace

TEST_CASE("schema: the compiled-in mirrors are schemas/format-v1.json to format-v4.json", "[store][schema]") {
    CHECK(kDatabaseFormatVersion == 4);
    CHECK(builtin_schema_json(1) == file_bytes(kSchemas / "format-v1.json"));
    CHECK(builtin_schema_json(2) == file_bytes(kSchemas / "format-v2.json"));
    CHECK(builtin_schema_json(3) == file_bytes(kSchemas / "format-v3.json"));
    CHECK(builtin_schema_json(4) == file_bytes(kSchemas / "format-v4.json"));
    CHECK(builtin_schema_json() == builtin_schema_json(kDatabaseFormatVersion));
    CHECK_THROWS_AS(builtin_schema_json(5), InvalidArgument);
    CHECK_THROWS_AS(builtin_schema_json(0), InvalidArgument);
}

TEST_CASE("schema: every object and attribute of each mirror is specified in its format-vN.md", "[store][schema]") {
    // Objects per version: version 2 adds /sets/{set}/model and its six datasets, version 3
    // /clips/{clip}/channels_packed, the packed tier (/packed, /packed/{group} and its 5 datasets),
    // the synthesis kernel /sets/{set}/model/kernel, the repaired dropouts /sets/{set}/repairs
    // with its 3 datasets and the periodic parameters' /sets/{set}/parameter_period. Version 4 changes
    // the layout (index and segments) and adds the kernel's optional factorized system and the sets'
    // categorical parameter levels and the reliability warning's calibration requests (issue #38).
    const std::pair<int, std::size_t> versions[] = {{1, 29}, {2, 36}, {3, 50}, {4, 54}};
    for (const auto& [version, path_count] : versions) {
        const std::string json = file_bytes(kSchemas / mirror_name(version));
        const std::string md = file_bytes(kSchemas / ("format-v" + std::to_string(version) + ".md"));
        INFO("version " << version);
        CHECK(json.find("\"format_version\": " + std::to_string(version) + ",") != std::string::npos);
        CHECK(md.find("# mocapdb database file, format version " + std::to_string(version)) != std::string::npos);
        const auto paths = matches(json, "\"path\": \"([^\"]+)\"");
        CHECK(paths.size() == path_count);
        for (const std::string& path : paths) {
            const std::string last = path == "/" ? "/" : path.substr(path.rfind('/') + 1);
            INFO(path);
            const bool in_table = md.find("`" + last + "`") != std::string::npos;
            const bool in_heading = md.find("`" + path + "`") != std::string::npos;
            const bool in_tree =
                md.find(" " + last + "/") != std::string::npos || md.find(" " + last + " ") != std::string::npos;
            CHECK((in_table || in_heading || in_tree));
        }
        for (const std::string& name : matches(json, "\"name\": \"([^\"]+)\"")) {
            INFO(name);
            CHECK(md.find("`" + name + "`") != std::string::npos);
        }
    }
    // Version 2 is version 1 plus the model: every version-1 path is still there.
    const auto v1 = matches(file_bytes(kSchemas / "format-v1.json"), "\"path\": \"([^\"]+)\"");
    const auto v2 = matches(file_bytes(kSchemas / "format-v2.json"), "\"path\": \"([^\"]+)\"");
    for (const std::string& path : v1) {
        INFO(path);
        CHECK(v2.count(path) == 1);
    }
    for (const std::string& path : v2)
        if (v1.count(path) == 0) CHECK(path.rfind("/sets/{set}/model", 0) == 0);
    // Version 3 is version 2 plus the packed clip channels, the packed tier, the synthesis kernel, the
    // repaired dropouts and the parameter periods.
    const auto v3 = matches(file_bytes(kSchemas / "format-v3.json"), "\"path\": \"([^\"]+)\"");
    for (const std::string& path : v2) {
        INFO(path);
        CHECK(v3.count(path) == 1);
    }
    for (const std::string& path : v3)
        if (v2.count(path) == 0)
            CHECK((path == "/clips/{clip}/channels_packed" || path.rfind("/packed", 0) == 0 ||
                   path == "/sets/{set}/model/kernel" || path.rfind("/sets/{set}/repairs", 0) == 0 ||
                   path == "/sets/{set}/parameter_period"));
    auto v4 = matches(file_bytes(kSchemas / "format-v4.json"), "\"path\": \"([^\"]+)\"");
    CHECK(v4.erase("/sets/{set}/model/kernel/covariance_inverse") == 1);
    CHECK(v4.erase("/sets/{set}/parameter_level_count") == 1);
    CHECK(v4.erase("/sets/{set}/parameter_level") == 1);
    CHECK(v4.erase("/sets/{set}/model/kernel/edge_probe_requests") == 1);
    CHECK(v4 == v3);
}

TEST_CASE("schema: a custom mirror is honoured and a malformed one refused", "[store][schema]") {
    std::string json = builtin_schema_json();
    const std::string from = "{\"name\": \"creator\", \"dtype\": \"string\", \"shape\": [], \"presence\": \"MAY\"}";
    const std::string to = "{\"name\": \"creator\", \"dtype\": \"string\", \"shape\": [], \"presence\": \"MAY\", "
                           "\"value\": \"someone else\"}";
    REQUIRE(json.find(from) != std::string::npos);
    json.replace(json.find(from), from.size(), to);
    ValidateOptions o;
    o.schema_json = json;
    const ValidationReport r = validate_database(test_data_dir() / "reference-v4.h5", o);
    REQUIRE(r.violations.size() == 1);
    CHECK(r.violations[0].path == "/");
    CHECK(r.violations[0].message == "attribute 'creator': expected \"someone else\", found \"mocapdb 0.1.0\"");
    o.schema_json = "{\"format\": \"mocapdb\", \"format_version\": 2, \"objects\": [}";
    CHECK_THROWS_AS(validate_database(test_data_dir() / "reference-v3.h5", o), ParseError);
}

TEST_CASE("schema: each file is checked against the mirror of its own version", "[store][schema]") {
    // The version-2 mirror on a version-1 file: the root's format_version differs.
    ValidateOptions o;
    o.schema_json = builtin_schema_json(2);
    const ValidationReport r = validate_database(test_data_dir() / "reference-v1.h5", o);
    REQUIRE(r.violations.size() == 1);
    CHECK(r.violations[0].message == "attribute 'format_version': expected 2, found 1");
    // The built-in choice follows the file.
    const ValidationReport v1 = validate_database(test_data_dir() / "reference-v1.h5");
    CHECK(v1.ok());
    CHECK(v1.format_version == 1);
    const ValidationReport v2 = validate_database(test_data_dir() / "reference-v2.h5");
    CHECK(v2.ok());
    CHECK(v2.format_version == 2);
    const ValidationReport v3 = validate_database(test_data_dir() / "reference-v3.h5");
    CHECK(v3.ok());
    CHECK(v3.format_version == 3);
    // The packed clip channels are not part of version 2.
    o.schema_json = builtin_schema_json(2);
    const ValidationReport packed = validate_database(test_data_dir() / "reference-v3.h5", o);
    CHECK_FALSE(packed.ok());
}
