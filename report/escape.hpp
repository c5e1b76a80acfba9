// Text from a case or a command line inside a report: escaped where it is written, so a case name
// can neither inject markup nor break a table.
#pragma once

#include <string>

namespace masonry {

// Text for HTML and SVG: the five XML special characters as entities.
std::string xml_escape(const std::string& s);

// Text for Markdown: Markdown punctuation and any '<' that would open a tag or '&' that would read
// as an entity escaped with a backslash (no HTML entities: report.md is read as text too); a line
// break becomes a space (a table row is one line).
std::string md_escape(const std::string& s);

// Text for a Markdown code span: a code span cannot escape a backtick, so backticks become
// quotes, and '|' becomes '/' so the span can sit in a table cell.
std::string md_code(const std::string& s);

}  // namespace masonry
