// Pictures of a paper: the crease pattern and the folded form side by side, titled.
#include <gtest/gtest.h>

#include <regex>

#include "virtual_origami/core/svg.h"

using namespace virtual_origami::core;

namespace
{
long count(const std::string& text, const std::string& pattern)
{
  const std::regex re(pattern);
  return std::distance(std::sregex_iterator(text.begin(), text.end(), re), std::sregex_iterator());
}
}  // namespace

TEST(PaperSvg, DrawsEveryEdgeAndEveryFace)
{
  const std::string svg = paperSvg(Paper::square(1.0));
  EXPECT_EQ(count(svg, "<line "), 4) << svg;     // the four sides in the crease pattern
  EXPECT_EQ(count(svg, "<polygon "), 1) << svg;  // the one face, folded
  EXPECT_EQ(svg.rfind("</svg>"), svg.size() - std::string("</svg>\n").size());
}

TEST(PaperSvg, ATitleGetsItsOwnLineAndIsEscaped)
{
  const std::string plain = paperSvg(Paper::square(1.0));
  const std::string titled = paperSvg(Paper::square(1.0), "004 fold <front> & back");
  EXPECT_NE(titled.find(">004 fold &lt;front&gt; &amp; back</text>"), std::string::npos) << titled;
  EXPECT_EQ(titled.find("<front>"), std::string::npos);
  // One line more of height for the title.
  const std::regex height(R"(height="([0-9.]+)\")");
  std::smatch a, b;
  ASSERT_TRUE(std::regex_search(plain, a, height));
  ASSERT_TRUE(std::regex_search(titled, b, height));
  EXPECT_GT(std::stod(b[1]), std::stod(a[1]));
}
