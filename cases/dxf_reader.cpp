// read_dxf, as named stages: the file's lines as (group code, value) pairs, each value checked
// against its code's type; the sections (HEADER for $INSUNITS, ENTITIES for what can be a
// block, the others skipped pair by pair); each entity's pairs interpreted with its counts and
// coordinates checked.
#include "cases/dxf_reader.hpp"

#include <algorithm>
#include <charconv>
#include <climits>
#include <cmath>
#include <optional>
#include <string_view>

#include "model/case.hpp"
#include "model/io.hpp"
#include "report/escape.hpp"

namespace masonry {

std::string DxfEntity::name() const {
  return printable(type, 40) + " (handle " + (handle.empty() ? std::string("none") : printable(handle, 40)) + ", layer '" + printable(layer, 80) +
         "')";
}

namespace {

// The value types of the group codes (DXF reference, "Group Code Value Types").
enum class GroupType { none, text, real, int16, int32, int64 };

GroupType group_type(int c) {
  using G = GroupType;
  if (c < 0) return G::none;
  if (c <= 9) return G::text;
  if (c <= 59) return G::real;
  if (c <= 79) return G::int16;
  if (c < 90) return G::none;
  if (c <= 99) return G::int32;
  if (c == 100 || c == 102 || c == 105) return G::text;
  if (c >= 110 && c <= 149) return G::real;
  if (c >= 160 && c <= 169) return G::int64;
  if (c >= 170 && c <= 179) return G::int16;
  if (c >= 210 && c <= 239) return G::real;
  if (c >= 270 && c <= 299) return G::int16;  // 290-299 are booleans, written as 0 and 1
  if (c >= 300 && c <= 369) return G::text;
  if (c >= 370 && c <= 389) return G::int16;
  if (c >= 390 && c <= 399) return G::text;
  if (c >= 400 && c <= 409) return G::int16;
  if (c >= 410 && c <= 419) return G::text;
  if (c >= 420 && c <= 429) return G::int32;
  if (c >= 430 && c <= 439) return G::text;
  if (c >= 440 && c <= 459) return G::int32;
  if (c >= 460 && c <= 469) return G::real;
  if (c >= 470 && c <= 481) return G::text;
  if (c == 999) return G::text;
  if (c >= 1000 && c <= 1009) return G::text;
  if (c >= 1010 && c <= 1059) return G::real;
  if (c >= 1060 && c <= 1070) return G::int16;
  if (c == 1071) return G::int32;
  return G::none;
}

const char* type_words(GroupType t) {
  switch (t) {
    case GroupType::real: return "a real number";
    case GroupType::int16: return "a 16-bit integer";
    case GroupType::int32: return "a 32-bit integer";
    case GroupType::int64: return "a 64-bit integer";
    default: return "text";
  }
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

// A decimal number as C writes one, nothing before or after it but blanks: no "nan", "inf",
// hexadecimal, thousands or decimal commas, or trailing text. False also when it overflows.
bool parse_real(std::string_view s, double& x) {
  s = trim(s);
  size_t i = 0;
  if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
  size_t digits = 0;
  while (i < s.size() && s[i] >= '0' && s[i] <= '9') ++i, ++digits;
  if (i < s.size() && s[i] == '.') {
    ++i;
    while (i < s.size() && s[i] >= '0' && s[i] <= '9') ++i, ++digits;
  }
  if (digits == 0) return false;
  if (i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
    ++i;
    if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
    size_t e = 0;
    while (i < s.size() && s[i] >= '0' && s[i] <= '9') ++i, ++e;
    if (e == 0) return false;
  }
  if (i != s.size()) return false;
  if (s.front() == '+') s.remove_prefix(1);  // from_chars takes no '+'
  const auto r = std::from_chars(s.data(), s.data() + s.size(), x);
  return r.ec == std::errc() && r.ptr == s.data() + s.size() && std::isfinite(x);
}

bool parse_integer(std::string_view s, long long lo, long long hi, long long& x) {
  s = trim(s);
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  if (s.empty()) return false;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), x);
  return r.ec == std::errc() && r.ptr == s.data() + s.size() && x >= lo && x <= hi;
}

bool valid_utf8(std::string_view s) {
  unsigned cp = 0;
  for (size_t i = 0, n = 0; i < s.size(); i += n)
    if ((n = utf8_char(s, i, cp)) == 0) return false;
  return true;
}

void put_utf8(std::string& o, unsigned cp) {
  if (cp < 0x80) {
    o += static_cast<char>(cp);
  } else if (cp < 0x800) {
    o += static_cast<char>(0xc0 | (cp >> 6));
    o += static_cast<char>(0x80 | (cp & 0x3f));
  } else {
    o += static_cast<char>(0xe0 | (cp >> 12));
    o += static_cast<char>(0x80 | ((cp >> 6) & 0x3f));
    o += static_cast<char>(0x80 | (cp & 0x3f));
  }
}

// A drawing's text as UTF-8: drawings before AutoCAD 2007 write 8-bit text in their code page
// (taken as Latin-1 where the bytes are not UTF-8) and other characters as \U+XXXX.
//
// An MTEXT's value also carries inline formatting codes (DXF reference, "MTEXT"; AutoCAD writes
// them as soon as a font, height or paragraph is set: `\A1;{\fArial|b1;Pier\P2}`). They say how
// the text looks, not what it says, and an id kept them verbatim, which nobody can type in a
// --hold or a fragment's loads, so they are removed (cases/README.md, "Ids"): the codes with a
// value up to ';' (\A \C \c \F \f \H \Q \T \W \p), the toggles \L \l \O \o \K \k, the braces
// that group them; \P (paragraph), \N (column), \X and \~ (non-breaking space) become a space;
// a stack \Sa^b; becomes a/b; \\ \{ \} are the characters themselves. Runs of blanks then become
// one space, and the ends are trimmed. An unknown code is kept as written.
std::string text_utf8(std::string_view raw, bool mtext) {
  std::string s;
  if (valid_utf8(raw)) {
    s = raw;
  } else {
    for (char ch : raw) put_utf8(s, static_cast<unsigned char>(ch));
  }
  std::string o;
  // A code's value runs to its ';' (to the end where the drawing omits it).
  const auto value_end = [&](size_t from) { return std::min(s.find(';', from), s.size()); };
  for (size_t i = 0; i < s.size(); ++i) {
    unsigned cp = 0;
    if (s.compare(i, 3, "\\U+") == 0 && i + 7 <= s.size() && std::from_chars(s.data() + i + 3, s.data() + i + 7, cp, 16).ptr == s.data() + i + 7 &&
        cp >= 0x20 && (cp < 0xd800 || cp > 0xdfff)) {
      put_utf8(o, cp);
      i += 6;
    } else if (mtext && (s[i] == '{' || s[i] == '}')) {
      continue;
    } else if (mtext && s[i] == '\\' && i + 1 < s.size()) {
      const char c = s[i + 1];
      if (c == '\\' || c == '{' || c == '}') {
        o += c;
        ++i;
      } else if (c == 'P' || c == 'N' || c == 'X' || c == '~') {
        o += ' ';
        ++i;
      } else if (std::string_view("LlOoKk").find(c) != std::string_view::npos) {
        ++i;
      } else if (std::string_view("ACcFfHQTWp").find(c) != std::string_view::npos) {
        i = value_end(i + 2);
      } else if (c == 'S') {
        const size_t end = value_end(i + 2);
        for (size_t k = i + 2; k < end; ++k) o += s[k] == '^' || s[k] == '#' ? '/' : s[k];
        i = end;
      } else {
        o += s[i];
      }
    } else {
      o += s[i];
    }
  }
  if (!mtext) return o;
  std::string plain;
  for (char ch : o) {
    const bool blank = ch == ' ' || ch == '\t';
    if (blank && (plain.empty() || plain.back() == ' ')) continue;
    plain += blank ? ' ' : ch;
  }
  if (!plain.empty() && plain.back() == ' ') plain.pop_back();
  return plain;
}

struct Pair {
  int code = 0;
  std::string_view value;
  size_t line = 0;  // the line of the group code; the value is on the next
};

// The file as pairs of lines, the group code checked; values are checked where an entity is read.
class Pairs {
 public:
  Pairs(const std::string& path, const std::string& text) : path_(path), text_(text) {}

