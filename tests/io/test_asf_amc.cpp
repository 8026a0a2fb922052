#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <random>
#include <regex>
#include <sstream>

#include "mocapdb/core/error.hpp"
#include "mocapdb/io/asf_amc.hpp"
#include "mocapdb/io/text_file.hpp"
#include "mocapdb/motion/forward_kinematics.hpp"
#include "shared_data.hpp"

using namespace mocapdb;
using Catch::Matchers::Contains;

namespace {

// A hand-made skeleton exercising what CMU files do not: a permuted root order, a root orientation
// with a non-XYZ axis order, bone axes in other orders, dof subsets out of XYZ order, a length unit
// other than CMU's, and limits glued to or apart from their parentheses, with infinities.
const char* const kTinyAsf = R"(# hand-made test skeleton
:version 1.10
:name tiny
:units
  mass 1.0
  length 0.5
  angle deg
:documentation
  root, then upper -> lower
:root
   order RY TX RX TZ RZ TY
   axis ZXY
   position 1 2 3
   orientation 10 -20 30
:bonedata
  begin
     id 1
     name upper
     direction 0.6 0 0.8
     length 4
     axis 30 -20 45 YZX
     dof rz rx
     limits (-90.0 90.0)
            ( -inf inf )
  end
  begin
     id 2
     name lower  # the second bone
     direction 0 -1 0
     length 3
     axis 10 60 -30 XYZ
     dof ry rx rz
  end
:hierarchy
  begin
    root upper
    upper lower
  end
)";

// Three frames; values follow the dof order (root: RY TX RX TZ RZ TY).
const char* const kTinyAmc = R"(# motion for the tiny skeleton
:FULLY-SPECIFIED
:DEGREES
1
root 20 1 2 3 -40 5
upper 35 -50
lower 15 25 -60
2
root -10 0.5 -3 1.5 12 0
upper -80 10
lower 170 -45 5
3
lower 0 0 0
upper 0 0
root 0 0 0 0 0 0
)";

std::shared_ptr<const Skeleton> tiny_skeleton() {
    return std::make_shared<const Skeleton>(parse_asf(kTinyAsf, "tiny.asf"));
}

// 1-based line of the first occurrence of `marker` in `text` (fixture introspection for error lines).
std::size_t line_of(const std::string& text, const std::string& marker) {
    const std::size_t pos = text.find(marker);
    REQUIRE(pos != std::string::npos);
    return 1 + static_cast<std::size_t>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(pos), '\n'));
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
    const std::size_t pos = text.find(from);
    REQUIRE(pos != std::string::npos);
    return text.replace(pos, from.size(), to);
}

std::string to_crlf(const std::string& lf) {
    std::string out;
    out.reserve(lf.size() + lf.size() / 16);
    for (char c : lf) {
        if (c == '\n') out += '\r';
        out += c;
    }
    return out;
}

// what() of the ParseError the call throws; fails the test when it throws nothing or something else.
template <class F>
std::string parse_error_of(F&& f) {
    try {
        f();
    } catch (const ParseError& e) {
        return e.what();
    } catch (const std::exception& e) {
        FAIL("expected ParseError, got another exception: " << e.what());
    }
    FAIL("expected ParseError, nothing was thrown");
    return {};
}

std::string asf_error(const std::string& asf) {
    return parse_error_of([&] { parse_asf(asf, "bad.asf"); });
}

std::string amc_error(const std::string& amc, bool strict = false) {
    AmcReadOptions options;
    options.strict = strict;
    return parse_error_of([&] { parse_amc(amc, "bad.amc", tiny_skeleton(), options); });
}

std::string at(const std::string& file, std::size_t line) { return file + ":" + std::to_string(line) + ":"; }

// ---- ASF definitions written out independently of Skeleton::local_rotation ----

Mat3 rot(int axis, double degrees) { return Eigen::AngleAxisd(degrees * kPi / 180.0, Vec3::Unit(axis)).toRotationMatrix(); }
constexpr int X = 0, Y = 1, Z = 2;

// ---- the shared CMU data, loaded once for the whole executable ----

std::filesystem::path cmu_dir() { return test::datasets_dir() / "cmu-asfamc"; }

struct CmuClip {
    std::string stem;
    Clip clip;
    Warnings warnings;
};

struct CmuData {
    std::vector<CmuClip> clips;
    std::vector<std::string> failures;  // "path: what()"
    std::size_t amc_files = 0;
};

