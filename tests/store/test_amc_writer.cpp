// ASF / AMC writing: skeletons the ASF mapping can express round-trip; others are refused with the
// reason; values are written in the source units.
#include <catch2/catch.hpp>

#include <sstream>

#include "mocapdb/core/error.hpp"
#include "mocapdb/io/amc_writer.hpp"
#include "mocapdb/io/asf_amc.hpp"
#include "store_test_support.hpp"

using namespace mocapdb;

namespace {

const char* kAsf = R"(:version 1.10
:name tiny
:units
  mass 1.0
  length 0.5
  angle rad
:root
  order TX TY TZ RZ RY RX
  axis XYZ
  position 1 2 3
  orientation 0 0.1 0
:bonedata
  begin
    id 1
    name hip
    direction 0 -1 0
    length 4
    axis 0 0 0.3 XYZ
  end
  begin
    id 2
    name femur
    direction 0.6 -0.8 0
    length 10
    axis 0.2 0 0.5 XYZ
    dof rx rz
  end
  begin
    id 3
    name spine
    direction 0 1 0
    length 6
    axis 0 0 0 XYZ
    dof ty rx ry rz
  end
  begin
    id 4
    name arm
    direction 1 0 0
    length 3
    axis 0 0.25 0 XYZ
    dof rz
  end
:hierarchy
  begin
    root hip spine
    hip femur
    spine arm
  end
)";

}  // namespace

TEST_CASE("amc writer: ASF skeletons and AMC motion round-trip", "[store][amc]") {
    const auto skeleton = std::make_shared<const Skeleton>(parse_asf(kAsf, "tiny.asf"));
    CHECK(asf_incompatibility(*skeleton).empty());
    std::ostringstream asf;
    write_asf(asf, *skeleton);
    INFO(asf.str());
    const Skeleton back = parse_asf(asf.str(), "written.asf");
    CHECK(back.same_structure(*skeleton, 1e-9));
    CHECK(back.source_units().cm_per_unit == Approx(skeleton->source_units().cm_per_unit).epsilon(1e-14));
    CHECK(back.source_units().degrees == false);

    const std::string amc = ":FULLY-SPECIFIED\n:RADIANS\n1\nroot 1 2 3 0.1 0.2 0.3\nfemur 0.5 -0.25\n"
                            "spine 0.125 0.01 0.02 0.03\narm 1.5\n2\nroot 1.5 2 3 0.1 0.2 0.3\nfemur 0.5 -0.5\n"
                            "spine 0.25 0.01 0.02 0.03\narm -1.25\n";
    const Clip clip = parse_amc(amc, "tiny_01.amc", skeleton);
    std::ostringstream out;
    AmcWriteOptions o;
    o.asf_name = "tiny.asf";
    write_amc(out, clip, o);
    INFO(out.str());
    CHECK(out.str().rfind("#!OML:ASF tiny.asf\n:FULLY-SPECIFIED\n:RADIANS\n1\nroot 1 2 3 0.1 0.2 0.3\n", 0) == 0);
    CHECK(out.str().find("spine 0.125 0.01 0.02 0.03\n") != std::string::npos);
    const Clip again = parse_amc(out.str(), "again.amc", std::make_shared<const Skeleton>(back));
    CHECK((again.channels - clip.channels).cwiseAbs().maxCoeff() < 1e-12);
}

TEST_CASE("amc writer: skeletons the ASF mapping cannot express are refused with the reason", "[store][amc]") {
    const Clip bvh_like = test::synthetic_clip(3, 2, 1);  // BVH rig: root named "root" but ZXY channels
    const std::string why = asf_incompatibility(*bvh_like.skeleton);
    CHECK(why.find("rotation order ZXY is not the ASF composition of its channels") != std::string::npos);
    std::ostringstream out;
    CHECK_THROWS_WITH(write_amc(out, bvh_like), Catch::Contains("export it as BVH instead"));
    CHECK_THROWS_AS(write_asf(out, *bvh_like.skeleton), InvalidArgument);
    AmcWriteOptions bad;
    bad.precision = 0;
    const auto skeleton = std::make_shared<const Skeleton>(parse_asf(kAsf, "tiny.asf"));
    Clip clip;
    clip.skeleton = skeleton;
    clip.channels = FrameMatrix::Zero(1, static_cast<Eigen::Index>(skeleton->channel_count()));
    CHECK_THROWS_WITH(write_amc(out, clip, bad), Catch::Contains("precision must be 1..17"));
}
