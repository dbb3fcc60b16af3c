// The gnuplot driver: paths never pass through a shell or a script (a folder
// and a file name full of spaces, quotes and shell syntax work), the PNG
// appears whole or not at all, and nothing is left beside it.
#include "plot/gnuplot_driver.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "tests/plot/plot_test_support.h"

namespace birotor {
namespace {

// A 320 x 200 plot of a two-point datablock.
const std::string kScript =
    "set terminal pngcairo size 320,200 noenhanced\n"
    "$d << EOD\n0 0\n1 1\nEOD\n"
    "plot $d u 1:2 w l title " +
    GnuplotQuoted("it's \"quoted\"; $(touch injected)") + "\n";

TEST(GnuplotDriverTest, QuotesForGnuplot) {
  EXPECT_EQ(GnuplotQuoted("plain"), "'plain'");
  EXPECT_EQ(GnuplotQuoted("it's"), "'it''s'");
  EXPECT_EQ(GnuplotQuoted("two\nlines\tand\rtab"), "'two lines and tab'");
  EXPECT_EQ(GnuplotQuoted("\"$HOME\" `ls`"), "'\"$HOME\" `ls`'");  // no expansion inside '...'
}

TEST(GnuplotDriverTest, PathWithSpacesAndQuotesAndNothingBeside) {
  TemporaryFolder root("birotor_gnuplot_test_");
  ASSERT_FALSE(root.path().empty());
  const std::string folder = root.path() + "/a folder with 'single' \"double\" $(x) ; quotes";
  ASSERT_TRUE(std::filesystem::create_directory(folder));
  const std::string png = folder + "/it's a \"plot\" `x` $HOME.png";
  std::string error;
  ASSERT_TRUE(RenderGnuplotPng(kScript, png, &error)) << error;
  const PngSize size = ReadPngSize(png);
  EXPECT_EQ(size.width, 320u);  // the terminal size of kScript
  EXPECT_EQ(size.height, 200u);
  // Only the PNG: no .dat, .gp or temporary file, and no file made by the title's $(...).
  EXPECT_EQ(FolderEntries(folder), std::vector<std::string>{"it's a \"plot\" `x` $HOME.png"});
  EXPECT_FALSE(std::filesystem::exists(root.path() + "/injected"));
  EXPECT_FALSE(std::filesystem::exists("injected"));
}

TEST(GnuplotDriverTest, FailureLeavesTheTargetAsItWasAndNoTemporaryFile) {
  TemporaryFolder root("birotor_gnuplot_test_");
  const std::string png = root.path() + "/plot.png";
  {
    std::ofstream old(png);
    old << "previous content";
  }
  std::string error;
  EXPECT_FALSE(RenderGnuplotPng("set terminal pngcairo\nplot $missing u 1:2\n", png, &error));
  EXPECT_NE(error.find("gnuplot failed (exit status 1)"), std::string::npos) << error;
  EXPECT_NE(error.find("no datablock named $missing"), std::string::npos) << error;  // gnuplot's own words
  EXPECT_EQ(error.find('\n'), std::string::npos) << error;                           // one line
  EXPECT_EQ(ReadFile(png), "previous content");
  EXPECT_EQ(root.Entries(), std::vector<std::string>{"plot.png"});

  // A script that draws nothing (no terminal output): refused, nothing written.
  EXPECT_FALSE(RenderGnuplotPng("print 1\n", root.path() + "/empty.png", &error));
  EXPECT_NE(error.find("wrote no PNG"), std::string::npos) << error;
  EXPECT_EQ(root.Entries(), std::vector<std::string>{"plot.png"});

  // An unwritable folder: one line naming the path.
  EXPECT_FALSE(RenderGnuplotPng(kScript, root.path() + "/no such folder/plot.png", &error));
  EXPECT_NE(error.find("cannot write " + root.path() + "/no such folder/plot.png"), std::string::npos) << error;
}

TEST(GnuplotDriverTest, ReplacesAnExistingPlot) {
  TemporaryFolder root("birotor_gnuplot_test_");
  const std::string png = root.path() + "/plot.png";
  {
    std::ofstream old(png);
    old << "old";
  }
  std::string error;
  ASSERT_TRUE(RenderGnuplotPng(kScript, png, &error)) << error;
  EXPECT_EQ(ReadPngSize(png).width, 320u);
  EXPECT_EQ(root.Entries(), std::vector<std::string>{"plot.png"});
}

}  // namespace
}  // namespace birotor
