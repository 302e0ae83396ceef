#include "common/base/nearest_word.h"

#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace glint {
namespace {

TEST(EditDistance, CountsInsertionsDeletionsAndSubstitutions) {
  EXPECT_EQ(editDistance("", ""), 0u);
  EXPECT_EQ(editDistance("samples", "samples"), 0u);
  EXPECT_EQ(editDistance("", "abc"), 3u);
  EXPECT_EQ(editDistance("abc", ""), 3u);
  EXPECT_EQ(editDistance("rendr", "render"), 1u);     // one insertion
  EXPECT_EQ(editDistance("sampels", "samples"), 2u);  // a swap is two substitutions
  EXPECT_EQ(editDistance("kitten", "sitting"), 3u);   // the textbook pair
  EXPECT_EQ(editDistance("view", "info"), editDistance("info", "view"));
}

TEST(NearestWord, NamesALikelyMisspelling) {
  const std::vector<std::string> commands{"render", "view", "accuracy", "info", "compare"};
  EXPECT_EQ(nearestWord("rendr", commands), "render");
  EXPECT_EQ(nearestWord("veiw", commands), "view");
  EXPECT_EQ(nearestWord("compaer", commands), "compare");
  EXPECT_EQ(nearestWord("render", commands), "render");
}

TEST(NearestWord, NamesNothingFarOrShortWordsCannotBeMisspelledAs) {
  const std::vector<std::string> commands{"render", "view", "accuracy", "info", "compare"};
  EXPECT_EQ(nearestWord("paint", commands), "");
  EXPECT_EQ(nearestWord("xyz", commands), "");
  EXPECT_EQ(nearestWord("", commands), "");
  // Two edits turn "ab" into any two-letter word: no suggestion for it.
  const std::vector<std::string> short_{"-o", "-q"};
  EXPECT_EQ(nearestWord("zz", short_), "");
  EXPECT_EQ(nearestWord("-x", short_), "-o");
}

// The first argument that looks like an option and is not one, named with
// the nearest there is; values (even negative numbers) are not options.
TEST(UnknownOption, NamesTheFirstAndItsNearest) {
  const std::vector<std::string> known{"--samples", "--size", "-o", "--eye"};
  const std::vector<std::string> fine{"scene.json", "-o", "x.png", "--samples=4", "--eye", "-1,2,3"};
  EXPECT_EQ(unknownOption("glint render", fine, known), "");
  const std::vector<std::string> typo{"scene.json", "--sampels=4", "--bogus"};
  EXPECT_EQ(unknownOption("glint render", typo, known), "glint render has no option --sampels; did you mean --samples?");
  const std::vector<std::string> far{"--threads", "2"};
  EXPECT_EQ(unknownOption("glint info", far, known), "glint info has no option --threads");
}

}  // namespace
}  // namespace glint
