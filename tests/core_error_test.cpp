// penumbra::Error: main() prints its message as the one line of an error, so the message is
// one line whatever the file name or key it quotes holds (a JSON key "a\n" is legal).
#include <gtest/gtest.h>

#include "core/error.h"
#include "core/files.h"

namespace penumbra {
namespace {

TEST(Error, MessageIsOneLineWhateverItQuotes) {
  const Error e("scene\n.json", "duplicate key 'descripti\n' (tab\there, bell\a, del\x7f, \r)");
  EXPECT_STREQ(e.what(), "scene\\n.json: duplicate key 'descripti\\n' (tab\\there, bell\\x07, del\\x7f, \\r)");
  EXPECT_EQ(e.where(), "scene\n.json");  // the raw value stays available to the code
  EXPECT_STREQ(Error("", "plain words, UTF-8 \xc3\xa9").what(), "plain words, UTF-8 \xc3\xa9");
}

// A scene's or a light's name in an output path is one harmless component: it never climbs out
// of the folder, names an absolute path, hides a file or carries a separator.
TEST(FileNames, ANameFromAFileIsOneHarmlessComponent) {
  EXPECT_EQ(fileNameComponent("engine", "scene"), "engine");
  EXPECT_EQ(fileNameComponent("../../x", "scene"), "_._.._x");
  EXPECT_EQ(fileNameComponent("/abs/path", "scene"), "_abs_path");
  EXPECT_EQ(fileNameComponent("..", "scene"), "_.");
  EXPECT_EQ(fileNameComponent(".hidden", "scene"), "_hidden");
  EXPECT_EQ(fileNameComponent("a\\b c\n", "scene"), "a_b_c_");
  EXPECT_EQ(fileNameComponent("", "scene"), "scene");
  EXPECT_EQ(fileNameComponent(std::string(5000, 'a'), "scene").size(), 100u);
  for (const std::string& bad : {"../../x", "/abs", "..", "a/b", "\\x", "caf\xc3\xa9"}) {
    const std::string c = fileNameComponent(bad, "scene");
    EXPECT_EQ(c.find('/'), std::string::npos) << c;
    EXPECT_NE(c, "..");
    EXPECT_NE(c.front(), '.');
  }
}

}  // namespace
}  // namespace penumbra