const CmuData& cmu_data() {
    static const CmuData data = [] {
        CmuData d;
        std::vector<std::filesystem::path> paths;
        for (const auto& entry : std::filesystem::directory_iterator(cmu_dir()))
            if (entry.path().extension() == ".amc") paths.push_back(entry.path());
        std::sort(paths.begin(), paths.end());
        d.amc_files = paths.size();
        std::map<std::string, std::shared_ptr<const Skeleton>> skeletons;
        for (const auto& p : paths) {
            try {
                const auto asf = find_asf_for_amc(p);
                if (!asf) {
                    d.failures.push_back(p.string() + ": no ASF found");
                    continue;
                }
                auto& skeleton = skeletons[asf->string()];
                if (!skeleton) skeleton = read_asf(*asf);
                CmuClip c;
                c.stem = p.stem().string();
                c.clip = read_amc(p, skeleton, {}, &c.warnings);
                d.clips.push_back(std::move(c));
            } catch (const std::exception& e) {
                d.failures.push_back(p.string() + ": " + e.what());
            }
        }
        return d;
    }();
    return data;
}

// Frame counts from the CLIPS table of SOURCE.txt ("  16_15.amc     471  walk ... | ...").
std::map<std::string, long> source_frame_counts() {
    std::ifstream in(cmu_dir() / "SOURCE.txt");
    std::map<std::string, long> out;
    const std::regex row(R"(^\s+(\d+_\d+)\.amc\s+(\d+)\s.*\|.*)");
    bool in_table = false;
    for (std::string line; std::getline(in, line);) {
        if (line.rfind("CLIPS", 0) == 0) in_table = true;
        if (line.rfind("GROUPS", 0) == 0) break;
        std::smatch m;
        if (in_table && std::regex_match(line, m, row)) out[m[1].str()] = std::stol(m[2].str());
    }
    return out;
}

}  // namespace

// ================================================================ ASF structure

TEST_CASE("ASF: joints are root then bones depth-first in :hierarchy order with an end site after each leaf", "[io][asf]") {
    const std::string asf = R"(:units
  length 1
:root
  order TX TY TZ RX RY RZ
:bonedata
  begin
    name a
    direction 1 0 0
    length 1
  end
  begin
    name b
    direction 0 1 0
    length 2
  end
  begin
    name c
    direction 0 0 1
    length 3
    dof rx
  end
  begin
    name d
    direction 0 0 -1
    length 4
    dof tx rz
  end
:hierarchy
  begin
    root b a
    a c
    b d
  end
)";
    const Skeleton s = parse_asf(asf, "tree.asf");
    std::vector<std::string> names;
    for (const Joint& j : s.joints()) names.push_back(j.name);
    CHECK(names == std::vector<std::string>{"root", "b", "d", "d_end", "a", "c", "c_end"});
    for (std::size_t i = 0; i < s.size(); ++i) CHECK(s.joint(i).end_site == (names[i].size() > 4 && names[i].substr(names[i].size() - 4) == "_end"));
    const double cm = 2.54;  // length factor 1: file lengths are inches
    CHECK(s.source_units().cm_per_unit == Approx(cm));
    CHECK(s.joint(*s.find("b")).offset.isZero());                                  // root children: no bone before
    CHECK(s.joint(*s.find("d")).offset.isApprox(Vec3(0, 2 * cm, 0)));             // b's vector
    CHECK(s.joint(*s.find("d_end")).offset.isApprox(Vec3(0, 0, -4 * cm)));        // d's own vector
    CHECK(s.joint(*s.find("c")).offset.isApprox(Vec3(1 * cm, 0, 0)));
    CHECK(s.joint(*s.find("c_end")).offset.isApprox(Vec3(0, 0, 3 * cm)));
    CHECK(s.joint(0).channels == std::vector<ChannelType>{ChannelType::Xposition, ChannelType::Yposition,
                                                          ChannelType::Zposition, ChannelType::Xrotation,
                                                          ChannelType::Yrotation, ChannelType::Zrotation});
    CHECK(s.joint(0).rotation_order == EulerOrder::ZYX);  // RX RY RZ: R = Rz·Ry·Rx
    CHECK(s.joint(*s.find("b")).channels.empty());
    CHECK(s.joint(*s.find("d")).channels == std::vector<ChannelType>{ChannelType::Xposition, ChannelType::Zrotation});
    CHECK(s.channel_count() == 6 + 1 + 2);
    CHECK(s.forward() == Vec3::UnitZ());
    CHECK(s.source_units().degrees);
}

TEST_CASE("ASF: the tiny skeleton's channels, orders and units", "[io][asf]") {
    const auto s = tiny_skeleton();
    REQUIRE(s->size() == 4);
    CHECK(s->joint(0).name == "root");
    CHECK(s->joint(1).name == "upper");
    CHECK(s->joint(2).name == "lower");
    CHECK(s->joint(3).name == "lower_end");
    using C = ChannelType;
    CHECK(s->joint(0).channels == std::vector<C>{C::Yrotation, C::Xposition, C::Xrotation, C::Zposition,
                                                 C::Zrotation, C::Yposition});
    CHECK(s->joint(1).channels == std::vector<C>{C::Zrotation, C::Xrotation});
    CHECK(s->joint(2).channels == std::vector<C>{C::Yrotation, C::Xrotation, C::Zrotation});
    CHECK(s->source_units().cm_per_unit == Approx(2.54 / 0.5));
    CHECK(s->joint(0).offset.isApprox(Vec3(1, 2, 3) * (2.54 / 0.5)));
}

