// Every deck in inputs/broken/ must be rejected with an InputError that names the deck, the key
// path and the line. The expected text is the first line of each deck ("# expect: <text>"), so
// adding a broken deck needs no code change here. A deck that parses must be rejected when the
// model is set up (errors only the mesh can show, such as a surface with no external face).
#include "driver/Solver.hpp"
#include "input/Deck.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace
{
namespace fs = std::filesystem;

const std::string kBrokenDir = std::string(SCPDYN_SOURCE_DIR) + "/inputs/broken";

std::vector<std::string> brokenDecks()
{
  std::vector<std::string> files;
  if (fs::is_directory(kBrokenDir))
    for (const auto &entry : fs::directory_iterator(kBrokenDir))
      if (entry.path().extension() == ".yaml")
        files.push_back(entry.path().string());
  std::sort(files.begin(), files.end());
  return files;
}

std::string expectation(const std::string &file)
{
  std::ifstream in(file);
  std::string first;
  std::getline(in, first);
  const std::string tag = "# expect: ";
  return first.rfind(tag, 0) == 0 ? first.substr(tag.size()) : std::string();
}

class BrokenDeck : public ::testing::TestWithParam<std::string>
{
};

TEST_P(BrokenDeck, IsRejectedWithKeyPathAndLine)
{
  const std::string file = GetParam();
  const std::string expected = expectation(file);
  ASSERT_FALSE(expected.empty()) << file << ": first line must be '# expect: <key path> (line N)'";
  try
  {
    const scpdyn::Deck deck = scpdyn::parseDeck(file);
    scpdyn::Solver solver(deck);
    FAIL() << file << " was accepted; expected an error containing: " << expected;
  }
  catch (const scpdyn::InputError &e)
  {
    const std::string msg = e.what();
    EXPECT_EQ(msg.rfind(file + ": ", 0), 0u) << "message must start with the deck path: " << msg;
    EXPECT_NE(msg.find(expected), std::string::npos)
        << "message: " << msg << "\nexpected to contain: " << expected;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << "message must be one line: " << msg;
  }
}

// The brief asks for at least 15 broken decks covering the error classes of docs/input.md.
TEST(BrokenDecks, AtLeastFifteen) { EXPECT_GE(brokenDecks().size(), 15u); }

std::string testName(const ::testing::TestParamInfo<std::string> &info)
{
  std::string name = fs::path(info.param).stem().string();
  for (char &c : name)
    if (!std::isalnum(static_cast<unsigned char>(c)))
      c = '_';
  return name;
}

INSTANTIATE_TEST_SUITE_P(InputsBroken, BrokenDeck, ::testing::ValuesIn(brokenDecks()), testName);
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(BrokenDeck);

} // namespace
