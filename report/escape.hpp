// Text from a case or a command line inside a report: escaped where it is written, so a case name
// can neither inject markup nor break a table.
#pragma once

#include <string>
#include <string_view>

namespace masonry {

// The length (1 to 4 bytes) of the UTF-8 character at s[i], its code point in `cp`; 0 where the
// bytes there are not UTF-8 (a stray continuation byte, an overlong form, a surrogate, beyond
// U+10FFFF, cut short).
size_t utf8_char(std::string_view s, size_t i, unsigned& cp);

// Text for HTML and SVG: the five XML special characters as entities, and whatever XML 1.0 does
// not allow in a document replaced, so the page stays well-formed whatever a case's ids hold:
// control characters (an ESC byte) written as \xNN, bytes that are not UTF-8 and U+FFFE/U+FFFF as
// U+FFFD.
std::string xml_escape(const std::string& s);

// Text for Markdown: Markdown punctuation and any '<' that would open a tag or '&' that would read
// as an entity escaped with a backslash (no HTML entities: report.md is read as text too); a line
// break becomes a space (a table row is one line).
std::string md_escape(const std::string& s);

// Text for a Markdown code span: a code span cannot escape a backtick, so backticks become
// quotes, and '|' becomes '/' so the span can sit in a table cell.
std::string md_code(const std::string& s);

}  // namespace masonry