// ================================================================ hand-checked forward kinematics

TEST_CASE("ASF/AMC: joint positions equal a hand computation from the ASF definition", "[io][asf][amc]") {
    Warnings warnings;
    const Clip clip = parse_amc(kTinyAmc, "dir/tiny_01.amc", tiny_skeleton(), {}, &warnings);
    CHECK(warnings.empty());
    CHECK(clip.name == "tiny_01");
    CHECK(clip.frame_rate == 120.0);
    REQUIRE(clip.frame_count() == 3);

    // Raw AMC values per frame as written in kTinyAmc (root: RY TX RX TZ RZ TY; upper: rz rx; lower: ry rx rz).
    struct Frame {
        double ry, tx, rx, tz, rz, ty;
        double u_rz, u_rx;
        double l_ry, l_rx, l_rz;
    };
    const Frame frames[] = {{20, 1, 2, 3, -40, 5, 35, -50, 15, 25, -60},
                            {-10, 0.5, -3, 1.5, 12, 0, -80, 10, 170, -45, 5},
                            {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0}};
    const double u = 2.54 / 0.5;  // cm per file unit (":units length 0.5")
    // Axis matrices C: angles about X, Y, Z as written; the order string's first axis is applied first.
    const Mat3 c_root = rot(Y, -20) * rot(X, 10) * rot(Z, 30);   // orientation 10 -20 30, axis ZXY
    const Mat3 c_upper = rot(X, 30) * rot(Z, 45) * rot(Y, -20);  // axis 30 -20 45 YZX
    const Mat3 c_lower = rot(Z, -30) * rot(Y, 60) * rot(X, 10);  // axis 10 60 -30 XYZ

    MatX positions = joint_positions(clip);
    for (int f = 0; f < 3; ++f) {
        const Frame& v = frames[f];
        // Dof lists: the first listed is applied first.
        const Mat3 r_root = rot(Z, v.rz) * rot(X, v.rx) * rot(Y, v.ry);  // RY RX RZ
        const Mat3 r_upper = rot(X, v.u_rx) * rot(Z, v.u_rz);            // rz rx
        const Mat3 r_lower = rot(Z, v.l_rz) * rot(X, v.l_rx) * rot(Y, v.l_ry);  // ry rx rz
        const Mat3 m_root = c_root * r_root * c_root.transpose();
        const Mat3 m_upper = m_root * c_upper * r_upper * c_upper.transpose();
        const Mat3 m_lower = m_upper * c_lower * r_lower * c_lower.transpose();
        const Vec3 root = (Vec3(1, 2, 3) + Vec3(v.tx, v.ty, v.tz)) * u;
        const Vec3 upper_end = root + m_upper * Vec3(0.6, 0, 0.8) * (4 * u);
        const Vec3 lower_end = upper_end + m_lower * Vec3(0, -1, 0) * (3 * u);
        const Vec3 expected[] = {root, root, upper_end, lower_end};
        for (int j = 0; j < 4; ++j) {
            const Vec3 got = positions.block<3, 1>(3 * j, f);
            INFO("frame " << f + 1 << " joint " << clip.skeleton->joint(static_cast<std::size_t>(j)).name
                          << " got " << got.transpose() << " expected " << expected[j].transpose());
            CHECK((got - expected[j]).norm() < 1e-9);
        }
    }
}

TEST_CASE("AMC: :RADIANS values are taken as radians and a clash with the ASF unit is a warning", "[io][amc]") {
    // Same motion as frame 1 of kTinyAmc, written in radians.
    const double d = kPi / 180.0;
    std::ostringstream amc;
    amc.precision(17);
    amc << ":RADIANS\n1\nroot " << 20 * d << " 1 " << 2 * d << " 3 " << -40 * d << " 5\nupper " << 35 * d << " "
        << -50 * d << "\nlower " << 15 * d << " " << 25 * d << " " << -60 * d << "\n";
    Warnings warnings;
    const Clip radians = parse_amc(amc.str(), "r.amc", tiny_skeleton(), {}, &warnings);
    REQUIRE(warnings.size() == 1);
    CHECK(warnings[0].line == 1);
    CHECK_THAT(warnings[0].message, Contains(":RADIANS") && Contains("deg"));
    const Clip degrees = parse_amc(kTinyAmc, "d.amc", tiny_skeleton());
    CHECK((radians.channels.row(0) - degrees.channels.row(0)).cwiseAbs().maxCoeff() < 1e-12);

    AmcReadOptions strict;
    strict.strict = true;
    CHECK_THROWS_AS(parse_amc(amc.str(), "r.amc", tiny_skeleton(), strict), ParseError);
}

