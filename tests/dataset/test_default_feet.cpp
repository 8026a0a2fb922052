// Foot joints found by name on the naming schemes of common rigs (issue #16: Foot_L/Toes_R were missed).
#include <catch2/catch.hpp>

#include "mocapdb/core/error.hpp"
#include "mocapdb/core/remedy.hpp"
#include "mocapdb/dataset/foot_contacts.hpp"

using namespace mocapdb;
using Catch::Matchers::Contains;

namespace {

// Hips with two legs of three joints each, named by `names` (left leg first), plus a spine.
Skeleton legs(const std::vector<std::string>& names) {
    std::vector<Joint> joints(1);
    joints[0].name = "Hips";
    joints[0].channels = {ChannelType::Xposition, ChannelType::Yposition, ChannelType::Zposition};
    for (std::size_t k = 0; k < names.size(); ++k) {
        Joint j;
        j.name = names[k];
        j.parent = k % 3 == 0 ? 0 : static_cast<int>(joints.size()) - 1;
        j.offset = Vec3(0, -10, 0);
        j.channels = {ChannelType::Zrotation, ChannelType::Xrotation, ChannelType::Yrotation};
        joints.push_back(j);
    }
    Joint spine;
    spine.name = "Spine";
    spine.parent = 0;
    joints.push_back(spine);
    return Skeleton(joints);
}

}  // namespace

TEST_CASE("default feet: side words before or after, camelCase, prefixes, CMU names", "[dataset][feet]") {
    CHECK(default_feet(legs({"UpLeg_L", "Foot_L", "Toes_L", "UpLeg_R", "Foot_R", "Toes_R"})) ==
          std::vector<std::string>{"Toes_L", "Toes_R"});
    CHECK(default_feet(legs({"thigh.l", "shin.l", "foot.l", "thigh.r", "shin.r", "foot.r"})) ==
          std::vector<std::string>{"foot.l", "foot.r"});
    CHECK(default_feet(legs({"mixamorig:LeftUpLeg", "mixamorig:LeftFoot", "mixamorig:LeftToeBase", "mixamorig:RightUpLeg",
                             "mixamorig:RightFoot", "mixamorig:RightToeBase"})) ==
          std::vector<std::string>{"mixamorig:LeftToeBase", "mixamorig:RightToeBase"});
    CHECK(default_feet(legs({"lfemur", "lfoot", "ltoes", "rfemur", "rfoot", "rtoes"})) ==
          std::vector<std::string>{"ltoes", "rtoes"});
    CHECK(default_feet(legs({"L_Hip", "L_Knee", "L_Foot", "R_Hip", "R_Knee", "R_Foot"})) ==
          std::vector<std::string>{"L_Foot", "R_Foot"});
}

TEST_CASE("default feet: none found says to name them, with the remedy for the front end", "[dataset][feet]") {
    const Skeleton s = legs({"a1", "a2", "a3", "b1", "b2", "b3"});
    CHECK_THROWS_WITH(default_feet(s), Contains("name them explicitly") && !Contains("--feet"));
    try {
        (void)default_feet(s);
        FAIL("feet found in a skeleton without foot names");
    } catch (const Remediable& e) {
        CHECK(e.remedy() == Remedy::Feet);  // the CLI adds --feet LEFT,RIGHT
    }
}
