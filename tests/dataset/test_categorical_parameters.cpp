// Categorical parameters of a motion set (dataset/motion_set.hpp, parameter_request.hpp): levels from
// clip ids by a regex's first group, sorted level names with index columns, refusals (one level, a level
// with one sample, a clip the regex misses), and requests by name or position with an unknown level
// refused listing the known ones.
#include <catch2/catch.hpp>

#include "mocapdb/core/error.hpp"
#include "mocapdb/dataset/motion_set.hpp"
#include "mocapdb/dataset/motion_set.hpp"

using namespace mocapdb;
using Catch::Matchers::Contains;

namespace {

MotionSet styled_set() {
    MotionSet set;
    set.name = "styles";
    for (const char* clip : {"m_happy_01", "m_sad_01", "m_happy_02", "m_sad_02", "m_angry_01", "m_angry_02"})
        set.samples.push_back({clip, 0, 10});
    set.parameter_names = {"turn"};
    set.parameter_units = {"rad"};
    set.parameters.resize(6, 1);
    set.parameters << 0.1, 0.2, 0.3, 0.4, 0.5, 0.6;
    return set;
}

}  // namespace

TEST_CASE("dataset: a categorical parameter from clip names", "[dataset]") {
    MotionSet set = styled_set();
    const auto levels = levels_from_clip_names(set, "_([a-z]+)_[0-9]+$");
    CHECK(levels == std::vector<std::string>{"happy", "sad", "happy", "sad", "angry", "angry"});
    add_categorical_parameter(set, "style", levels);
    validate(set);
    REQUIRE(set.parameter_names == std::vector<std::string>{"turn", "style"});
    REQUIRE(set.parameter_levels.size() == 2);
    CHECK(set.parameter_levels[0].empty());
    CHECK(set.parameter_levels[1] == std::vector<std::string>{"angry", "happy", "sad"});  // sorted
    const VecX expected = (VecX(6) << 1, 2, 1, 2, 0, 0).finished();                       // level indices
    CHECK(set.parameters.col(1) == expected);
    CHECK(set.parameters.col(0)(3) == 0.4);  // the numeric column is kept
    CHECK(parameter_level_counts(set) == std::vector<int>{0, 3});
    CHECK(describe_parameters(set) == "turn [rad], style {angry|happy|sad}");

    // Requests: named in any order, or positional; levels by name.
    const VecX named = parameter_request(set, {"style=sad", " turn = 0.25"});
    CHECK(named(0) == 0.25);
    CHECK(named(1) == 2.0);
    CHECK(parameter_request(set, {"0.25", "sad"}) == named);
    CHECK(parameter_value_text(set, 1, 2.0) == "sad");
    CHECK_THROWS_WITH(parameter_request(set, {"style=calm", "turn=0"}),
                      Contains("no level 'calm'") && Contains("angry, happy, sad"));
    CHECK_THROWS_WITH(parameter_request(set, {"0", "2"}), Contains("no level '2'"));
    CHECK_THROWS_WITH(parameter_request(set, {"style=sad"}), Contains("no value for parameter 'turn'"));
    CHECK_THROWS_WITH(parameter_request(set, {"style=sad", "speed=1"}), Contains("no parameter 'speed'"));
    CHECK_THROWS_WITH(parameter_request(set, {"style=sad", "turn=x"}), Contains("not a finite number"));
    CHECK_THROWS_WITH(parameter_request(set, {"style=sad", "0.1"}), Contains("has no name"));
    CHECK_THROWS_WITH(parameter_request(set, {"0.1"}), Contains("expected 2 values"));

    // A stored level index out of range is refused by validate.
    set.parameters(0, 1) = 3.0;
    CHECK_THROWS_AS(validate(set), InvalidArgument);
}

TEST_CASE("dataset: categorical parameters refuse what cannot serve", "[dataset]") {
    MotionSet set = styled_set();
    CHECK_THROWS_WITH(levels_from_clip_names(set, "_[a-z]+_"), Contains("has no group"));
    CHECK_THROWS_WITH(levels_from_clip_names(set, "_(happy|sad)_"), Contains("does not match clip 'm_angry_01'"));
    CHECK_THROWS_WITH(levels_from_clip_names(set, "(["), Contains("not a valid regular expression"));
    CHECK_THROWS_WITH(add_categorical_parameter(set, "style", std::vector<std::string>(6, "happy")),
                      Contains("it needs at least 2"));
    CHECK_THROWS_WITH(add_categorical_parameter(set, "style", {"a", "a", "b", "b", "b", "c"}),
                      Contains("level 'c'") && Contains("1 sample"));
    CHECK_THROWS_WITH(add_categorical_parameter(set, "turn", {"a", "a", "b", "b", "b", "b"}),
                      Contains("exists already"));
    CHECK(set.parameters.cols() == 1);  // nothing was added by the refusals
}