// ================================================================ real CMU data

TEST_CASE("CMU: every AMC loads with the ASF found by find_asf_for_amc", "[io][amc][shared]") {
    MOCAPDB_REQUIRE_SHARED(cmu_dir());
    const CmuData& data = cmu_data();
    for (const auto& f : data.failures) FAIL_CHECK(f);
    CHECK(data.amc_files == 182);
    CHECK(data.clips.size() == 182);

    const auto expected = source_frame_counts();
    CHECK(expected.size() == 182);
    CHECK(expected.at("16_15") == 471);  // spot checks that the table was read
    CHECK(expected.at("14_06") == 5357);
    std::size_t compared = 0;
    for (const CmuClip& c : data.clips) {
        INFO(c.stem);
        CHECK(c.warnings.empty());
        CHECK(c.clip.skeleton->channel_count() == 62);
        CHECK(c.clip.name == c.stem);
        CHECK(c.clip.frame_rate == 120.0);
        CHECK_NOTHROW(validate(c.clip));
        const auto it = expected.find(c.stem);
        if (it == expected.end()) continue;
        CHECK(static_cast<long>(c.clip.frame_count()) == it->second);
        ++compared;
    }
    CHECK(compared == 182);
}

TEST_CASE("CMU: the skeleton follows the ASF file", "[io][asf][shared]") {
    MOCAPDB_REQUIRE_SHARED(cmu_dir());
    const auto s = read_asf(cmu_dir() / "16.asf");
    CHECK(s->source_units().cm_per_unit == Approx(2.54 / 0.45));
    CHECK(s->source_units().degrees);
    // 1 root + 30 bones + an end site for each of the 7 leaves (ltoes rtoes head lfingers lthumb rfingers rthumb).
    CHECK(s->size() == 38);
    CHECK(s->joint(1).name == "lhipjoint");
    CHECK(s->joint(2).name == "lfemur");
    CHECK(s->joint(5).name == "ltoes");
    CHECK(s->joint(6).name == "ltoes_end");
    CHECK(s->joint(7).name == "rhipjoint");
    // lfemur hangs off lhipjoint: "direction 0.635348 -0.713158 0.296208", "length 2.47672" in 16.asf.
    const Vec3 lhip = Vec3(0.635348, -0.713158, 0.296208) * 2.47672 * (2.54 / 0.45);
    CHECK((s->joint(2).offset - lhip).norm() < 1e-9);
    // lfemur "axis 0 0 20 XYZ"
    CHECK(angle_between(s->joint(2).axis, Quat(Eigen::AngleAxisd(20 * kPi / 180, Vec3::UnitZ()))) < 1e-12);
    CHECK(s->joint(2).rotation_order == EulerOrder::ZYX);  // dof rx ry rz
    CHECK(s->joint(*s->find("lfoot")).channels ==
          std::vector<ChannelType>{ChannelType::Xrotation, ChannelType::Zrotation});
    for (std::size_t j = 0; j < s->size(); ++j)
        if (s->joint(j).end_site) {
            CHECK(s->joint(j).name == s->joint(j - 1).name + "_end");
            CHECK(s->joint(j).parent == static_cast<int>(j - 1));
        }
}

TEST_CASE("CMU: FK bone lengths are constant and equal the child's offset", "[io][amc][shared]") {
    MOCAPDB_REQUIRE_SHARED(cmu_dir());
    const CmuData& data = cmu_data();
    REQUIRE_FALSE(data.clips.empty());
    for (const CmuClip& c : data.clips) {
        const Skeleton& s = *c.clip.skeleton;
        const MatX p = joint_positions(c.clip);
        double worst = 0.0;
        std::string worst_joint;
        for (std::size_t j = 1; j < s.size(); ++j) {
            const auto parent = static_cast<Eigen::Index>(s.joint(j).parent);
            const double expected = s.joint(j).offset.norm();
            const double tol_scale = std::max(expected, 1.0);  // root children have zero offset
            for (Eigen::Index f = 0; f < p.cols(); ++f) {
                const double len = (p.block<3, 1>(3 * static_cast<Eigen::Index>(j), f) - p.block<3, 1>(3 * parent, f)).norm();
                const double err = std::abs(len - expected) / tol_scale;
                if (err > worst) {
                    worst = err;
                    worst_joint = s.joint(j).name;
                }
            }
        }
        INFO(c.stem << ": worst relative bone-length error " << worst << " at " << worst_joint);
        CHECK(worst < 1e-6);
    }
}

