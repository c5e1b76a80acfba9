#include "report/escape.hpp"

#include <algorithm>
#include <cctype>

namespace masonry {

size_t utf8_char(std::string_view s, size_t i, unsigned& cp) {
  const unsigned char c = static_cast<unsigned char>(s[i]);
  const size_t n = c < 0x80 ? 0 : (c >> 5) == 6 ? 1 : (c >> 4) == 14 ? 2 : (c >> 3) == 30 ? 3 : 4;
  if (n == 4 || i + n >= s.size()) return 0;
  cp = n == 0 ? c : c & (0x3fu >> n);
  for (size_t k = 1; k <= n; ++k) {
    const unsigned char t = static_cast<unsigned char>(s[i + k]);
    if ((t >> 6) != 2) return 0;
    cp = (cp << 6) | (t & 0x3f);
  }
  const bool overlong = (n == 1 && cp < 0x80) || (n == 2 && cp < 0x800) || (n == 3 && cp < 0x10000);
  if (overlong || cp > 0x10ffff || (cp >= 0xd800 && cp <= 0xdfff)) return 0;
  return n + 1;
}

std::string xml_escape(const std::string& s) {
  std::string o;
  o.reserve(s.size());
  for (size_t i = 0; i < s.size();) {
    const char ch = s[i];
    unsigned cp = 0;
    const size_t n = utf8_char(s, i, cp);
    if (n == 0 || cp == 0xfffe || cp == 0xffff) {
      o += "\xEF\xBF\xBD";  // U+FFFD, the replacement character
      i += n == 0 ? 1 : n;
      continue;
    }
    if (n == 1 && cp < 0x20 && ch != '\t' && ch != '\n' && ch != '\r') {
      static const char hex[] = "0123456789abcdef";
      o += "\\x";
      o += hex[cp >> 4];
      o += hex[cp & 15];
      ++i;
      continue;
    }
    switch (ch) {
      case '&': o += "&amp;"; break;
      case '<': o += "&lt;"; break;
      case '>': o += "&gt;"; break;
      case '"': o += "&quot;"; break;
      case '\'': o += "&#39;"; break;
      default: o.append(s, i, n);
    }
    i += n;
  }
  return o;
}

namespace {

// Whether the text from position k on reads as an HTML entity or numeric reference ("&gt;",
// "&#39;"): only then does a '&' need escaping, so "Romano & Ochsendorf" stays as written.
bool entity_at(const std::string& s, size_t k) {
  size_t e = k + 1;
  if (e < s.size() && s[e] == '#') ++e;
  const size_t start = e;
  while (e < s.size() && std::isalnum(static_cast<unsigned char>(s[e]))) ++e;
  return e > start && e < s.size() && s[e] == ';';
}

// Whether a '<' at position k opens a tag, a comment or an autolink (a letter, '/', '!' or '?'
// follows): only then does it need escaping, so "-> 3 < 4" stays as written.
bool tag_at(const std::string& s, size_t k) {
  if (k + 1 >= s.size()) return false;
  const char n = s[k + 1];
  return std::isalpha(static_cast<unsigned char>(n)) || n == '/' || n == '!' || n == '?';
}

}  // namespace

std::string md_escape(const std::string& s) {
  std::string o;
  o.reserve(s.size());
  for (size_t k = 0; k < s.size(); ++k) {
    const char ch = s[k];
    switch (ch) {
      // Raw HTML is never passed through (a case name cannot open a tag), by backslash escapes
      // where the character would act, not entities: report.md is read as text too.
      case '&':
        if (entity_at(s, k)) o += '\\';
        o += ch;
        break;
      case '<':
        if (tag_at(s, k)) o += '\\';
        o += ch;
        break;
      case '\n':
      case '\r': o += ' '; break;
      // Emphasis, code, links and images ('!' and '(' only act after '[' or ']'), tables and
      // strike-through; '#' makes a heading and '>' a quotation only at the start of a line.
      case '\\':
      case '`':
      case '*':
      case '_':
      case '[':
      case ']':
      case '|':
      case '~':
        o += '\\';
        o += ch;
        break;
      case '#':
      case '>':
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
