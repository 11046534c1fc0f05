// penumbra::Error: main() prints its message as the one line of an error, so the message is
// one line whatever the file name or key it quotes holds (a JSON key "a\n" is legal).
#include <gtest/gtest.h>

#include "core/error.h"

namespace penumbra {
namespace {

TEST(Error, MessageIsOneLineWhateverItQuotes) {
  const Error e("scene\n.json", "duplicate key 'descripti\n' (tab\there, bell\a, del\x7f, \r)");
  EXPECT_STREQ(e.what(), "scene\\n.json: duplicate key 'descripti\\n' (tab\\there, bell\\x07, del\\x7f, \\r)");
  EXPECT_EQ(e.where(), "scene\n.json");  // the raw value stays available to the code
  EXPECT_STREQ(Error("", "plain words, UTF-8 \xc3\xa9").what(), "plain words, UTF-8 \xc3\xa9");
}

}  // namespace
}  // namespace penumbra
