// A report's content as one structure (headings, paragraphs, lists, tables, figures), written as
// Markdown and as the body of an HTML page by one writer each, so the two renderings hold the
// same text and numbers. Where the media differ on purpose (a figure file beside the Markdown, an
// interactive slider in the page) an element says which medium it is for.
#pragma once

#include <string>
#include <vector>

#include "report/table.hpp"

namespace masonry {

// Inline text: runs of cells, each plain, strong, code or a link.
using Text = std::vector<Cell>;

struct Item {
  Text text;
  std::vector<Text> sub;  // a nested list
};

enum class Medium { both, markdown, html };

struct Element {
  enum class Kind { heading, paragraph, list, table, figure, raw_html } kind = Kind::paragraph;
  Medium medium = Medium::both;
  int level = 2;              // heading
  Text text;                  // heading, paragraph
  std::vector<Item> items;    // list
  Table table;                // table
  std::string file, caption;  // figure: the Markdown links `file` (relative), captioned
  std::string svg;            // figure: the page inlines it
  std::string html;           // raw_html: as it is, in the page only
};

struct Document {
  std::string title;  // plain text: the first heading and the page title
  std::vector<Element> body;

  Document& heading(int level, Text t);
  Document& paragraph(Text t, Medium m = Medium::both);
  Document& list(std::vector<Item> items);
  Document& table(Table t);
  Document& figure(std::string file, std::string caption, std::string svg);
  Document& raw_html(std::string html);
  Element& last() { return body.back(); }
};

// Both end with the line that says which masonry wrote the report ("Written by masonry 0.1.0 (git
// 96c2a98a1b2c)."), so every report records the version that made it.
std::string markdown(const Document& d);
// The page body (to go into html_page): the title as <h1>, then the elements.
std::string html_body(const Document& d);

}  // namespace masonry
