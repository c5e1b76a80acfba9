// A report table as plain data, written as Markdown or HTML by one writer each, so the two
// renderings of a report cannot drift apart. Cells hold plain text; the writers escape it.
#pragma once

#include <string>
#include <vector>

namespace masonry {

// How a cell is shown: emphasis for a failed check, code for settings, a link to a run's files.
enum class CellStyle { plain, strong, code, link };

struct Cell {
  std::string text;
  CellStyle style = CellStyle::plain;
  std::string href;  // CellStyle::link only: a relative path
  Cell() = default;
  Cell(std::string t) : text(std::move(t)) {}  // NOLINT: a plain cell from text
  Cell(const char* t) : text(t) {}             // NOLINT
  Cell(std::string t, CellStyle s, std::string h = {}) : text(std::move(t)), style(s), href(std::move(h)) {}
};

enum class Align { left, right };

struct Table {
  std::vector<std::string> head;
  std::vector<std::vector<Cell>> rows;
  // Per column; empty: a column of numbers (or dashes) right-aligned, text left.
  std::vector<Align> align;
};

// The alignment of every column: `align` where given, else detected from the cells.
std::vector<Align> alignment(const Table& t);

// Markdown: a header row, the alignment row and one line per row, then a blank line.
std::string markdown(const Table& t);
// HTML: <table> with left-aligned cells of class "l" (the page shell styles it).
std::string html(const Table& t);

// A cell's text as inline Markdown or HTML, styled (shared with lists and paragraphs).
std::string markdown(const Cell& c);
std::string html(const Cell& c);

}  // namespace masonry
