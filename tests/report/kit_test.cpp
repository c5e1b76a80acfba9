// The report kit: escaping by the rules of each format (CommonMark, XML), tables whose two
// renderings hold the same cells, a document whose Markdown and HTML carry the same text, and
// axes whose ticks are exact multiples of a nice step.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "report/document.hpp"
#include "report/escape.hpp"
#include "report/format.hpp"
#include "report/html.hpp"
#include "report/svg.hpp"
#include "report/table.hpp"
#include "xml.hpp"

namespace masonry {
namespace {

size_t count(const std::string& s, const std::string& what) {
  size_t n = 0;
  for (size_t at = s.find(what); at != std::string::npos; at = s.find(what, at + 1)) ++n;
  return n;
}

TEST(ReportEscape, MarkupFromACaseIsText) {
  // XML: the five predefined entities (XML 1.0, section 4.6).
  EXPECT_EQ(xml_escape("<b a=\"1\">'&'</b>"), "&lt;b a=&quot;1&quot;&gt;&#39;&amp;&#39;&lt;/b&gt;");
  // Markdown: no raw HTML, no emphasis, code, link or table cell break; one line. A '<' that
  // would open a tag and a '&' that would start an entity get a backslash (CommonMark: any ASCII
  // punctuation may be escaped so), never an entity, since report.md is read as text too.
  EXPECT_EQ(md_escape("<i>a|b</i>"), "\\<i>a\\|b\\</i>");
  EXPECT_EQ(md_escape("<!-- x --> <?p <http://a>"), "\\<!-- x --> \\<?p \\<http://a>");
  EXPECT_EQ(md_escape("&gt; &#39; &amp;"), "\\&gt; \\&#39; \\&amp;");
  // What cannot act stays as written: arrows, comparisons, a plain ampersand.
  EXPECT_EQ(md_escape("a -> b, 3 < 4 > 2, Romano & Ochsendorf, R&D;"), "a -> b, 3 < 4 > 2, Romano & Ochsendorf, R\\&D;");
  EXPECT_EQ(md_escape("> not a quotation"), "\\> not a quotation");
  EXPECT_EQ(md_escape("*x* _y_ `z` [l](u)"), "\\*x\\* \\_y\\_ \\`z\\` \\[l\\](u)");
  EXPECT_EQ(md_escape("a\nb"), "a b");
  EXPECT_EQ(md_escape("# not a heading, #2 stays"), "\\# not a heading, #2 stays");
  // A code span cannot hold a backtick, and a table cell no bar.
  EXPECT_EQ(md_code("a`b|c"), "a'b/c");
}

// XML 1.0 allows no control character but tab and line breaks, no byte that is not UTF-8 and not
// U+FFFE or U+FFFF, even as a character reference: an id with an ESC byte made the figures
// ill-formed. Whatever the text, element and attribute content stays well-formed (expat).
TEST(ReportEscape, XmlStaysWellFormedWhateverTheText) {
  const std::vector<std::string> texts = {
      "v\x1b[31m3",
      std::string("nul\0byte", 8),
      "bell\a, bs\b, vt\v, ff\f",
      "tab\tnl\ncr\r",
      "\xff\xfe latin-1 \xe9t\xe9",
      "cut \xc3",
      "overlong \xc0\xaf",
      "surrogate \xed\xa0\x80",
      "U+FFFF \xef\xbf\xbf and U+FFFE \xef\xbf\xbe",
      "caf\xc3\xa9 \xe2\x82\xac \xf0\x9f\xa7\xb1",
      "<&\"'>",
  };
  for (const std::string& t : texts) {
    const std::string doc = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg a=\"" + xml_escape(t) + "\"><title>" + xml_escape(t) + "</title></svg>";
    std::string why;
    EXPECT_TRUE(test::xml_well_formed(doc, why)) << why << ": " << doc;
  }
  // What is kept stays as it was: valid UTF-8 and the white space XML allows.
  EXPECT_EQ(xml_escape("caf\xc3\xa9 \xf0\x9f\xa7\xb1\t"), "caf\xc3\xa9 \xf0\x9f\xa7\xb1\t");
  EXPECT_EQ(xml_escape("a\x1b"), "a\\x1b");
  EXPECT_EQ(xml_escape("\xff"), "\xef\xbf\xbd");
}

TEST(ReportFormat, NoNanAndNoExponent) {
  EXPECT_EQ(fmt::g(NAN), "n/a");
  EXPECT_EQ(fmt::mm(0.2784), "278");
  EXPECT_EQ(fmt::mm(0.2784, 1), "278.4");
  EXPECT_EQ(fmt::pct(-0.0111), "-1.1%");
  EXPECT_EQ(fmt::pct(0.00126, 2), "+0.13%");
  EXPECT_EQ(fmt::secs(0.01234), "0.0123");
  EXPECT_EQ(fmt::secs(2222.4), "2222");
  EXPECT_EQ(fmt::px(INFINITY), "0.0");  // a coordinate never breaks the drawing
  EXPECT_EQ(fmt::kn(19350), "19.4");
  EXPECT_EQ(fmt::duration(0.0038), "3.8 ms");
  EXPECT_EQ(fmt::duration(0.00096), "0.96 ms");
  EXPECT_EQ(fmt::duration(0.79), "790 ms");
  EXPECT_EQ(fmt::duration(21.2), "21.2 s");
  EXPECT_EQ(fmt::duration(NAN), "n/a");
}

TEST(ReportTable, NumbersRightTextLeftInBothRenderings) {
  Table t;
  t.head = {"run", "capacity (m)", "difference"};
  t.rows = {{"PRD", "0.278", "-"}, {"DEM <x>", "0.275", "-1.1%"}, {"failed", "n/a", Cell("no", CellStyle::strong)}};
  const std::vector<Align> a = alignment(t);
  EXPECT_EQ(a[0], Align::left);
  EXPECT_EQ(a[1], Align::left);  // "n/a" is text: the column is not all numbers
  EXPECT_EQ(a[2], Align::left);  // "no"
  t.rows.pop_back();
  EXPECT_EQ(alignment(t)[1], Align::right);
  EXPECT_EQ(alignment(t)[2], Align::right);  // a dash is no text
  const std::string md = markdown(t), h = html(t);
  EXPECT_NE(md.find("|---|---:|---:|"), std::string::npos) << md;
  EXPECT_EQ(count(md, "\n"), 2 + t.rows.size() + 1);  // head, rule, rows, blank line
  EXPECT_NE(md.find("DEM \\<x>"), std::string::npos);
  EXPECT_NE(h.find("<td class=\"l\">DEM &lt;x&gt;</td><td>0.275</td><td>-1.1%</td>"), std::string::npos) << h;
  // Given alignments win over detection.
  t.align = {Align::right, Align::left, Align::left};
  EXPECT_NE(markdown(t).find("|---:|---|---|"), std::string::npos);
}

TEST(ReportDocument, BothMediaCarryTheSameTextEachItsOwnParts) {
  Document d;
  d.title = "arch <1>";
  d.paragraph({"Made with ", Cell("masonry `x`", CellStyle::code), ", see ", Cell("a run", CellStyle::link, "runs/a/results.json")});
  d.heading(2, {"Hinges"});
  d.list({{{"PRD: v0/v1:A"}, {{"sub item"}}}});
  d.paragraph({"only in the Markdown"}, Medium::markdown);
  d.raw_html("<div id=\"slider\"></div>");
  d.figure("figures/f.svg", "a figure", "<svg></svg>");
  const std::string md = markdown(d), h = html_body(d);
  EXPECT_EQ(md.rfind("# arch <1>\n\n", 0), 0u) << md;  // "<1" opens no tag
  EXPECT_NE(h.find("<h1>arch &lt;1&gt;</h1>"), std::string::npos);
  EXPECT_NE(md.find("Made with `masonry 'x'`, see [a run](runs/a/results.json)"), std::string::npos) << md;
  EXPECT_NE(h.find("Made with <code>masonry `x`</code>, see <a href=\"runs/a/results.json\">a run</a>"), std::string::npos) << h;
  EXPECT_NE(md.find("## Hinges\n\n- PRD: v0/v1:A\n  - sub item\n"), std::string::npos) << md;
  EXPECT_NE(h.find("<li>PRD: v0/v1:A<ul><li>sub item</li></ul></li>"), std::string::npos) << h;
  EXPECT_NE(md.find("only in the Markdown"), std::string::npos);
  EXPECT_EQ(h.find("only in the Markdown"), std::string::npos);
  EXPECT_EQ(md.find("slider"), std::string::npos);
  EXPECT_NE(h.find("<div id=\"slider\"></div>"), std::string::npos);
  EXPECT_NE(md.find("![a figure](figures/f.svg)"), std::string::npos);
  EXPECT_NE(h.find("<svg></svg><figcaption>a figure</figcaption>"), std::string::npos);
}

TEST(ReportHtml, NoScriptRunsWithoutTheNonce) {
  HtmlPage p;
  p.title = "<t>";
  p.body = "<p>x</p>\n";
  const std::string plain = html_page(p);
  EXPECT_NE(plain.find("content=\"default-src 'none'; style-src 'unsafe-inline'\""), std::string::npos);
  EXPECT_EQ(plain.find("script-src"), std::string::npos);
  EXPECT_NE(plain.find("<title>&lt;t&gt;</title>"), std::string::npos);
  p.script_nonce = script_nonce();
  EXPECT_EQ(p.script_nonce.size(), 24u);
  EXPECT_NE(script_nonce(), p.script_nonce);  // fresh per page
  EXPECT_NE(html_page(p).find("script-src 'nonce-" + p.script_nonce + "'"), std::string::npos);
}

TEST(ReportSvg, TicksAreExactMultiplesOfANiceStep) {
  EXPECT_DOUBLE_EQ(nice_step(1.0, 5), 0.2);
  EXPECT_DOUBLE_EQ(nice_step(0.93, 8), 0.1);
  EXPECT_DOUBLE_EQ(nice_step(270, 6), 50);
  const Ticks t = linear_ticks(-0.03, 0.07, 5, 3);
  EXPECT_DOUBLE_EQ(t.step, 0.02);
  ASSERT_EQ(t.at.size(), 5u);  // -0.02, 0, 0.02, 0.04, 0.06: the multiples inside the range
  for (size_t k = 0; k < t.at.size(); ++k) EXPECT_NEAR(std::remainder(t.at[k], t.step), 0.0, 1e-15);
  // The tick at zero is zero, not round-off, and reads "0".
  bool zero = false;
  for (size_t k = 0; k < t.at.size(); ++k)
    if (t.at[k] == 0.0) zero = t.label[k] == "0";
  EXPECT_TRUE(zero);
  const Ticks d = decade_ticks(-5, 3);
  EXPECT_EQ(d.label.front(), "1e-5");
  EXPECT_EQ(d.label[2], "0.001");
  EXPECT_EQ(d.label[5], "1");
  EXPECT_EQ(d.label.back(), "1000");
  // A log plot puts a decade at the same distance whatever its place; zeros go in the band.
  const Plot p{0, 0, 300, 300, -3, 0, -3, 0, true, true, 30};
  EXPECT_NEAR(p.X(0.01) - p.X(0.001), p.X(1) - p.X(0.1), 1e-9);
  EXPECT_GT(p.Y(0.0), p.top + p.height);
  EXPECT_LT(p.Y(0.0), p.top + p.height + p.band);
}

}  // namespace
}  // namespace masonry
