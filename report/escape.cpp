#include "report/escape.hpp"

#include <algorithm>

namespace masonry {

std::string xml_escape(const std::string& s) {
  std::string o;
  o.reserve(s.size());
  for (char ch : s) {
    switch (ch) {
      case '&': o += "&amp;"; break;
      case '<': o += "&lt;"; break;
      case '>': o += "&gt;"; break;
      case '"': o += "&quot;"; break;
      case '\'': o += "&#39;"; break;
      default: o += ch;
    }
  }
  return o;
}

std::string md_escape(const std::string& s) {
  std::string o;
  o.reserve(s.size());
  for (size_t k = 0; k < s.size(); ++k) {
    const char ch = s[k];
    switch (ch) {
      // Raw HTML is never passed through: a case name cannot open a tag.
      case '&': o += "&amp;"; break;
      case '<': o += "&lt;"; break;
      case '>': o += "&gt;"; break;
      case '\n': case '\r': o += ' '; break;
      // Emphasis, code, links and images ('!' and '(' only act after '[' or ']'), tables and
      // strike-through; '#' makes a heading only at the start of a line.
      case '\\': case '`': case '*': case '_': case '[': case ']': case '|': case '~':
        o += '\\';
        o += ch;
        break;
      case '#':
        if (k == 0) o += '\\';
        o += ch;
        break;
      default: o += ch;
    }
  }
  return o;
}

std::string md_code(const std::string& s) {
  std::string o = s;
  std::replace(o.begin(), o.end(), '`', '\'');
  std::replace(o.begin(), o.end(), '|', '/');
  std::replace(o.begin(), o.end(), '\n', ' ');
  std::replace(o.begin(), o.end(), '\r', ' ');
  return o;
}

}  // namespace masonry
