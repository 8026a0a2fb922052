#include <catch2/catch.hpp>

#include <limits>
#include <sstream>

#include "mocapdb/core/error.hpp"
#include "mocapdb/io/bvh.hpp"
#include "mocapdb/io/frame_rate.hpp"
#include "mocapdb/motion/forward_kinematics.hpp"

using namespace mocapdb;
using Catch::Matchers::Contains;

namespace {

// Tabs, CRLF, scientific notation, a leading '+', every rotation order, two End Sites under one joint.
const char* kSample =
    "HIERARCHY\r\n"
    "ROOT Hips\r\n"
    "{\r\n"
    "\tOFFSET 0 0 0\r\n"
    "\tCHANNELS 6 Xposition Yposition Zposition Yrotation Xrotation Zrotation\r\n"
    "\tJOINT A\r\n"
    "\t{\r\n"
    "\t\tOFFSET 0 1.0e1 0\r\n"
    "\t\tCHANNELS 3 Xrotation Yrotation Zrotation\r\n"
    "\t\tJOINT B\r\n"
    "\t\t{\r\n"
    "\t\t\tOFFSET 1 2 3\r\n"
    "\t\t\tCHANNELS 3 Xrotation Zrotation Yrotation\r\n"
    "\t\t\tEnd Site\r\n"
    "\t\t\t{\r\n"
    "\t\t\t\tOFFSET 0 5 0\r\n"
    "\t\t\t}\r\n"
    "\t\t\tEnd Site\r\n"
    "\t\t\t{\r\n"
    "\t\t\t\tOFFSET 0 0 5\r\n"
    "\t\t\t}\r\n"
    "\t\t}\r\n"
    "\t}\r\n"
    "\tJOINT C\r\n"
    "\t{\r\n"
    "\t\tOFFSET -4 0 0\r\n"
    "\t\tCHANNELS 3 Zrotation Yrotation Xrotation\r\n"
    "\t\tJOINT D\r\n"
    "\t\t{\r\n"
    "\t\t\tOFFSET 0 -3 0\r\n"
    "\t\t\tCHANNELS 3 Zrotation Xrotation Yrotation\r\n"
    "\t\t\tJOINT E\r\n"
    "\t\t\t{\r\n"
    "\t\t\t\tOFFSET 0 -3 0\r\n"
    "\t\t\t\tCHANNELS 3 Yrotation Zrotation Xrotation\r\n"
    "\t\t\t\tEnd Site\r\n"
    "\t\t\t\t{\r\n"
    "\t\t\t\t\tOFFSET 0 -1 0\r\n"
    "\t\t\t\t}\r\n"
    "\t\t\t}\r\n"
    "\t\t}\r\n"
    "\t}\r\n"
    "}\r\n"
    "MOTION\r\n"
    "Frames:\t2\r\n"
    "Frame Time:\t0.0083333333\r\n"
    "1 2 3 90 0 0 10 20 30 1e1 -2.5E+1 +3 45 45 45 0 0 0 -170 170 5\r\n"
    "1.5\t2\t3\t91 0 0 10 20 30 10 -25 3 45 45 45 0 0 0 -175 175 5\r\n";

std::string sample_with(const std::string& from, const std::string& to) {
    std::string s = kSample;
    const auto at = s.find(from);
    REQUIRE(at != std::string::npos);
    s.replace(at, from.size(), to);
    return s;
}

}  // namespace

TEST_CASE("BVH: tabs, CRLF, scientific notation, all six orders, End Sites", "[bvh]") {
    Warnings warnings;
    const Clip clip = parse_bvh(kSample, "sample.bvh", {}, &warnings);
    CHECK(warnings.empty());
    const Skeleton& s = *clip.skeleton;
    REQUIRE(s.size() == 9);  // Hips A B B_end B_end2 C D E E_end
    CHECK(s.joint(3).name == "B_end");
    CHECK(s.joint(4).name == "B_end2");
    CHECK(s.joint(3).end_site);
    CHECK(s.joint(1).offset == Vec3(0, 10, 0));
    CHECK(s.joint(0).rotation_order == EulerOrder::YXZ);
    CHECK(s.joint(1).rotation_order == EulerOrder::XYZ);
    CHECK(s.joint(2).rotation_order == EulerOrder::XZY);
    CHECK(s.joint(5).rotation_order == EulerOrder::ZYX);
    CHECK(s.joint(6).rotation_order == EulerOrder::ZXY);
    CHECK(s.joint(7).rotation_order == EulerOrder::YZX);
    CHECK(s.channel_count() == 21);
    REQUIRE(clip.frame_count() == 2);
    CHECK(clip.frame_rate == Approx(120.0).epsilon(1e-8));
    CHECK(clip.channels(0, 3) == Approx(kPi / 2));
    CHECK(clip.channels(0, 9) == Approx(10 * kPi / 180));
    CHECK(clip.channels(0, 10) == Approx(-25 * kPi / 180));
    CHECK(clip.channels(0, 11) == Approx(3 * kPi / 180));
    CHECK(clip.channels(1, 0) == 1.5);
}