TEST_CASE("CMU: a CRLF copy parses exactly like the LF original", "[io][asf][amc][shared]") {
    MOCAPDB_REQUIRE_SHARED(cmu_dir());
    const std::string asf = read_text_file(cmu_dir() / "16.asf");
    const std::string amc = read_text_file(cmu_dir() / "16_15.amc");
    REQUIRE(asf.find('\r') == std::string::npos);
    REQUIRE(amc.find('\r') == std::string::npos);
    const auto lf_skeleton = std::make_shared<const Skeleton>(parse_asf(asf, "16.asf"));
    const auto crlf_skeleton = std::make_shared<const Skeleton>(parse_asf(to_crlf(asf), "16.asf"));
    CHECK(crlf_skeleton->same_structure(*lf_skeleton, 0.0));
    const Clip lf = parse_amc(amc, "16_15.amc", lf_skeleton);
    const Clip crlf = parse_amc(to_crlf(amc), "16_15.amc", crlf_skeleton);
    CHECK(lf.frame_count() == 471);
    CHECK(crlf.channels == lf.channels);
}

TEST_CASE("find_asf_for_amc follows the CMU naming", "[io][amc]") {
    const auto dir = std::filesystem::temp_directory_path() / ("mocapdb_asf_test_" + std::to_string(std::random_device{}()));
    std::filesystem::create_directories(dir);
    { std::ofstream(dir / "07.asf") << kTinyAsf; }
    CHECK(find_asf_for_amc(dir / "07_12.amc") == dir / "07.asf");
    CHECK_FALSE(find_asf_for_amc(dir / "08_01.amc"));
    CHECK_FALSE(find_asf_for_amc(dir / "0712.amc"));
    std::filesystem::remove_all(dir);
}

// ================================================================ bad input

TEST_CASE("ASF: malformed skeletons give a ParseError naming file and line and what was expected", "[io][asf][errors]") {
    const std::string good = kTinyAsf;
    SECTION("truncated inside a bone") {
        const std::string cut = good.substr(0, good.find("     axis 30"));
        CHECK_THAT(asf_error(cut), Contains("bad.asf:") && Contains("unexpected end of file in the bone begun at line " +
                                                                    std::to_string(line_of(good, "  begin"))));
    }
    SECTION("truncated in :hierarchy") {
        const std::string cut = good.substr(0, good.find("    upper lower"));
        CHECK_THAT(asf_error(cut), Contains("in :hierarchy (expected 'end')"));
    }
    SECTION("garbage") {
        const char raw[] = "\x01\x7f\xfe garbage {}\n\0\0 more\n";
        const std::string garbage(raw, sizeof raw - 1);
        CHECK_THAT(asf_error(garbage), Contains(at("bad.asf", 1)) && Contains("expected a section keyword"));
        CHECK_THAT(asf_error("BVH\nHIERARCHY\n"), Contains(at("bad.asf", 1)) && Contains("found 'BVH'"));
        CHECK_THAT(asf_error(""), Contains("no :root section"));
    }
    SECTION("unknown axis order") {
        const std::string bad = replaced(good, "45 YZX", "45 XYQ");
        CHECK_THAT(asf_error(bad), Contains(at("bad.asf", line_of(good, "45 YZX"))) &&
                                       Contains("unknown axis order 'XYQ'") && Contains("expected XYZ"));
        CHECK_THAT(asf_error(replaced(good, "axis ZXY", "axis ZZY")),
                   Contains(at("bad.asf", line_of(good, "axis ZXY"))) && Contains("unknown axis order 'ZZY'"));
    }
    SECTION(":hierarchy names a bone that does not exist") {
        const std::string bad = replaced(good, "upper lower", "upper lowr");
        CHECK_THAT(asf_error(bad), Contains(at("bad.asf", line_of(good, "upper lower"))) &&
                                       Contains("unknown bone 'lowr' in :hierarchy"));
        CHECK_THAT(asf_error(replaced(good, "upper lower", "uper lower")), Contains("unknown bone 'uper'"));
    }
    SECTION("a bone with two parents") {
        const std::string bad = replaced(good, "    upper lower\n", "    upper lower\n    root lower\n");
        CHECK_THAT(asf_error(bad), Contains(at("bad.asf", line_of(good, "upper lower") + 1)) &&
                                       Contains("bone 'lower' has two parents") && Contains("'upper' (line " + std::to_string(line_of(good, "upper lower")) + ")"));
    }
    SECTION("cycles") {
        const std::string two = replaced(good, "    root upper\n    upper lower\n", "    upper lower\n    lower upper\n");
        CHECK_THAT(asf_error(two), Contains(at("bad.asf", line_of(good, "upper lower"))) && Contains("cycle in :hierarchy"));
        const std::string self = replaced(good, "    root upper\n    upper lower\n", "    root upper\n    lower lower\n");
        CHECK_THAT(asf_error(self), Contains("cycle in :hierarchy") && Contains("'lower'"));
    }
    SECTION("a bone outside the hierarchy") {
        const std::string bad = replaced(good, "    upper lower\n", "");
        CHECK_THAT(asf_error(bad), Contains(at("bad.asf", line_of(good, "name lower"))) &&
                                       Contains("bone 'lower' is not connected to the root"));
    }
    SECTION("NaN, infinities and absurd magnitudes") {
        for (const char* v : {"nan", "inf", "-inf", "1e300", "2e9"}) {
            INFO(v);
            const std::string bad = replaced(good, "length 4", std::string("length ") + v);
            CHECK_THAT(asf_error(bad), Contains(at("bad.asf", line_of(good, "length 4"))) && Contains(v));
        }
        CHECK_THAT(asf_error(replaced(good, "length 4", "length 1e300")), Contains("absurdly large"));
        CHECK_THAT(asf_error(replaced(good, "length 4", "length nan")), Contains("not finite"));
        CHECK_THAT(asf_error(replaced(good, "length 0.5", "length 0")), Contains("length unit must be positive"));
    }
    SECTION("the l dof is refused") {
        CHECK_THAT(asf_error(replaced(good, "dof rz rx", "dof rz rx l")),
                   Contains(at("bad.asf", line_of(good, "dof rz rx"))) && Contains("dof 'l'"));
    }
    SECTION("other field errors") {
        CHECK_THAT(asf_error(replaced(good, "dof rz rx", "dof rz rw")), Contains("unknown dof 'rw'"));
        CHECK_THAT(asf_error(replaced(good, "dof rz rx", "dof rz rz")), Contains("appears twice"));
        CHECK_THAT(asf_error(replaced(good, "direction 0.6 0 0.8", "direction 0.6 0")),
                   Contains(at("bad.asf", line_of(good, "direction 0.6"))) && Contains("expected direction (a number), found end of line"));
        CHECK_THAT(asf_error(replaced(good, "            ( -inf inf )\n", "")),
                   Contains(at("bad.asf", line_of(good, "limits"))) && Contains("expected 2 limits pairs"));
        CHECK_THAT(asf_error(replaced(good, "(-90.0 90.0)", "(-90.0 90.0 7)")), Contains("expected two numbers"));
        CHECK_THAT(asf_error(replaced(good, "name lower", "name upper")),
                   Contains("duplicate bone name 'upper' (first defined at line " + std::to_string(line_of(good, "name upper")) + ")"));
        CHECK_THAT(asf_error(replaced(good, "order RY TX", "order RY QX")), Contains("unknown root channel 'QX'"));
        CHECK_THAT(asf_error(replaced(good, "     length 3\n", "")), Contains("bone 'lower' has no 'length'"));
        CHECK_THAT(asf_error(replaced(good, "     id 2\n", "     colour 2\n")), Contains("unknown bone field 'colour'"));
        CHECK_THAT(asf_error(replaced(good, ":hierarchy", ":hierarchyy")), Contains("unknown section ':hierarchyy'"));
        CHECK_THAT(asf_error(replaced(good, "angle deg", "angle grad")), Contains("expected 'deg' or 'rad'"));
        CHECK_THAT(asf_error(replaced(good, "     dof ry rx rz\n", "     dof tx\n")),
                   Contains("translation dofs (tx, ty, tz) are supported only on bones whose axis is 0 0 0"));
    }
}