  [[noreturn]] void fail(size_t line, const std::string& what) const { throw CaseError(path_ + ":" + std::to_string(line) + ": " + what); }

  bool next(Pair& p) {
    if (held_) {
      held_ = false;
      p = last_;
      return true;
    }
    std::string_view code;
    if (!line(code)) return false;
    p.line = line_no_;
    long long c = 0;
    if (!parse_integer(code, -32768, 32767, c) || group_type(static_cast<int>(c)) == GroupType::none)
      fail(p.line, "'" + printable(std::string(trim(code)), 40) +
                       "' is not a group code of the DXF reference (a DXF file is pairs of lines: a group code, then its value)");
    p.code = static_cast<int>(c);
    if (!line(p.value)) fail(p.line, "the drawing ends after group code " + std::to_string(p.code) + ", without its value (truncated?)");
    last_ = p;
    return true;
  }
  void hold() { held_ = true; }  // the next call returns the same pair again
  size_t line_no() const { return line_no_; }

 private:
  bool line(std::string_view& out) {
    if (at_ >= text_.size()) return false;
    size_t end = text_.find('\n', at_);
    if (end == std::string::npos) end = text_.size();
    out = std::string_view(text_).substr(at_, end - at_);
    at_ = end + 1;
    ++line_no_;
    if (!out.empty() && out.back() == '\r') out.remove_suffix(1);
    for (char ch : out)
      if (static_cast<unsigned char>(ch) < 0x20 && ch != '\t')
        fail(line_no_, "binary content (byte " + printable(std::string(1, ch)) + "): not an ASCII DXF drawing");
    return true;
  }