TEST_CASE("BVH: write then read returns the same skeleton and values", "[bvh]") {
    const Clip clip = parse_bvh(kSample, "sample.bvh");
    for (int precision : {6, 9, 17}) {
        std::ostringstream out;
        BvhWriteOptions options;
        options.precision = precision;
        write_bvh(out, clip, options);
        const Clip back = parse_bvh(out.str(), "written.bvh");
        CHECK(back.skeleton->same_structure(*clip.skeleton));
        CHECK(back.frame_rate == Approx(clip.frame_rate).epsilon(1e-15));
        const double tol = 2 * std::pow(10.0, 1 - precision) * clip.channels.cwiseAbs().maxCoeff();
        INFO("precision " << precision);
        CHECK((back.channels - clip.channels).cwiseAbs().maxCoeff() <= tol);
    }
}

TEST_CASE("BVH: Frames larger than the rows present warns, or fails in strict mode", "[bvh]") {
    const std::string text = sample_with("Frames:\t2", "Frames:\t3");
    Warnings warnings;
    const Clip clip = parse_bvh(text, "short.bvh", {}, &warnings);
    CHECK(clip.frame_count() == 2);
    REQUIRE(warnings.size() == 1);
    CHECK_THAT(warnings[0].to_string(), Contains("short.bvh") && Contains("declares 3 frames but 2"));
    BvhReadOptions strict;
    strict.strict = true;
    CHECK_THROWS_WITH(parse_bvh(text, "short.bvh", strict), Contains("short.bvh") && Contains("declares 3 frames"));
}

TEST_CASE("BVH: a wrong Frame Time can be overridden", "[bvh]") {
    BvhReadOptions options;
    options.frame_rate = 60.0;
    CHECK(parse_bvh(kSample, "s.bvh", options).frame_rate == 60.0);
    const std::string zero = sample_with("Frame Time:\t0.0083333333", "Frame Time:\t0");
    CHECK_THROWS_WITH(parse_bvh(zero, "z.bvh"), Contains("Frame Time must be positive"));
    CHECK(parse_bvh(zero, "z.bvh", options).frame_rate == 60.0);
}

TEST_CASE("BVH: a given frame rate that disagrees with the Frame Time by more than 1 % warns, naming both", "[bvh]") {
    // kSample's Frame Time is 0.0083333333 s (120 Hz).
    BvhReadOptions options;
    Warnings warnings;
    options.frame_rate = 30.0;
    CHECK(parse_bvh(kSample, "s.bvh", options, &warnings).frame_rate == 30.0);
    REQUIRE(warnings.size() == 1);
    CHECK_THAT(warnings[0].to_string(), Contains("s.bvh") && Contains("30 Hz") && Contains("0.00833333 s (120 Hz)"));
    // Within 1 %: no warning (119 Hz is 0.83 % off); just beyond it: a warning.
    warnings.clear();
    options.frame_rate = 119.0;
    parse_bvh(kSample, "s.bvh", options, &warnings);
    CHECK(warnings.empty());
    options.frame_rate = 121.3;
    parse_bvh(kSample, "s.bvh", options, &warnings);
    CHECK(warnings.size() == 1);
    // No override: nothing to compare.
    warnings.clear();
    parse_bvh(kSample, "s.bvh", {}, &warnings);
    CHECK(warnings.empty());
}

TEST_CASE("BVH: a frame rate <= 0, absurd or not finite is a clear error", "[bvh]") {
    for (const double bad : {0.0, -30.0, 20000.0, std::numeric_limits<double>::infinity(),
                             std::numeric_limits<double>::quiet_NaN()}) {
        BvhReadOptions options;
        options.frame_rate = bad;
        CHECK_THROWS_AS(parse_bvh(kSample, "s.bvh", options), InvalidArgument);
        try {
            parse_bvh(kSample, "s.bvh", options);
        } catch (const InvalidArgument& e) {
            const std::string what = e.what();
            CHECK_THAT(what, Contains("frame rate must be > 0 and <= 10000 Hz, got"));
            CHECK(what.size() < 120);  // the value as %g, never hundreds of digits
        }
    }
    CHECK_THROWS_WITH(check_frame_rate(0.0, "x"), "x: frame rate must be > 0 and <= 10000 Hz, got 0");
    CHECK_NOTHROW(check_frame_rate(10000.0, "x"));
}