TEST_CASE("AMC: malformed motion gives a ParseError naming file and line and what was expected", "[io][amc][errors]") {
    const std::string good = kTinyAmc;
    SECTION("unknown bone") {
        const std::string bad = replaced(good, "upper -80 10", "uper -80 10");
        CHECK_THAT(amc_error(bad), Contains(at("bad.amc", line_of(good, "upper -80"))) &&
                                       Contains("unknown bone 'uper' in frame 2"));
        CHECK_THAT(amc_error(replaced(good, "upper -80 10", "lower_end 1")), Contains("unknown bone 'lower_end'"));
    }
    SECTION("wrong number of values") {
        CHECK_THAT(amc_error(replaced(good, "lower 15 25 -60", "lower 15 25")),
                   Contains(at("bad.amc", line_of(good, "lower 15 25"))) &&
                       Contains("expected 3 values for bone 'lower', found 2") && Contains("frame 1"));
        CHECK_THAT(amc_error(replaced(good, "lower 15 25 -60", "lower 15 25 -60 7 8")),
                   Contains(at("bad.amc", line_of(good, "lower 15 25"))) &&
                       Contains("expected 3 values for bone 'lower', found 5"));
        CHECK_THAT(amc_error(replaced(good, "root 20 1 2 3 -40 5", "root 20 1 2 3 -40")),
                   Contains("expected 6 values for bone 'root', found 5"));
    }
    SECTION("NaN, infinities, absurd magnitudes and non-numbers") {
        for (const char* v : {"nan", "NaN", "inf", "-inf", "1e300", "-3e9", "abc", "1.5.2"}) {
            INFO(v);
            const std::string bad = replaced(good, "upper -80 10", std::string("upper -80 ") + v);
            CHECK_THAT(amc_error(bad), Contains(at("bad.amc", line_of(good, "upper -80"))) && Contains(v) &&
                                           Contains("bone 'upper', frame 2"));
        }
        CHECK_THAT(amc_error(replaced(good, "upper -80 10", "upper -80 1e300")), Contains("absurdly large"));
        CHECK_THAT(amc_error(replaced(good, "upper -80 10", "upper -80 inf")), Contains("not finite"));
    }
    SECTION("a bone missing from a frame") {
        const std::string bad = replaced(good, "upper 35 -50\n", "");
        CHECK_THAT(amc_error(bad), Contains(at("bad.amc", line_of(good, "\n1\n") + 1)) &&
                                       Contains("frame 1 has no line for bone 'upper'"));
        const std::string two = replaced(replaced(good, "upper -80 10\n", ""), "lower 170 -45 5\n", "");
        CHECK_THAT(amc_error(two), Contains("frame 2 has no line for bone 'upper' (nor for 1 other bone)"));
    }
    SECTION("a bone twice in a frame") {
        const std::string bad = replaced(good, "upper 35 -50\n", "upper 35 -50\nupper 1 2\n");
        CHECK_THAT(amc_error(bad), Contains(at("bad.amc", line_of(good, "upper 35") + 1)) &&
                                       Contains("bone 'upper' appears twice in frame 1 (first at line " +
                                                std::to_string(line_of(good, "upper 35")) + ")"));
    }
    SECTION("garbage and empty motion") {
        const char raw[] = "\xff\xfe\x01 binary\n\0\x02\n";
        const std::string garbage(raw, sizeof raw - 1);
        CHECK_THAT(amc_error(garbage), Contains(at("bad.amc", 1)) && Contains("expected a frame number"));
        CHECK_THAT(amc_error(":FULLY-SPECIFIED\n:DEGREES\n"), Contains("bad.amc: no complete motion frames"));
        CHECK_THAT(amc_error(""), Contains("no complete motion frames"));
        CHECK_THAT(amc_error("1.5\nroot 1 2 3 4 5 6\n"), Contains(at("bad.amc", 1)) && Contains("expected a frame number"));
        CHECK_THAT(amc_error("1 root\n"), Contains(at("bad.amc", 1)) && Contains("unexpected 'root' after the frame number"));
        CHECK_THAT(amc_error("99999999999999999999999\n"), Contains("expected a frame number"));
    }
    SECTION("frame numbering: a warning, or an error in strict mode") {
        const std::string gap = replaced(good, "\n3\n", "\n5\n");
        Warnings warnings;
        const Clip clip = parse_amc(gap, "gap.amc", tiny_skeleton(), {}, &warnings);
        CHECK(clip.frame_count() == 3);
        REQUIRE(warnings.size() == 1);
        CHECK(warnings[0].line == line_of(good, "\n3\n") + 1);
        CHECK_THAT(warnings[0].to_string(), Contains("frame number 5 follows frame 2 (expected 3)"));
        CHECK_THAT(amc_error(gap, true), Contains(at("bad.amc", line_of(good, "\n3\n") + 1)) && Contains("frame number 5"));
        CHECK_THAT(amc_error(replaced(good, "\n2\n", "\n1\n"), true), Contains("frame number 1 follows frame 1"));
        const std::string top = replaced(replaced(good, "\n1\n", "\n9223372036854775807\n"), "\n2\n", "\n0\n");
        CHECK_THAT(amc_error(top, true), Contains("expected 9223372036854775808"));
    }
    SECTION("truncated last frame: dropped with a warning, or an error in strict mode") {
        // Cut inside frame 3: once between lines, once inside a line.
        const std::string between = good.substr(0, good.find("root 0 0 0 0 0 0"));
        const std::string inside = good.substr(0, good.find("root 0 0 0 0 0 0") + 8);
        for (const std::string& cut : {between, inside}) {
            Warnings warnings;
            const Clip clip = parse_amc(cut, "cut.amc", tiny_skeleton(), {}, &warnings);
            CHECK(clip.frame_count() == 2);
            REQUIRE(warnings.size() == 1);
            CHECK_THAT(warnings[0].message, Contains("the file ends inside frame 3") && Contains("dropped"));
            CHECK_THAT(amc_error(cut, true), Contains("bad.amc:") && Contains("the file ends inside frame 3"));
        }
        CHECK_THAT(amc_error(between, true), Contains(at("bad.amc", line_of(good, "\n3\n") + 1)) &&
                                                 Contains("frame 3 has no line for bone 'root'"));
        CHECK_THAT(amc_error(inside, true), Contains(at("bad.amc", line_of(good, "root 0 0"))) &&
                                                Contains("expected 6 values for bone 'root', found 2"));
        // Only a frame number: nothing complete in the last frame.
        const std::string header_only = good.substr(0, good.find("lower 0 0 0"));
        Warnings warnings;
        CHECK(parse_amc(header_only, "cut.amc", tiny_skeleton(), {}, &warnings).frame_count() == 2);
        CHECK(warnings.size() == 1);
        // A single truncated frame leaves an empty motion, which is an error either way.
        CHECK_THAT(amc_error(good.substr(0, good.find("lower 15"))), Contains("no complete motion frames"));
    }
    SECTION("bone values before any frame number, unknown header keywords") {
        CHECK_THAT(amc_error("root 1 2 3 4 5 6\n"), Contains(at("bad.amc", 1)) && Contains("expected a frame number before the bone values"));
        Warnings warnings;
        parse_amc(replaced(good, ":DEGREES", ":DEGREES\n:SOMETHING"), "h.amc", tiny_skeleton(), {}, &warnings);
        REQUIRE(warnings.size() == 1);
        CHECK_THAT(warnings[0].message, Contains("unknown AMC header keyword ':SOMETHING'"));
    }
    SECTION("bad arguments") {
        CHECK_THROWS_AS(parse_amc(good, "x.amc", nullptr), InvalidArgument);
        AmcReadOptions options;
        options.frame_rate = 0.0;
        CHECK_THROWS_AS(parse_amc(good, "x.amc", tiny_skeleton(), options), InvalidArgument);
        CHECK_THROWS_AS(read_amc("/nonexistent/dir/01_01.amc", tiny_skeleton()), IoError);
        CHECK_THROWS_AS(read_asf("/nonexistent/dir/01.asf"), IoError);
    }
}