  const std::string& path_;
  const std::string& text_;
  size_t at_ = 0, line_no_ = 0;
  Pair last_;
  bool held_ = false;
};

// One entity: its pairs after the group code 0 that names it, each value checked against its
// code's type, with what messages say about it.
struct Entity {
  DxfEntity e;
  std::vector<Pair> pairs;
  double nz = 1;  // the extrusion's z sign: -1 mirrors x (DXF's arbitrary axis algorithm for -z)

  [[noreturn]] void fail(const Pairs& in, size_t line, const std::string& what) const { in.fail(line, e.name() + ": " + what); }
  [[noreturn]] void fail(const Pairs& in, const Pair& p, const std::string& what) const {
    fail(in, p.line, "group code " + std::to_string(p.code) + " = '" + printable(std::string(trim(p.value)), 40) + "': " + what);
  }
  double real(const Pairs& in, const Pair& p) const {
    double x = 0;
    if (!parse_real(p.value, x)) fail(in, p, "not a real number");
    return x;
  }
  long long integer(const Pairs& in, const Pair& p) const {
    long long x = 0;
    const GroupType t = group_type(p.code);
    const long long lo = t == GroupType::int16 ? -32768 : t == GroupType::int32 ? INT32_MIN : INT64_MIN;
    const long long hi = t == GroupType::int16 ? 32767 : t == GroupType::int32 ? INT32_MAX : INT64_MAX;
    if (!parse_integer(p.value, lo, hi, x)) fail(in, p, std::string("not ") + type_words(t));
    return x;
  }
  // Every value against its type, then what every entity carries: handle, layer, space, plane.
  void check(const Pairs& in) {
    Vec2 nxy(0, 0);
    bool seen5 = false, seen8 = false;
    for (const Pair& p : pairs) {
      const GroupType t = group_type(p.code);
      if (t == GroupType::real)
        (void)real(in, p);
      else if (t != GroupType::text)
        (void)integer(in, p);
      if (p.code == 5 || p.code == 8) {
        bool& seen = p.code == 5 ? seen5 : seen8;
        if (seen) fail(in, p, "given twice");
        seen = true;
        (p.code == 5 ? e.handle : e.layer) = std::string(trim(p.value));
      }
      if (p.code == 67) e.paper_space = integer(in, p) == 1;
      if (p.code == 210) nxy.x() = real(in, p);
      if (p.code == 220) nxy.y() = real(in, p);
      if (p.code == 230) nz = real(in, p);
    }
    // Only a drawing in the x-y plane, seen from either side: a normal of -z mirrors x.
    e.off_plane = !(std::abs(nz) > 0) || nxy.norm() > 1e-9 * std::abs(nz);
    nz = nz < 0 ? -1.0 : 1.0;
  }
};

// Whatever pair comes next must exist: the drawing is cut off otherwise.
Pair must_next(Pairs& in, const char* where) {
  Pair p;
  if (!in.next(p)) in.fail(in.line_no(), std::string("the drawing ends inside ") + where + " (truncated?)");
  return p;
}

// The entity that starts with `head` (group code 0): its pairs up to the next group code 0.
Entity read_entity(Pairs& in, const Pair& head, const char* section) {
  Entity x;
  x.e.type = std::string(trim(head.value));
  x.e.line = head.line;
  x.e.layer = "0";
  for (;;) {
    const Pair p = must_next(in, section);
    if (p.code == 0) {
      in.hold();
      break;
    }
    x.pairs.push_back(p);
  }
  x.check(in);
  return x;
}

// Stage: LWPOLYLINE, the vertices inline: 90 the count, then 10 and 20 for each vertex, 42 its
// bulge (40, 41 its widths and 91 its id are not geometry here).
DxfPolyline lwpolyline(const Pairs& in, const Entity& x) {
  DxfPolyline out;
  out.e = x.e;
  long long count = -1;
  const Pair* count_pair = nullptr;
  bool flags = false, bulged = false;
  for (size_t k = 0; k < x.pairs.size(); ++k) {
    const Pair& p = x.pairs[k];
    switch (p.code) {
      case 90:
        if (count_pair) x.fail(in, p, "the number of vertices given twice");
        count = x.integer(in, p);
        count_pair = &p;
        if (count < 0) x.fail(in, p, "a negative number of vertices");
        break;
      case 70:
        if (flags) x.fail(in, p, "the flags given twice");
        flags = true;
        out.closed = (x.integer(in, p) & 1) != 0;
        break;
      case 10: {
        if (k + 1 >= x.pairs.size() || x.pairs[k + 1].code != 20) x.fail(in, p, "a vertex's x without its y (group code 20 next)");
        out.v.push_back({x.nz * x.real(in, p), x.real(in, x.pairs[k + 1]), 0, p.line});
        bulged = false;
        ++k;
        break;
      }
      case 20: x.fail(in, p, "a vertex's y without its x (group code 10 before it)");
      case 42:
        if (out.v.empty()) x.fail(in, p, "a bulge before the first vertex");
        if (bulged) x.fail(in, p, "a vertex's bulge given twice");
        out.v.back().bulge = x.nz * x.real(in, p);
        bulged = true;
        break;
      default: break;
    }
  }
  if (!count_pair) x.fail(in, x.e.line, "group code 90 (the number of vertices) is missing");
  if (static_cast<size_t>(count) != out.v.size())
    x.fail(in, *count_pair, "the entity has " + std::to_string(out.v.size()) + " vertices (group code 10)");
  return out;
}

// Stage: POLYLINE (70: its flags) and its VERTEX entities, up to SEQEND.
DxfPolyline polyline(const Pairs& in, const Entity& x) {
  DxfPolyline out;
  out.e = x.e;
  for (const Pair& p : x.pairs)
    if (p.code == 70) {
      const long long f = x.integer(in, p);
      out.closed = (f & 1) != 0;
      out.mesh = (f & (16 | 64)) != 0;
    }
  return out;
}

void add_vertex(const Pairs& in, const Entity& x, const Entity& poly, DxfPolyline& to) {
  const Pair *px = nullptr, *py = nullptr;
  DxfVertex v;
  for (const Pair& p : x.pairs) {
    if (p.code == 10 || p.code == 20) {
      const Pair*& q = p.code == 10 ? px : py;
      if (q) x.fail(in, p, "given twice");
      q = &p;
    } else if (p.code == 42) {
      v.bulge = poly.nz * x.real(in, p);
    } else if (p.code == 70 && (x.integer(in, p) & 16)) {
      return;  // a spline's frame control point: not on the outline
    }
  }
  if (!px || !py) x.fail(in, x.e.line, "a VERTEX without its point (group codes 10 and 20)");
  v.x = poly.nz * x.real(in, *px);
  v.y = x.real(in, *py);
  v.line = px->line;
  to.v.push_back(v);
}

// Stage: TEXT and MTEXT (1: the text, MTEXT's earlier chunks in 3; 10, 20: where it stands).
DxfText text(const Pairs& in, const Entity& x) {
  DxfText t;
  t.e = x.e;
  std::string chunks, last;
  const Pair *px = nullptr, *py = nullptr;
  for (const Pair& p : x.pairs) {
    if (p.code == 3) chunks += trim(p.value);
    if (p.code == 1) last = std::string(trim(p.value));
    if (p.code == 10 || p.code == 20) {
      const Pair*& q = p.code == 10 ? px : py;
      if (q) x.fail(in, p, "given twice");
      q = &p;
    }
  }
  if (!px || !py) x.fail(in, x.e.line, "no insertion point (group codes 10 and 20)");
  t.x = x.nz * x.real(in, *px);
  t.y = x.real(in, *py);
  t.text = text_utf8(chunks + last, x.e.type == "MTEXT");
  return t;
}

void read_header(Pairs& in, DxfDrawing& d) {
  for (;;) {
    const Pair p = must_next(in, "the HEADER section");
    if (p.code == 0) {
      if (trim(p.value) != "ENDSEC") in.fail(p.line, "'" + printable(std::string(p.value), 40) + "' inside the HEADER section (0 ENDSEC expected)");
      return;
    }
    if (p.code == 9 && trim(p.value) == "$INSUNITS") {
      const Pair v = must_next(in, "the HEADER section");
      long long u = 0;
      if (v.code != 70 || !parse_integer(v.value, -32768, 32767, u))
        in.fail(v.line, "$INSUNITS: group code " + std::to_string(v.code) + " = '" + printable(std::string(v.value), 40) +
                            "': expected group code 70 with a 16-bit integer");
      d.insunits = static_cast<int>(u);
    }
  }
}

void skip_section(Pairs& in, const std::string& name) {
  for (;;) {
    const Pair p = must_next(in, ("the " + name + " section").c_str());
    if (p.code == 0 && trim(p.value) == "ENDSEC") return;
    if (p.code == 0 && (trim(p.value) == "SECTION" || trim(p.value) == "EOF"))
      in.fail(p.line, "0 " + std::string(trim(p.value)) + " inside the " + printable(name, 40) + " section (0 ENDSEC expected)");
  }
}

void read_entities(Pairs& in, DxfDrawing& d) {
  std::optional<Entity> poly_entity;  // the open POLYLINE, until its SEQEND
  std::optional<DxfPolyline> poly;
  bool attribs = false;  // an INSERT's ATTRIB entities, until their SEQEND
  for (;;) {
    const Pair head = must_next(in, "the ENTITIES section");
    if (head.code == 999) continue;  // a comment
    if (head.code != 0) in.fail(head.line, "group code " + std::to_string(head.code) + " where an entity (group code 0) starts");
    const std::string type(trim(head.value));
    if (type == "ENDSEC" || type == "SECTION" || type == "EOF") {
      if (poly_entity) poly_entity->fail(in, poly_entity->e.line, "its vertices end without a SEQEND");
      if (type != "ENDSEC") in.fail(head.line, "0 " + type + " inside the ENTITIES section (0 ENDSEC expected)");
      return;
    }
    const Entity x = read_entity(in, head, "the ENTITIES section");
    if (poly_entity) {
      if (type == "VERTEX") {
        add_vertex(in, x, *poly_entity, *poly);
        continue;
      }
      if (type != "SEQEND")
        poly_entity->fail(in, poly_entity->e.line,
                          "its vertices end without a SEQEND (a " + printable(type, 40) + " at line " + std::to_string(head.line) + ")");
      if (poly_entity->e.paper_space)
        d.skipped.push_back(poly_entity->e);
      else
        d.polylines.push_back(std::move(*poly));
      poly_entity.reset();
      poly.reset();
      continue;
    }
    if (attribs && (type == "ATTRIB" || type == "SEQEND")) {
      attribs = type == "ATTRIB";
      continue;
    }
    attribs = false;
    if (type == "VERTEX" || type == "SEQEND") x.fail(in, x.e.line, "outside a POLYLINE");
    if (type == "POLYLINE") {
      poly_entity = x;
      poly = polyline(in, x);
      continue;
    }
    if (x.e.paper_space) {
      d.skipped.push_back(x.e);
      continue;
    }
    if (type == "LWPOLYLINE")
      d.polylines.push_back(lwpolyline(in, x));
    else if (type == "TEXT" || type == "MTEXT")
      d.texts.push_back(text(in, x));
    else if (type == "LINE")
      d.lines.push_back(x.e);
    else if (type == "CIRCLE" || type == "ARC" || type == "ELLIPSE" || type == "SPLINE" || type == "INSERT") {
      d.curves.push_back(x.e);
      if (type == "INSERT")
        for (const Pair& p : x.pairs) attribs = attribs || (p.code == 66 && x.integer(in, p) == 1);
    } else {
      d.skipped.push_back(x.e);
    }
  }
}

}  // namespace

