#include "report/document.hpp"

#include "model/version.hpp"
#include "report/escape.hpp"

namespace masonry {

namespace {

// The last line of every report.
Text written_by() { return {"Written by " + version_text() + "."}; }

std::string md_text(const Text& t) {
  std::string o;
  for (const Cell& c : t) o += markdown(c);
  return o;
}

std::string html_text(const Text& t) {
  std::string o;
  for (const Cell& c : t) o += html(c);
  return o;
}

Element& add(Document& d, Element::Kind k) {
  d.body.emplace_back();
  d.body.back().kind = k;
  return d.body.back();
}

}  // namespace

Document& Document::heading(int level, Text t) {
  Element& e = add(*this, Element::Kind::heading);
  e.level = level;
  e.text = std::move(t);
  return *this;
}

Document& Document::paragraph(Text t, Medium m) {
  Element& e = add(*this, Element::Kind::paragraph);
  e.text = std::move(t);
  e.medium = m;
  return *this;
}

Document& Document::list(std::vector<Item> items) {
  add(*this, Element::Kind::list).items = std::move(items);
  return *this;
}

Document& Document::table(Table t) {
  add(*this, Element::Kind::table).table = std::move(t);
  return *this;
}

Document& Document::figure(std::string file, std::string caption, std::string svg) {
  Element& e = add(*this, Element::Kind::figure);
  e.file = std::move(file);
  e.caption = std::move(caption);
  e.svg = std::move(svg);
  return *this;
}

Document& Document::raw_html(std::string html) {
  Element& e = add(*this, Element::Kind::raw_html);
  e.html = std::move(html);
  e.medium = Medium::html;
  return *this;
}

std::string markdown(const Document& d) {
  std::string o = "# " + md_escape(d.title) + "\n\n";
  for (const Element& e : d.body) {
    if (e.medium == Medium::html) continue;
    switch (e.kind) {
      case Element::Kind::heading: o += std::string(e.level, '#') + " " + md_text(e.text) + "\n\n"; break;
      case Element::Kind::paragraph: o += md_text(e.text) + "\n\n"; break;
      case Element::Kind::list:
        for (const Item& it : e.items) {
          o += "- " + md_text(it.text) + "\n";
          for (const Text& s : it.sub) o += "  - " + md_text(s) + "\n";
        }
        o += "\n";
        break;
      case Element::Kind::table: o += markdown(e.table); break;
      case Element::Kind::figure:
        if (!e.file.empty()) o += "![" + md_escape(e.caption) + "](" + md_code(e.file) + ")\n\n";
        break;
      case Element::Kind::raw_html: break;
    }
  }
  return o + md_text(written_by()) + "\n";
}

std::string html_body(const Document& d) {
  std::string o = "<h1>" + xml_escape(d.title) + "</h1>\n";
  for (const Element& e : d.body) {
    if (e.medium == Medium::markdown) continue;
    switch (e.kind) {
      case Element::Kind::heading: {
        const std::string h = std::string(1, 'h').append(std::to_string(e.level));  // (not "h" +: GCC 12's false -Wrestrict)
        o += "<" + h + ">" + html_text(e.text) + "</" + h + ">\n";
        break;
      }
      case Element::Kind::paragraph: o += "<p>" + html_text(e.text) + "</p>\n"; break;
      case Element::Kind::list:
        o += "<ul>\n";
        for (const Item& it : e.items) {
          o += "<li>" + html_text(it.text);
          if (!it.sub.empty()) {
            o += "<ul>";
            for (const Text& s : it.sub) o += "<li>" + html_text(s) + "</li>";
            o += "</ul>";
          }
          o += "</li>\n";
        }
        o += "</ul>\n";
        break;
      case Element::Kind::table: o += html(e.table); break;
      case Element::Kind::figure:
        if (e.svg.empty()) break;
        o += "<figure>" + e.svg + "<figcaption>" + xml_escape(e.caption) + "</figcaption></figure>\n";
        break;
      case Element::Kind::raw_html: o += e.html; break;
    }
  }
  return o + "<p>" + html_text(written_by()) + "</p>\n";
}

}  // namespace masonry
