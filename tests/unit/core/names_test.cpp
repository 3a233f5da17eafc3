#include <string>
#include <string_view>
#include <utility>

#include <gtest/gtest.h>

#include <pc/core/error.h>
#include <pc/core/names.h>

namespace pc {
namespace {

enum class Colour { kRed, kGreen, kBlue, kUnnamed };
constexpr std::pair<std::string_view, Colour> kColours[] = {
    {"red", Colour::kRed}, {"green", Colour::kGreen}, {"blue", Colour::kBlue}};

TEST(Names, EveryWordReadsBackAsItsValue) {
    for (const auto& [word, value] : kColours) {
        EXPECT_EQ(parse_name<Colour>(kColours, word, "--colour"), value);
        EXPECT_EQ(name_of<Colour>(kColours, value), word);
    }
    EXPECT_EQ(name_of<Colour>(kColours, Colour::kUnnamed), "?");
}

TEST(Names, AnUnknownWordListsTheKnownOnes) {
    try {
        (void)parse_name<Colour>(kColours, "Red", "--colour");
        FAIL() << "no exception";
    } catch (const InvalidArgument& e) {
        EXPECT_EQ(std::string(e.what()), "--colour must be red, green or blue, got 'Red'");
    }
}

}  // namespace
}  // namespace pc
