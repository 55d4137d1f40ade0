#include "dlslam/io/text_table.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>

#include "dlslam/util/check.h"
#include "tests/support/test_data.h"

namespace dlslam::io {
namespace {

using ::testing::HasSubstr;

TEST(TextTable, SkipsCommentsAndBlankLinesAndKeepsLineNumbers) {
  const auto dir = testing::MakeTempDir("text_table");
  const auto path = dir / "rgb.txt";
  std::ofstream(path) << "# color images\n\n1.0 rgb/1.png\r\n  # indented comment\n2.0,rgb/2.png\t x\n";
  const TextTable t = ReadTextTable(path);
  ASSERT_EQ(t.rows.size(), 2u);
  EXPECT_EQ(t.rows[0].line, 3);
  EXPECT_EQ(t.rows[0].fields, (std::vector<std::string>{"1.0", "rgb/1.png"}));
  EXPECT_EQ(t.rows[1].line, 5);
  EXPECT_EQ(t.rows[1].fields, (std::vector<std::string>{"2.0", "rgb/2.png", "x"}));
  EXPECT_EQ(t.comments.size(), 2u);
  std::filesystem::remove_all(dir);
}

TEST(TextTable, MissingFileNamesTheFile) {
  try {
    ReadTextTable("/nonexistent/groundtruth.txt");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("/nonexistent/groundtruth.txt"));
    EXPECT_THAT(e.what(), HasSubstr("not found"));
  }
}

TEST(TextTable, ParseDouble) {
  EXPECT_DOUBLE_EQ(ParseDouble("1341846313.592026", "f", 1, "t"), 1341846313.592026);
  EXPECT_DOUBLE_EQ(ParseDouble("-1e-3", "f", 1, "t"), -1e-3);
  try {
    ParseDouble("1.0abc", "gt.txt", 7, "timestamp");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "gt.txt:7: timestamp '1.0abc' is not a finite number");
  }
  EXPECT_THROW(ParseDouble("nan", "f", 1, "x"), InputError);
  EXPECT_THROW(ParseDouble("inf", "f", 1, "x"), InputError);
  EXPECT_THROW(ParseDouble("", "f", 1, "x"), InputError);
  EXPECT_THROW(ParseDouble("1e999", "f", 1, "x"), InputError);
}

}  // namespace
}  // namespace dlslam::io

namespace dlslam::io {
namespace {

// A device or FIFO named as a list or trajectory is refused at once instead
// of being read without end.
TEST(TextTable, DevicesAreNotFiles) {
  try {
    ReadTextTable("/dev/zero");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("not a regular file"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace dlslam::io