DxfDrawing read_dxf(const std::string& path) {
  const std::optional<std::string> file = read_text(path);
  if (!file) throw CaseError(path + ": cannot open the drawing");
  const std::string& text = *file;
  if (text.empty()) throw CaseError(path + ": the drawing is empty");
  if (text.rfind("AutoCAD Binary DXF", 0) == 0) throw CaseError(path + ": a binary DXF: save the drawing as ASCII DXF");
  for (size_t i = 0; i < std::min<size_t>(text.size(), 64); ++i) {
    const char ch = text[i];
    if (ch == '\0' || (static_cast<unsigned char>(ch) < 0x20 && ch != '\n' && ch != '\r' && ch != '\t'))
      throw CaseError(path + ": not a DXF drawing (binary content in its first bytes)");
  }
  Pairs in(path, text);
  DxfDrawing d;
  Pair p;
  bool sections = false;
  while (in.next(p)) {
    if (p.code == 999) continue;  // a comment
    const std::string_view v = trim(p.value);
    if (p.code == 0 && v == "EOF") return d;
    if (p.code != 0 || v != "SECTION")
      in.fail(p.line, "group code " + std::to_string(p.code) + " = '" + printable(std::string(v), 40) +
                          "' where a section (0 SECTION) or the end (0 EOF) is expected" + (sections ? "" : ": not a DXF drawing"));
    sections = true;
    const Pair n = must_next(in, "a section's head");
    if (n.code != 2) in.fail(n.line, "a section without its name (group code 2)");
    const std::string name(trim(n.value));
    if (name == "HEADER")
      read_header(in, d);
    else if (name == "ENTITIES")
      read_entities(in, d);
    else
      skip_section(in, name);
  }
  in.fail(in.line_no(), "the drawing ends without 0 EOF (truncated?)");
}

}  // namespace masonry