TEST_CASE("ASF/AMC: truncations and byte mutations give a result or a ParseError and nothing else", "[io][asf][amc][errors]") {
    const std::string asf = kTinyAsf, amc = kTinyAmc;
    const auto skeleton = tiny_skeleton();
    std::size_t parse_errors = 0, successes = 0;
    auto attempt = [&](auto&& f) {
        try {
            f();
            ++successes;
        } catch (const ParseError&) {
            ++parse_errors;
        } catch (const std::exception& e) {
            FAIL_CHECK("unexpected exception: " << e.what());
        }
    };
    for (std::size_t n = 0; n <= asf.size(); ++n) attempt([&] { parse_asf(asf.substr(0, n), "t.asf"); });
    for (std::size_t n = 0; n <= amc.size(); ++n) attempt([&] { parse_amc(amc.substr(0, n), "t.amc", skeleton); });

    std::mt19937 rng(12345);
    const std::string alphabet = std::string("0123456789 -+.eE()#:\n\r\tXYZxyzrtl_abc") + '\0' + '\xff';
    auto mutate = [&](std::string s) {
        std::uniform_int_distribution<int> count(1, 4);
        for (int k = count(rng); k > 0; --k) {
            const std::size_t pos = std::uniform_int_distribution<std::size_t>(0, s.size() - 1)(rng);
            const char c = alphabet[std::uniform_int_distribution<std::size_t>(0, alphabet.size() - 1)(rng)];
            switch (rng() % 3) {
                case 0: s[pos] = c; break;
                case 1: s.insert(pos, 1, c); break;
                default: s.erase(pos, 1); break;
            }
        }
        return s;
    };
    for (int i = 0; i < 3000; ++i) {
        attempt([&] { parse_asf(mutate(asf), "m.asf"); });
        attempt([&] { parse_amc(mutate(amc), "m.amc", skeleton); });
    }
    INFO("successes " << successes << ", parse errors " << parse_errors);
    CHECK(parse_errors > 0);
    CHECK(successes > 0);
}

