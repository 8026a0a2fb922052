// The import manifest CSV: columns, quoting, matching by file name or stem, and its errors.
#include <catch2/catch.hpp>

#include "mocapdb/core/error.hpp"
#include "mocapdb/workflow/manifest.hpp"

using namespace mocapdb;

TEST_CASE("manifest: fields, quoting and matching", "[store][manifest]") {
    const workflow::Manifest m = workflow::Manifest::parse(
        "file,subject,description,labels,fps\r\n"
        "16_15.amc,16,\"walk, veer left\",walk;turn ; left,\n"
        "\n"
        "02_01_60fps,2,\"a \"\"quoted\"\" walk\",,60\n",
        "m.csv");
    CHECK(m.size() == 2);
    const workflow::ManifestEntry* a = m.find("/data/cmu/16_15.amc");
    REQUIRE(a != nullptr);
    CHECK(a->subject == "16");
    CHECK(a->description == "walk, veer left");
    CHECK(a->labels == std::vector<std::string>{"walk", "turn", "left"});
    CHECK_FALSE(a->frame_rate.has_value());
    const workflow::ManifestEntry* b = m.find("x/02_01_60fps.bvh");  // matched by stem
    REQUIRE(b != nullptr);
    CHECK(b->description == "a \"quoted\" walk");
    CHECK(b->frame_rate == std::optional<double>(60.0));
    CHECK(m.find("16_16.amc") == nullptr);
}

TEST_CASE("manifest: malformed input names the line and column", "[store][manifest]") {
    CHECK_THROWS_WITH(workflow::Manifest::parse("file,colour\na,b\n", "m.csv"),
                      Catch::Contains("m.csv:1:6: unknown manifest column 'colour'"));
    CHECK_THROWS_WITH(workflow::Manifest::parse("subject\n16\n", "m.csv"), Catch::Contains("no 'file' column"));
    CHECK_THROWS_WITH(workflow::Manifest::parse("file,subject\na.amc\n", "m.csv"),
                      Catch::Contains("m.csv:2: expected 2 comma-separated cells (as in the header), found 1"));
    CHECK_THROWS_WITH(workflow::Manifest::parse("file\na.amc\na.amc\n", "m.csv"),
                      Catch::Contains("m.csv:3:1: file 'a.amc' is listed twice (first on line 2)"));
    CHECK_THROWS_WITH(workflow::Manifest::parse("file,fps\na.amc,fast\n", "m.csv"),
                      Catch::Contains("m.csv:2:7: expected a positive frame rate in Hz, found 'fast'"));
    CHECK_THROWS_WITH(workflow::Manifest::parse("file\n\"a.amc\n", "m.csv"), Catch::Contains("m.csv:2:1: unterminated quoted field"));
    CHECK_THROWS_AS(workflow::Manifest::parse("", "m.csv"), ParseError);
}