TEST_CASE("BVH: bad input names file, line and what was expected", "[bvh]") {
    struct Case {
        std::string text;
        std::string expected;
    };
    const std::string truncated = std::string(kSample).substr(0, std::string(kSample).find("MOTION") - 20);
    const Case cases[] = {
        {"", "expected 'HIERARCHY', found end of file"},
        {"garbage\x01\x02", "expected 'HIERARCHY', found 'garbage\\x01\\x02'"},
        {truncated, "end of file"},
        {sample_with("CHANNELS 3 Xrotation Yrotation Zrotation", "CHANNELS 3 Xrotation Yrotation Qrotation"),
         "sample.bvh:9:"},
        {sample_with("CHANNELS 3 Xrotation Yrotation Zrotation", "CHANNELS 3 Xrotation Yrotation Qrotation"),
         "expected a channel name"},
        {sample_with("CHANNELS 3 Xrotation Yrotation Zrotation", "CHANNELS 3 Xrotation Yrotation Xrotation"),
         "twice"},
        {sample_with("CHANNELS 3 Xrotation Yrotation Zrotation", "CHANNELS 7 Xrotation Yrotation Zrotation"),
         "at most 6"},
        {sample_with("1 2 3 90", "1 2 90"), "sample.bvh:47: frame 1 has 20 values, expected 21"},
        {sample_with("1 2 3 90", "1 2 3 4 90"), "sample.bvh:47: frame 1 has 22 values, expected 21"},
        {sample_with("10 20 30 1e1", "10 20 30 nan"), "sample.bvh:47:"},
        {sample_with("10 20 30 1e1", "10 20 30 inf"), "channel value"},
        {sample_with("10 20 30 1e1", "10 20 30 1e300"), "absurdly large"},
        {sample_with("10 20 30 1e1", "10 20 30 1e999"), "out of range"},
        {sample_with("OFFSET 1 2 3", "OFFSET 1 2 x"), "sample.bvh:12:"},
        {sample_with("JOINT D", "JOINT A"), "duplicate joint name 'A'"},
        {sample_with("Frames:\t2", "Frames:\t-2"), "frame count"},
        {sample_with("JOINT C", "JIONT C"), "expected JOINT, End Site or '}'"},
    };
    for (const Case& c : cases) {
        INFO("expecting: " << c.expected);
        CHECK_THROWS_AS(parse_bvh(c.text, "sample.bvh"), ParseError);
        CHECK_THROWS_WITH(parse_bvh(c.text, "sample.bvh"), Contains("sample.bvh") && Contains(c.expected));
    }
}

TEST_CASE("BVH: a truncated last row is dropped with a warning, refused when strict", "[bvh]") {
    std::string text = kSample;
    text = text.substr(0, text.size() - 12);  // cut the last row short
    Warnings warnings;
    const Clip clip = parse_bvh(text, "cut.bvh", {}, &warnings);
    CHECK(clip.frame_count() == 1);
    CHECK(warnings.size() == 2);  // the dropped row, and Frames: larger than rows
    BvhReadOptions strict;
    strict.strict = true;
    CHECK_THROWS_WITH(parse_bvh(text, "cut.bvh", strict), Contains("cut.bvh:48"));
}

TEST_CASE("BVH: forward kinematics of a parsed file", "[bvh][fk]") {
    const Clip clip = parse_bvh(kSample, "sample.bvh");
    GlobalPose pose;
    forward_kinematics(*clip.skeleton, clip.frame(0), pose);
    // Root at (1,2,3), yawed 90° about Y (YXZ with X = Z = 0): A's offset (0,10,0) is unaffected.
    CHECK((pose.positions[0] - Vec3(1, 2, 3)).norm() < 1e-12);
    CHECK((pose.positions[1] - Vec3(1, 12, 3)).norm() < 1e-12);
    // C's offset (−4,0,0) turned by Ry(90°) becomes (0,0,4).
    CHECK((pose.positions[5] - Vec3(1, 2, 7)).norm() < 1e-12);
}
