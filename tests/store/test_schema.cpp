// The specification (schemas/format-v1.md), its mirror (schemas/format-v1.json, compiled in) and the
// validator agree.
#include <catch2/catch.hpp>

#include <regex>
#include <set>

#include "mocapdb/core/error.hpp"
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

}  // namespace

TEST_CASE("schema: the compiled-in mirror is schemas/format-v1.json", "[store][schema]") {
    CHECK(builtin_schema_json() == file_bytes(kSchemas / "format-v1.json"));
}

TEST_CASE("schema: every object and attribute of the mirror is specified in format-v1.md", "[store][schema]") {
    const std::string json = file_bytes(kSchemas / "format-v1.json");
    const std::string md = file_bytes(kSchemas / "format-v1.md");
    const auto paths = matches(json, "\"path\": \"([^\"]+)\"");
    CHECK(paths.size() == 29);
    for (const std::string& path : paths) {
        const std::string last = path == "/" ? "/" : path.substr(path.rfind('/') + 1);
        INFO(path);
        const bool in_table = md.find("`" + last + "`") != std::string::npos;
        const bool in_heading = md.find("`" + path + "`") != std::string::npos;
        const bool in_tree = md.find(" " + last + "/") != std::string::npos || md.find(" " + last + " ") != std::string::npos;
        CHECK((in_table || in_heading || in_tree));
    }
    for (const std::string& name : matches(json, "\"name\": \"([^\"]+)\"")) {
        INFO(name);
        CHECK(md.find("`" + name + "`") != std::string::npos);
    }
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
    const ValidationReport r = validate_database(test_data_dir() / "reference-v1.h5", o);
    REQUIRE(r.violations.size() == 1);
    CHECK(r.violations[0].path == "/");
    CHECK(r.violations[0].message == "attribute 'creator': expected \"someone else\", found \"mocapdb 0.1.0\"");
    o.schema_json = "{\"format\": \"mocapdb\", \"format_version\": 1, \"objects\": [}";
    CHECK_THROWS_AS(validate_database(test_data_dir() / "reference-v1.h5", o), ParseError);
}