TEST_CASE("ASF/AMC: the fuzz seed corpus parses", "[io][asf][amc]") {
    const auto corpus = test::test_data_dir().parent_path() / "fuzz" / "corpus";
    REQUIRE(std::filesystem::exists(corpus / "asf"));
    std::size_t seeds = 0;
    for (const auto& entry : std::filesystem::directory_iterator(corpus / "asf")) {
        INFO(entry.path().string());
        CHECK_NOTHROW(read_asf(entry.path()));
        ++seeds;
    }
    CHECK(seeds >= 3);
    const auto tiny = read_asf(corpus / "asf" / "tiny.asf");
    CHECK(tiny->same_structure(*tiny_skeleton(), 0.0));
    for (const auto& entry : std::filesystem::directory_iterator(corpus / "amc")) {
        INFO(entry.path().string());
        Warnings warnings;
        const Clip clip = read_amc(entry.path(), tiny, {}, &warnings);
        if (entry.path().filename().string().find("truncated") == std::string::npos) {
            CHECK(clip.frame_count() == 2);
            CHECK(warnings.empty());
        } else {
            CHECK(clip.frame_count() == 1);  // the second frame is cut short and dropped
            CHECK(warnings.size() == 3);     // :RADIANS vs deg, frame 3 after 1, cut inside frame 3
        }
    }
}
