#include "report/table.hpp"

#include <cstdlib>

#include "report/escape.hpp"

namespace masonry {

namespace {

// A number, possibly followed by a unit or a percent sign: "0.913", "-1.8%", "12 / 14".
bool numeric(const std::string& s) {
  char* end = nullptr;
  std::strtod(s.c_str(), &end);
  return end != s.c_str() && (*end == '\0' || *end == '%' || *end == ' ');
}

}  // namespace

std::vector<Align> alignment(const Table& t) {
  const size_t n = t.head.size();
  std::vector<Align> a(n, Align::left);
  for (size_t k = 0; k < n; ++k) {
    if (k < t.align.size()) {
      a[k] = t.align[k];
      continue;
    }
    bool number = false, text = false;
    for (const auto& r : t.rows) {
      if (k >= r.size() || r[k].text == "-" || r[k].text.empty()) continue;
      (numeric(r[k].text) ? number : text) = true;
    }
    a[k] = number && !text ? Align::right : Align::left;
  }
  return a;
}

std::string markdown(const Cell& c) {
  switch (c.style) {
    case CellStyle::strong: return "**" + md_escape(c.text) + "**";
    // Appended piece by piece: GCC 12 warns (-Wrestrict, falsely) about a one-character literal
    // + std::string.
    case CellStyle::code: return std::string(1, '`').append(md_code(c.text)).append(1, '`');
    case CellStyle::link: return std::string(1, '[').append(md_escape(c.text)).append("](").append(md_code(c.href)).append(1, ')');
    case CellStyle::plain: break;
  }
  return md_escape(c.text);
}

std::string html(const Cell& c) {
  switch (c.style) {
    case CellStyle::strong: return "<strong>" + xml_escape(c.text) + "</strong>";
    case CellStyle::code: return "<code>" + xml_escape(c.text) + "</code>";
    case CellStyle::link: return "<a href=\"" + xml_escape(c.href) + "\">" + xml_escape(c.text) + "</a>";
    case CellStyle::plain: break;
  }
  return xml_escape(c.text);
}

std::string markdown(const Table& t) {
  std::string o;
  // Appended piece by piece: GCC 12 warns (-Wrestrict, falsely) about " " + std::string here.
  o += '|';
  for (const std::string& h : t.head) {
    o += ' ';
    o += md_escape(h);
    o += " |";
  }
  o += "\n|";
  for (const Align a : alignment(t)) o += a == Align::right ? "---:|" : "---|";
  o += '\n';
  for (const auto& r : t.rows) {
    o += '|';
    for (size_t k = 0; k < t.head.size(); ++k) {
      o += ' ';
      if (k < r.size()) o += markdown(r[k]);
      o += " |";
    }
    o += '\n';
  }
  o += '\n';
  return o;
}

std::string html(const Table& t) {
  const std::vector<Align> a = alignment(t);
  std::string o = "<table>\n<tr>";
  for (size_t k = 0; k < t.head.size(); ++k) {
    o += a[k] == Align::right ? "<th>" : "<th class=\"l\">";
    o += xml_escape(t.head[k]);
    o += "</th>";
  }
  o += "</tr>\n";
  for (const auto& r : t.rows) {
    o += "<tr>";
    for (size_t k = 0; k < t.head.size(); ++k) {
      o += a[k] == Align::right ? "<td>" : "<td class=\"l\">";
      if (k < r.size()) o += html(r[k]);
      o += "</td>";
    }
    o += "</tr>\n";
  }
  return o + "</table>\n";
}

}  // namespace masonry
