// The helpers behind the deck messages: edit distance for "did you mean", and the exact real
// formatting that makes the resolved deck read back bit for bit.
#include "input/YamlReader.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <random>

namespace
{
using namespace scpdyn::input_impl;
using scpdyn::formatReal;

TEST(YamlReader, EditDistance)
{
  EXPECT_EQ(editDistance("courant", "courant"), 0);
  EXPECT_EQ(editDistance("corant", "courant"), 1);   // deletion
  EXPECT_EQ(editDistance("courtnat", "courant"), 2); // extra letter + transposition
  EXPECT_EQ(editDistance("cuorant", "courant"), 1);  // adjacent transposition counts once
  EXPECT_EQ(editDistance("", "end"), 3);
  EXPECT_EQ(editDistance("node_set", "face_set"), 3);
}

TEST(YamlReader, SuggestionWithinTwoEdits)
{
  EXPECT_EQ(suggestion("materails", {"materials", "parts"}), "; did you mean 'materials'?");
  EXPECT_EQ(suggestion("gravty", {"gravity", "geometry"}), "; did you mean 'gravity'?");
  EXPECT_EQ(suggestion("solver", {"time", "parts"}), " (expected one of: time, parts)");
}

TEST(YamlReader, FormatRealIsExactAndShort)
{
  EXPECT_EQ(formatReal(0.05), "0.05");
  EXPECT_EQ(formatReal(2.0e11), "2e+11");
  EXPECT_EQ(formatReal(7850), "7850");
  EXPECT_EQ(formatReal(123456.7), "123456.7");
  EXPECT_EQ(formatReal(0.00025), "0.00025");
  EXPECT_EQ(formatReal(-1e-6), "-1e-06");
  EXPECT_EQ(formatReal(1e30), "1e+30");
  EXPECT_EQ(formatReal(0.1 + 0.2), "0.30000000000000004");
  // random doubles over many decades must read back exactly (no tolerance: bitwise round trip)
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> mant(-1, 1), expo(-300, 300), everyday(-6, 8);
  for (int i = 0; i < 4000; ++i)
  {
    // half over all decades, half where the plain-decimal branch is taken
    const double x = mant(rng) * std::pow(10.0, i % 2 ? expo(rng) : everyday(rng));
    EXPECT_EQ(std::strtod(formatReal(x).c_str(), nullptr), x);
  }
}

} // namespace
