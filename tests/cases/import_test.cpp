// Importing drawings (masonry cases import) and drawing cases (masonry cases show). Expected
// values: the generator's or hand-written case that the drawing reproduces (the same capacities on
// both methods), and the refusals' one-line messages naming the drawing, layer and entity.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "cases/dxf.hpp"
#include "cases/generators.hpp"
#include "cases/show.hpp"
#include "common.hpp"
#include "dem/dem.hpp"
#include "prd/prd.hpp"
#include "xml.hpp"

namespace masonry {
namespace {

using test::Scratch;
const std::string kDrawings = std::string(MASONRY_SOURCE_DIR) + "/cases/drawings/";

// An ASCII DXF of LWPOLYLINEs: each {layer, closed, vertices (x, y, bulge)}, units in $INSUNITS.
struct Poly {
  std::string layer;
  bool closed = true;
  std::vector<std::array<double, 3>> v;
};
std::string dxf(const std::vector<Poly>& polys, int insunits = 6, const std::string& extra = "") {
  std::ostringstream o;
  o.precision(17);
  o << "0\nSECTION\n2\nHEADER\n9\n$INSUNITS\n70\n" << insunits << "\n0\nENDSEC\n0\nSECTION\n2\nENTITIES\n";
  int handle = 0x40;
  for (const Poly& p : polys) {
    o << "0\nLWPOLYLINE\n5\n"
      << std::hex << std::uppercase << handle++ << std::dec << "\n8\n"
      << p.layer << "\n90\n"
      << p.v.size() << "\n70\n"
      << (p.closed ? 1 : 0) << "\n";
    for (const auto& x : p.v) {
      o << "10\n" << x[0] << "\n20\n" << x[1] << "\n";
      if (x[2] != 0) o << "42\n" << x[2] << "\n";
    }
  }
  o << extra << "0\nENDSEC\n0\nEOF\n";
  return o.str();
}

Poly rect(const std::string& layer, double x0, double y0, double x1, double y1) {
  return {layer, true, {{x0, y0, 0}, {x1, y0, 0}, {x1, y1, 0}, {x0, y1, 0}}};
}

std::string import_error(const std::string& text, DxfImportOptions o = {}, const std::string& name = "d.dxf") {
  Scratch dir("import");
  const std::string path = (dir.path / name).string();
  test::write(path, text);
  if (!o.density) o.density = 2000;
  try {
    import_dxf(path, o);
  } catch (const CaseError& e) {
    return e.what();
  }
  return "";
}

TEST(CasesImport, TheDrawnTiltingBlockTopplesAsTheCaseFileDoes) {
  // Drawn by hand in millimetres, with a vertex in the middle of the block's base.
  DxfImportOptions o;
  o.layers_file = kDrawings + "layers.json";
  o.merge_file = kDrawings + "tilting-block.fragment.json";
  const DxfImport imp = import_dxf(kDrawings + "tilting-block.dxf", o);
  const Case& c = imp.c;
  ASSERT_EQ(c.blocks.size(), 2u);
  EXPECT_EQ(c.blocks[0].id, "ground");
  EXPECT_TRUE(c.blocks[0].support);
  EXPECT_EQ(c.blocks[1].id, "block");
  EXPECT_NEAR(c.blocks[1].density, 2000, 0);
  EXPECT_NEAR(std::abs(signed_area(c.blocks[1].vertices)), 0.2 * 0.4, 1e-12);  // mm -> m
  const Case ref = load_case(std::string(MASONRY_SOURCE_DIR) + "/cases/tilting-block.json");
  const RunResult p = prd_run(c, PrdSettings::from_case(c)), pr = prd_run(ref, PrdSettings::from_case(ref));
  EXPECT_EQ(p.status, RunStatus::collapse);
  EXPECT_NEAR(p.capacity, pr.capacity, 1e-12);
  EXPECT_LE(p.capacity, std::atan(0.5));  // toppling at atan(b/h), within one step
  EXPECT_GT(p.capacity, std::atan(0.5) - c.motion.step);
  const RunResult d = dem_run(c, DemSettings::from_case(c)), dr = dem_run(ref, DemSettings::from_case(ref));
  EXPECT_EQ(d.status, RunStatus::collapse) << d.message;
  EXPECT_NEAR(d.capacity, dr.capacity, 0.01 * c.motion.step);
}

TEST(CasesImport, ThePointedArchDrawingIsTheStandardScene) {
  // Written by scripts/case-to-dxf.py from cases/pointed-arch.json; motion and settings merged.
  DxfImportOptions o;
  o.density = 1800;
  o.merge_file = kDrawings + "pointed-arch.fragment.json";
  const Case c = import_dxf(kDrawings + "pointed-arch.dxf", o).c;
  const Case ref = standard_case("pointed-arch");
  ASSERT_EQ(c.blocks.size(), ref.blocks.size());
  for (size_t b = 0; b < c.blocks.size(); ++b) {
    EXPECT_EQ(c.blocks[b].id, ref.blocks[b].id);
    EXPECT_EQ(c.blocks[b].support, ref.blocks[b].support);
    ASSERT_EQ(c.blocks[b].vertices.size(), ref.blocks[b].vertices.size());
    for (size_t k = 0; k < c.blocks[b].vertices.size(); ++k) EXPECT_NEAR((c.blocks[b].vertices[k] - ref.blocks[b].vertices[k]).norm(), 0, 1e-12);
  }
  const RunResult p = prd_run(c, PrdSettings::from_case(c)), pr = prd_run(ref, PrdSettings::from_case(ref));
  EXPECT_EQ(p.status, RunStatus::collapse);
  EXPECT_NEAR(p.capacity, pr.capacity, 1e-12);
  EXPECT_NEAR(p.capacity, 0.278, 0.002);  // the paper's PRD
}

TEST(CasesImport, ArcsBecomeChordsWithinTheTolerance) {
  // A block whose top is a half circle (bulge 1 on the top edge, drawn right to left).
  const double tol = 1e-4;
  DxfImportOptions o;
  o.arc_tolerance = tol;
  const std::string text = dxf({rect("SUPPORT", -1, -0.2, 1, 0), {"MASONRY", true, {{-0.5, 0, 0}, {0.5, 0, 0}, {0.5, 0.3, 1}, {-0.5, 0.3, 0}}}});
  Scratch dir("arcs");
  test::write(dir.path / "a.dxf", text);
  o.density = 2000;
  const Case c = import_dxf((dir.path / "a.dxf").string(), o).c;
  const auto& v = c.blocks[1].vertices;
  // Area: the rectangle and a half disc of radius 0.5, less the chords' segments (at most
  // tolerance x perimeter of the arc).
  const double exact = 1.0 * 0.3 + M_PI * 0.25 / 2;
  EXPECT_LT(std::abs(signed_area(v)), exact);
  EXPECT_GT(std::abs(signed_area(v)), exact - tol * M_PI * 0.5);
  for (const Vec2& p : v)
    if (p.y() > 0.3 + 1e-12) {
      EXPECT_NEAR((p - Vec2(0, 0.3)).norm(), 0.5, 1e-12);  // on the arc
    }
}

TEST(CasesImport, RefusalsAreOneLineNamingDrawingLayerAndEntity) {
  const Poly ground = rect("SUPPORT", -2, -0.5, 2, 0);
  struct Bad {
    std::string text, needle;
  };
  const std::vector<Bad> bad = {
      {dxf({ground, {"MASONRY", false, {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}}}), "layer 'MASONRY', entity 41: an open polyline"},
      {dxf({ground, rect("MASONRY", 0, 0, 1, 1), rect("MASONRY", 0.5, 0.5, 1.5, 1.5)}), "overlaps block 'MASONRY-1'"},
      {dxf({ground, rect("MASONRY", 0, 0, 1, 1), rect("MASONRY", 0.5, 0.5, 1.5, 1.5)}), "[drawing: MASONRY-1: layer 'MASONRY', entity 41"},
      {dxf({ground}), "no free block"},
      {dxf({}), "nothing to import"},
      {"", "the drawing is empty"},
      {std::string("AutoCAD Binary DXF\r\n\x1a\0", 22) + std::string(200, '\x01'), "binary DXF"},
      {std::string("\x7f"
                   "ELF\x02\x01\x01\0\0\0",
                   10) +
           std::string(300, '\x03'),
       "not a DXF drawing"},
      {dxf({ground, rect("MASONRY", 0, 0, 1, 1)}, 0), "$INSUNITS"},
      {dxf({ground, rect("MASONRY", 0, 0, 1, 1)}, 6, "0\nCIRCLE\n5\n99\n8\nMASONRY\n10\n0\n20\n2\n40\n0.5\n"),
       "CIRCLE on layer 'MASONRY' (handle 99)"},
  };
  for (const Bad& b : bad) {
    const std::string msg = import_error(b.text);
    EXPECT_NE(msg.find(b.needle), std::string::npos) << b.needle << " | " << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    EXPECT_NE(msg.find("d.dxf"), std::string::npos) << msg;
  }
  // A layer with no convention: not a support, not ignored, and no density given.
  DxfImportOptions none;
  Scratch dir("layers");
  test::write(dir.path / "d.dxf", dxf({ground, rect("WALLS", 0, 0, 1, 1)}));
  try {
    import_dxf((dir.path / "d.dxf").string(), none);
    ADD_FAILURE() << "imported without a density";
  } catch (const CaseError& e) {
    EXPECT_NE(std::string(e.what()).find("layer 'WALLS', entity 41: the layer follows no convention"), std::string::npos) << e.what();
  }
  // Corrupt content after a valid start: refused or imported, never a crash.
  std::string corrupt = dxf({ground, rect("MASONRY", 0, 0, 1, 1)});
  for (size_t k = 40; k < corrupt.size(); k += 7) corrupt[k] = static_cast<char>('0' + k % 43);
  (void)import_error(corrupt);
}

// A --density given must be a density: 0 was taken for "not given" (then "the layer follows no
// convention ... no density"), and nan or inf read "--density n/a". Each is refused quoting it.
TEST(CasesImport, ADensityGivenMustBePositiveAndFinite) {
  const std::string text = dxf({rect("SUPPORT", -2, -0.5, 2, 0), rect("MASONRY", 0, 0, 1, 1)});
  for (const auto& [x, shown] :
       std::vector<std::pair<double, std::string>>{{0.0, "0"}, {-1.0, "-1"}, {NAN, "nan"}, {INFINITY, "inf"}, {-INFINITY, "-inf"}}) {
    DxfImportOptions o;
    o.density = x;
    const std::string msg = import_error(text, o);
    EXPECT_NE(msg.find("d.dxf: --density " + shown + ": must be a density in kg/m^3, positive and finite"), std::string::npos) << msg;
  }
  // On the command line too, where 0 was the "not given" of the option's slot.
  Scratch dir("density");
  test::write(dir.path / "d.dxf", text);
  const std::string err = (dir.path / "err").string();
  for (const std::string v : {"0", "nan"}) {
    EXPECT_EQ(test::run(std::string(MASONRY_EXE) + " cases import " + (dir.path / "d.dxf").string() + " --density " + v + " --out " +
                        (dir.path / "c.json").string() + " 2>" + err),
              2);
    const std::string e = test::read(err);
    EXPECT_NE(e.find("--density " + v + ": must be a density"), std::string::npos) << e;
    EXPECT_EQ(e.find('\n'), e.size() - 1) << e;
  }
}

// The drawing of a block on the ground, the block an LWPOLYLINE (handle 2C, layer MASONRY) whose
// group codes after its layer are given as text.
std::string block_on_ground(const std::string& codes) {
  return dxf({rect("SUPPORT", -2, -0.5, 2, 0)}, 6, "0\nLWPOLYLINE\n5\n2C\n8\nMASONRY\n" + codes);
}
const std::string kSquare = "10\n0\n20\n0\n10\n1\n20\n0\n10\n1\n20\n1\n10\n0\n20\n1\n";

// A drawing that breaks the DXF reference is refused in one line naming the drawing, its line,
// the entity's handle and the group code: dxflib crashed on the counts (SIGSEGV at 99999999999
// vertices, a double free at 2147483647) and read "XYZ", "nan" and "abc" as 0, "1,5" as 1.5 and
// "0.4 junk" as 0.4; an empty value or a missing y silently changed the polygon.
TEST(CasesImport, MalformedDrawingsAreRefusedNamingTheHandleAndGroupCode) {
  struct Bad {
    std::string codes, needle;
  };
  const auto square_with = [](const std::string& from, const std::string& to) {
    std::string q = kSquare;
    q.replace(q.find(from), from.size(), to);
    return q;
  };
  const std::vector<Bad> bad = {
      {"90\n99999999999\n70\n1\n" + kSquare, "group code 90 = '99999999999': not a 32-bit integer"},
      {"90\n2147483647\n70\n1\n" + kSquare, "group code 90 = '2147483647': the entity has 4 vertices"},
      {"90\n-4\n70\n1\n" + kSquare, "group code 90 = '-4': a negative number of vertices"},
      {"70\n1\n" + kSquare, "group code 90 (the number of vertices) is missing"},
      {"90\n4\n70\n1\n" + square_with("10\n1\n20\n1\n", "10\nXYZ\n20\n1\n"), "group code 10 = 'XYZ': not a real number"},
      {"90\n4\n70\n1\n" + square_with("10\n1\n20\n1\n", "10\nnan\n20\n1\n"), "group code 10 = 'nan': not a real number"},
      {"90\n4\n70\n1\n" + square_with("10\n1\n20\n1\n", "10\n1\n20\nabc\n"), "group code 20 = 'abc': not a real number"},
      {"90\n4\n70\n1\n" + square_with("10\n1\n20\n1\n", "10\n1\n20\n\n"), "group code 20 = '': not a real number"},
      {"90\n4\n70\n1\n" + square_with("10\n1\n20\n1\n", "10\n1,5\n20\n1\n"), "group code 10 = '1,5': not a real number"},
      {"90\n4\n70\n1\n" + square_with("10\n1\n20\n1\n", "10\n0.4  junk\n20\n1\n"), "group code 10 = '0.4  junk': not a real number"},
      {"90\n4\n70\n1\n" + square_with("10\n1\n20\n1\n", "10\n1e999\n20\n1\n"), "group code 10 = '1e999': not a real number"},
      {"90\n4\n70\n1\n" + square_with("10\n1\n20\n1\n", "10\n1\n"), "group code 10 = '1': a vertex's x without its y"},
      {"90\n4\n70\n1\n" + square_with("10\n1\n20\n1\n", "20\n1\n10\n1\n"), "a vertex's y without its x"},
      {"90\n4\n70\n1.0\n" + kSquare, "group code 70 = '1.0': not a 16-bit integer"},
      {"90\n4\n70\n1\n" + square_with("10\n0\n20\n0\n", "42\n0.5\n10\n0\n20\n0\n"), "group code 42 = '0.5': a bulge before the first vertex"},
      {"90\n4\n70\n1\n" + square_with("10\n1\n20\n1\n", "10\n1e9\n20\n1\n"), "group codes 10/20: a vertex beyond 1e5 m from the origin"},
      {"90\n4\n70\n1\n" + square_with("10\n1\n20\n1\n", "10\n1\n20\n1\n42\n1e15\n"), "group code 42 = 1e+15: the arc needs more than"},
      {"90\n4\n70\n1\n210\n0\n220\n1\n230\n0\n" + kSquare, "group codes 210/220/230: drawn in another plane than x-y"},
      {"90\n4\n70\n1\n" + kSquare + "abc\nx\n", "'abc' is not a group code"},
      {"90\n4\n70\n1\n" + kSquare + "9999\nx\n", "'9999' is not a group code"},
      {"90\n4\n70\n1\n" + kSquare + "0\nVERTEX\n5\n2D\n10\n0\n20\n0\n", "VERTEX (handle 2D, layer '0'): outside a POLYLINE"},
      {"90\n4\n70\n1\n" + kSquare + "0\nPOLYLINE\n5\n2E\n8\nMASONRY\n70\n1\n0\nVERTEX\n10\n0\n20\n2\n",
       "POLYLINE (handle 2E, layer 'MASONRY'): its vertices end without a SEQEND"},
  };
  for (const Bad& b : bad) {
    const std::string msg = import_error(block_on_ground(b.codes));
    EXPECT_NE(msg.find(b.needle), std::string::npos) << b.needle << " | " << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    EXPECT_NE(msg.find("d.dxf:"), std::string::npos) << msg;
  }
  // Each refusal about the entity names its handle, its layer and the line in the file.
  const std::string text = block_on_ground("90\n4\n70\n1\n" + square_with("10\n1\n20\n1\n", "10\nXYZ\n20\n1\n"));
  const std::string msg = import_error(text);
  EXPECT_NE(msg.find("LWPOLYLINE (handle 2C, layer 'MASONRY')"), std::string::npos) << msg;
  const auto line = std::count(text.begin(), text.begin() + static_cast<long>(text.find("XYZ")), '\n');  // the line of its group code
  EXPECT_NE(msg.find("d.dxf:" + std::to_string(line) + ": "), std::string::npos) << msg;
  // Cut short anywhere: refused, never read as far as it goes.
  const std::string whole = block_on_ground("90\n4\n70\n1\n" + kSquare);
  for (const std::string& cut : {whole.substr(0, whole.rfind("0\nEOF")), whole.substr(0, whole.rfind("ENDSEC")), whole.substr(0, whole.size() / 2)}) {
    const std::string m = import_error(cut);
    EXPECT_NE(m.find("truncated"), std::string::npos) << m;
  }
  // A NUL byte inside the file is binary content, not text.
  std::string nul = whole;
  nul[whole.find("MASONRY")] = '\0';
  EXPECT_NE(import_error(nul).find("binary content"), std::string::npos);
}

// What the reference allows is read as it means: blanks around numbers, a sign, a bare decimal
// point, an exponent, CR LF line ends, comments; and the square is the square.
TEST(CasesImport, WellFormedNumbersInAnyWrittenFormImport) {
  const std::string q = "10\n  0.0  \n20\n+0\n10\n1.\n20\n-0.0\n10\n1E0\n20\n.1e1\n10\n0\n20\n1\n";
  std::string text = block_on_ground("999\nA comment\n90\n     4\n70\n     1\n" + q);
  std::string crlf;
  for (char ch : text) crlf += ch == '\n' ? std::string("\r\n") : std::string(1, ch);
  for (const std::string& t : {text, crlf}) {
    Scratch dir("forms");
    test::write(dir.path / "f.dxf", t);
    DxfImportOptions o;
    o.density = 2000;
    const Case c = import_dxf((dir.path / "f.dxf").string(), o).c;
    ASSERT_EQ(c.blocks.size(), 2u);
    EXPECT_EQ(c.blocks[1].vertices.size(), 4u);
    EXPECT_NEAR(std::abs(signed_area(c.blocks[1].vertices)), 1.0, 1e-15);
  }
}

// A polyline drawn from the other side (extrusion direction 0, 0, -1, as a CAD program's mirror
// leaves it) has its x mirrored in the drawing's frame (DXF's arbitrary axis algorithm), and
// its bulges turn the other way: it imports where it is seen, the same block as drawn plainly.
TEST(CasesImport, AnEntitySeenFromBelowIsMirroredBack) {
  const Poly plain{"MASONRY", true, {{0, 0, 0}, {1, 0, 0}, {1, 0.5, 0.4}, {0, 0.5, 0}}};
  std::string mirrored = "0\nLWPOLYLINE\n5\n2C\n8\nMASONRY\n90\n4\n70\n1\n";
  for (const auto& v : plain.v) {
    mirrored += "10\n" + std::to_string(-v[0]) + "\n20\n" + std::to_string(v[1]) + "\n";
    if (v[2] != 0) mirrored += "42\n" + std::to_string(-v[2]) + "\n";
  }
  mirrored += "210\n0\n220\n0\n230\n-1\n";
  DxfImportOptions o;
  o.density = 2000;
  Scratch dir("mirror");
  test::write(dir.path / "a.dxf", dxf({rect("SUPPORT", -2, -0.5, 2, 0), plain}));
  test::write(dir.path / "b.dxf", dxf({rect("SUPPORT", -2, -0.5, 2, 0)}, 6, mirrored));
  const Case a = import_dxf((dir.path / "a.dxf").string(), o).c, b = import_dxf((dir.path / "b.dxf").string(), o).c;
  ASSERT_EQ(a.blocks[1].vertices.size(), b.blocks[1].vertices.size());
  for (size_t k = 0; k < a.blocks[1].vertices.size(); ++k) EXPECT_NEAR((a.blocks[1].vertices[k] - b.blocks[1].vertices[k]).norm(), 0, 1e-6);
}

// An arc of more than a half circle (bulge above 1): its centre lies beyond the chord, and every
// chord vertex lies on the circle. Three quarters of the unit circle from (1, 0) round to
// (0, -1), counter-clockwise: bulge tan(270 deg / 4).
TEST(CasesImport, ArcsBeyondAHalfCircleStayOnTheirCircle) {
  const double bulge = std::tan(3 * M_PI / 8);
  DxfImportOptions o;
  o.density = 2000;
  o.arc_tolerance = 1e-4;
  Scratch dir("arc270");
  test::write(dir.path / "a.dxf", dxf({rect("SUPPORT", -2, -1.5, 2, -1), {"MASONRY", true, {{1, 0, bulge}, {0, -1, 0}, {1, -1, 0}}}}));
  const Case c = import_dxf((dir.path / "a.dxf").string(), o).c;
  const auto& v = c.blocks[1].vertices;
  int on_arc = 0;
  for (const Vec2& p : v)
    if ((p - Vec2(1, -1)).norm() > 1e-12) {
      EXPECT_NEAR(p.norm(), 1.0, 1e-12) << p.transpose();
      ++on_arc;
    }
  EXPECT_GT(on_arc, 20);
  // Three quarters of the disc and the triangle (0,-1), (1,-1), (1,0) outside it, less the chords' segments.
  const double exact = 0.75 * M_PI + 0.5 + 0.5;
  EXPECT_LT(std::abs(signed_area(v)), exact);
  EXPECT_GT(std::abs(signed_area(v)), exact - 1e-4 * 1.5 * M_PI);
}

// Texts name blocks in UTF-8 whatever the drawing's age: 8-bit code page text (Latin-1 here) and
// AutoCAD's \U+XXXX escapes are converted.
TEST(CasesImport, TextIsReadAsUtf8) {
  const std::string texts =
      "0\nTEXT\n5\n50\n8\nMASONRY\n10\n0.5\n20\n0.5\n1\npi\xe8"
      "ce\n"
      "0\nTEXT\n5\n51\n8\nSUPPORT\n10\n0\n20\n-0.2\n1\nsol \\U+00E9\\U+20AC\n";
  Scratch dir("utf8");
  test::write(dir.path / "t.dxf", dxf({rect("SUPPORT", -2, -0.5, 2, 0), rect("MASONRY", 0, 0, 1, 1)}, 6, texts));
  DxfImportOptions o;
  o.density = 2000;
  const Case c = import_dxf((dir.path / "t.dxf").string(), o).c;
  EXPECT_EQ(c.blocks[0].id, "sol \xc3\xa9\xe2\x82\xac");
  EXPECT_EQ(c.blocks[1].id,
            "pi\xc3\xa8"
            "ce");
}

// An MTEXT's inline formatting codes are how it looks, not its id: AutoCAD writes
// `\A1;{\fArial|b1;Pier\P2}` for "Pier" over "2", and the id kept it verbatim. A TEXT has no such
// codes: its backslashes stay.
TEST(CasesImport, MtextFormattingCodesAreNotPartOfTheId) {
  const std::string texts =
      "0\nMTEXT\n5\n50\n8\nMASONRY\n10\n0.5\n20\n0.5\n1\n\\A1;{\\fArial|b1;Pier\\P2}\n"
      "0\nMTEXT\n5\n51\n8\nMASONRY\n10\n1.5\n20\n0.5\n3\n{\\H0.5x;\\C1;\\Q15;\\W0.8;\\T1.1;\\c255;\\pxqc;arch \\{1\\}\\~\\LA\\l\\O\\o\\K\\k\n"
      "1\n\\~\\P\\Ppi\\U+00E8ce\\\\x}\n"
      "0\nTEXT\n5\n52\n8\nSUPPORT\n10\n0\n20\n-0.2\n1\nsol\\P1\n";
  Scratch dir("mtext");
  test::write(dir.path / "m.dxf", dxf({rect("SUPPORT", -2, -0.5, 3, 0), rect("MASONRY", 0, 0, 1, 1), rect("MASONRY", 1, 0, 2, 1)}, 6, texts));
  DxfImportOptions o;
  o.density = 2000;
  const Case c = import_dxf((dir.path / "m.dxf").string(), o).c;
  EXPECT_EQ(c.blocks[0].id, "sol\\P1");
  EXPECT_EQ(c.blocks[1].id, "Pier 2");
  EXPECT_EQ(c.blocks[2].id,
            "arch {1} A pi\xc3\xa8"
            "ce\\x");
}

// Ids may not hold '/' or ':' (the case loader's rule: joints are named BLOCK/BLOCK, corners
// BLOCK/BLOCK:A), and an MTEXT's stacked fraction \S1^2; reads 1/2: the import refuses such an
// id, naming the text entity that gives it (its line and handle) and the block it names; a
// block named after a layer whose name holds one is refused naming the layer.
TEST(CasesImport, AnIdHoldingASeparatorOfJointNamesIsRefusedWhereTheDrawingGivesIt) {
  const std::string stacked = "0\nMTEXT\n5\n50\n8\nMASONRY\n10\n0.5\n20\n0.5\n1\nPier \\S1^2;\n";
  const std::string text = dxf({rect("SUPPORT", -2, -0.5, 3, 0), rect("MASONRY", 0, 0, 1, 1)}, 6, stacked);
  // The entity's line is that of its group code 0, the line before "MTEXT".
  const long line = std::count(text.begin(), text.begin() + long(text.find("\nMTEXT\n")), '\n') + 1;
  std::string msg = import_error(text);
  EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  EXPECT_NE(msg.find("d.dxf:" + std::to_string(line) +
                     ": MTEXT (handle 50, layer 'MASONRY'): the id 'Pier 1/2' it gives (the block of layer 'MASONRY', entity 41) holds '/'"),
            std::string::npos)
      << msg;
  msg =
      import_error(dxf({rect("SUPPORT", -2, -0.5, 3, 0), rect("MASONRY", 0, 0, 1, 1)}, 6, "0\nTEXT\n5\n51\n8\nMASONRY\n10\n0.5\n20\n0.5\n1\nv:1\n"));
  EXPECT_NE(msg.find("TEXT (handle 51, layer 'MASONRY'): the id 'v:1' it gives (the block of layer 'MASONRY', entity 41) holds ':'"),
            std::string::npos)
      << msg;
  msg = import_error(dxf({rect("SUPPORT", -2, -0.5, 3, 0), rect("WALL/EAST", 0, 0, 1, 1)}));
  EXPECT_NE(msg.find("d.dxf: layer 'WALL/EAST', entity 41: the id 'WALL/EAST-1' made from the layer's name holds '/'"), std::string::npos) << msg;
}

// DXF writes entity types in upper case and the reader takes them as written: a 'lwpolyline' was
// dropped with no note (HATCH gets "1 HATCH ignored"), and a drawing of nothing else ended "no
// free block" with nothing to say why. The note names it, and a refusal carries the note.
TEST(CasesImport, AnEntityTypeInLowerCaseIsNamedInTheNotes) {
  const std::string lower = "0\nlwpolyline\n5\n60\n8\nMASONRY\n90\n4\n70\n1\n10\n2\n20\n0\n10\n3\n20\n0\n10\n3\n20\n1\n10\n2\n20\n1\n";
  const std::string note = "1 lwpolyline ignored (blocks are closed polylines; 'lwpolyline' is not an entity type: DXF writes them in upper case)";
  Scratch dir("lowercase");
  test::write(dir.path / "l.dxf", dxf({rect("SUPPORT", -2, -0.5, 4, 0), rect("MASONRY", 0, 0, 1, 1)}, 6, lower));
  DxfImportOptions o;
  o.density = 2000;
  const DxfImport imp = import_dxf((dir.path / "l.dxf").string(), o);
  EXPECT_EQ(imp.c.blocks.size(), 2u);
  EXPECT_NE(std::find(imp.notes.begin(), imp.notes.end(), note), imp.notes.end()) << testing::PrintToString(imp.notes);
  const std::string msg = import_error(dxf({rect("SUPPORT", -2, -0.5, 4, 0)}, 6, lower));
  EXPECT_NE(msg.find("no free block: every block is a support [" + note + "]"), std::string::npos) << msg;
}

// A text outside every block named nothing and said nothing (the block it was meant for became
// MASONRY-1): each is a note, the first five one by one.
TEST(CasesImport, ATextInNoBlockIsANote) {
  std::string texts = "0\nTEXT\n5\n70\n8\nMASONRY\n10\n5\n20\n5\n1\nlost\n";
  for (int k = 0; k < 6; ++k) texts += "0\nMTEXT\n5\n" + std::to_string(80 + k) + "\n8\nNOTES\n10\n-5\n20\n" + std::to_string(k) + "\n1\nnote\n";
  Scratch dir("stray");
  test::write(dir.path / "s.dxf", dxf({rect("SUPPORT", -2, -0.5, 2, 0), rect("MASONRY", 0, 0, 1, 1)}, 6, texts));
  DxfImportOptions o;
  o.density = 2000;
  const DxfImport imp = import_dxf((dir.path / "s.dxf").string(), o);
  EXPECT_EQ(imp.c.blocks[1].id, "MASONRY-1");
  const std::vector<std::string> expected = {
      "TEXT 'lost' at (5, 5) (handle 70, layer 'MASONRY') lies in no block: ignored",
      "MTEXT 'note' at (-5, 0) (handle 80, layer 'NOTES') lies in no block: ignored",
      "MTEXT 'note' at (-5, 3) (handle 83, layer 'NOTES') lies in no block: ignored",
      "2 more texts lie in no block: ignored",
  };
  for (const std::string& n : expected)
    EXPECT_NE(std::find(imp.notes.begin(), imp.notes.end(), n), imp.notes.end()) << n << " | " << testing::PrintToString(imp.notes);
  EXPECT_EQ(imp.notes.size(), 6u) << testing::PrintToString(imp.notes);
}

// A wall drawn as a stack of bricks, each named by a text inside it: every brick gets its name
// and the joints are those of the bond (each brick on the one below or the ground, and beside
// its neighbours in the course): C x R + (C - 1) x R.
TEST(CasesImport, ABrickWallDrawingImportsEveryBrickWithItsName) {
  const int courses = 12, bricks = 15;
  std::vector<Poly> polys = {rect("SUPPORT", -1, -0.3, bricks * 0.25 + 1, 0)};
  std::string texts;
  int handle = 0x1000;
  for (int r = 0; r < courses; ++r)
    for (int k = 0; k < bricks; ++k) {
      polys.push_back(rect("MASONRY", k * 0.25, r * 0.125, (k + 1) * 0.25, (r + 1) * 0.125));
      std::ostringstream t;
      t << "0\nTEXT\n5\n"
        << std::hex << handle++ << std::dec << "\n8\nMASONRY\n10\n"
        << (k + 0.5) * 0.25 << "\n20\n"
        << (r + 0.5) * 0.125 << "\n1\nb" << r << "-" << k << "\n";
      texts += t.str();
    }
  Scratch dir("wall");
  test::write(dir.path / "w.dxf", dxf(polys, 6, texts));
  DxfImportOptions o;
  o.density = 2000;
  const Case c = import_dxf((dir.path / "w.dxf").string(), o).c;
  ASSERT_EQ(c.blocks.size(), static_cast<size_t>(1 + courses * bricks));
  for (int r = 0; r < courses; ++r)
    for (int k = 0; k < bricks; ++k) {
      std::ostringstream id;
      id << "b" << r << "-" << k;
      EXPECT_EQ(c.blocks[1 + r * bricks + k].id, id.str());
    }
  EXPECT_EQ(detect_interfaces(c, c.prd.contact_tolerance).size(), static_cast<size_t>(bricks * courses + (bricks - 1) * courses));
}

TEST(CasesImport, DraftingGapsAreReportedAndSnapped) {
  // The block hovers 0.5 mm above the ground: no joint, so the case is refused with the gap named.
  const std::string text = dxf({rect("SUPPORT", -2, -0.5, 2, 0), rect("MASONRY", 0, 0.0005, 1, 1)});
  const std::string msg = import_error(text);
  EXPECT_NE(msg.find("touches no other block"), std::string::npos) << msg;
  EXPECT_NE(msg.find("almost meet"), std::string::npos) << msg;
  EXPECT_NE(msg.find("0.5 mm"), std::string::npos) << msg;
  // --snap 1 mm closes it: the block stands on the ground, one joint.
  Scratch dir("snap");
  test::write(dir.path / "g.dxf", text);
  DxfImportOptions o;
  o.density = 2000;
  o.snap = 1e-3;
  const DxfImport imp = import_dxf((dir.path / "g.dxf").string(), o);
  EXPECT_EQ(detect_interfaces(imp.c, imp.c.prd.contact_tolerance).size(), 1u);
  EXPECT_TRUE(prd_check(imp.c, imp.c.prd.contact_tolerance).stable);
  bool told = false;
  for (const std::string& n : imp.notes) told = told || n.find("snapped") != std::string::npos;
  EXPECT_TRUE(told);
}

// A fragment's fields are checked as the case's, and a refusal names the file that holds the bad
// field first: the fragment for its settings and its loads (they named the drawing only), the
// drawing for its blocks. A contact tolerance out of range is refused before gaps are measured with it: a
// negative one called two blocks that meet exactly "a gap of 5.55e-14 mm".
TEST(CasesImport, AFragmentsErrorsNameTheFragment) {
  Scratch dir("fragment");
  const std::string drawing = (dir.path / "d.dxf").string(), frag = (dir.path / "f.json").string();
  test::write(drawing, dxf({rect("SUPPORT", -2, -0.5, 2, 0), rect("MASONRY", 0, 0, 0.3, 0.4), rect("MASONRY", 0, 0.4, 0.3, 0.8)}));
  DxfImportOptions o;
  o.density = 2000;
  o.merge_file = frag;
  const auto refusal = [&](const std::string& fragment) {
    test::write(frag, fragment);
    try {
      import_dxf(drawing, o);
    } catch (const CaseError& e) {
      return std::string(e.what());
    }
    return std::string("imported");
  };
  struct Bad {
    std::string fragment, message;
  };
  for (const Bad& b : std::vector<Bad>{
           {R"({"prd": {"contact_tolerance": -1}})", frag + ": prd: field 'contact_tolerance' = -1 is outside"},
           {R"({"loads": [{"block": "b9", "force": [0, -10]}]})", frag + ": load #0: field 'block': no block 'b9'"},
           {R"({"motion": {"supports": [{"block": "MASONRY-1", "rotation": 1}]}})",
            frag + ": motion of block 'MASONRY-1': field 'block': not a support"},
           {R"({"gravity": 0})", frag + ": case: field 'gravity': nothing loads the structure"},
           {R"({"prd": {"contact_tolerance": 1}})", frag + ": prd: field 'contact_tolerance'"},
       }) {
    const std::string msg = refusal(b.fragment);
    EXPECT_EQ(msg.rfind(b.message, 0), 0u) << b.fragment << " | " << msg;
    // The drawing is named after it: the fragment names its blocks (every refusal names the drawing, tests/cases/fuzz_test.cpp).
    const size_t merged = msg.find(" [merged into " + drawing + "]");
    EXPECT_NE(merged, std::string::npos) << msg;
    EXPECT_EQ(msg.find(drawing), merged + 14) << msg;
    EXPECT_EQ(msg.find("almost meet"), std::string::npos) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  }
  // The drawing's own fault names the drawing, fragment or not: a block floating 0.5 mm high.
  test::write(drawing, dxf({rect("SUPPORT", -2, -0.5, 2, 0), rect("MASONRY", 0, 0.0005, 0.3, 0.4)}));
  const std::string msg = refusal(R"({"prd": {"contact_tolerance": 1e-4}})");
  EXPECT_EQ(msg.rfind(drawing + ": block 'MASONRY-1'", 0), 0u) << msg;
  EXPECT_NE(msg.find("almost meet"), std::string::npos) << msg;
  // Unless the fragment's tolerance closes that gap: then its own bad load is the fault.
  const std::string load = refusal(R"({"prd": {"contact_tolerance": 1e-3}, "loads": [{"block": "b9", "force": [0, -10]}]})");
  EXPECT_EQ(load.rfind(frag + ": load #0: field 'block': no block 'b9' [merged into " + drawing + "]", 0), 0u) << load;
}

// A small well-formedness check: every tag closed in order, attributes quoted, no raw & or <.
bool well_formed(const std::string& x, std::string& why) {
  std::vector<std::string> open;
  size_t i = 0;
  if (x.rfind("<?xml", 0) == 0) i = x.find("?>") + 2;
  while (i < x.size()) {
    if (x[i] == '&') {
      const size_t semi = x.find(';', i);
      const std::string ent = x.substr(i, semi - i + 1);
      if (ent != "&amp;" && ent != "&lt;" && ent != "&gt;" && ent != "&quot;" && ent != "&apos;") return why = "entity " + ent, false;
      i = semi + 1;
      continue;
    }
    if (x[i] != '<') {
      ++i;
      continue;
    }
    const size_t end = x.find('>', i);
    if (end == std::string::npos) return why = "unclosed tag", false;
    std::string tag = x.substr(i + 1, end - i - 1);
    if (tag.find('<') != std::string::npos) return why = "< inside a tag", false;
    if (std::count(tag.begin(), tag.end(), '"') % 2) return why = "unbalanced quotes in <" + tag + ">", false;
    if (tag[0] == '/') {
      if (open.empty() || open.back() != tag.substr(1))
        return why = "</" + tag.substr(1) + "> closes " + (open.empty() ? "nothing" : open.back()), false;
      open.pop_back();
    } else if (tag.back() != '/') {
      open.push_back(tag.substr(0, tag.find_first_of(" \n")));
    }
    i = end + 1;
  }
  if (!open.empty()) return why = "<" + open.back() + "> never closed", false;
  return true;
}

TEST(CasesShow, SvgIsWellFormedWithOnePolygonPerBlock) {
  Case c = standard_case("pointed-arch");
  c.blocks[3].id = "v<3> & \"friends\"\x1b";  // markup and a control character in an id stay text
  Load l;
  l.block = 5;
  l.force = Vec2(0, -100);
  l.point = centroid(c.blocks[5].vertices);
  c.loads.push_back(l);
  c.blocks[4].id = "v4 \xff\xfe \xef\xbf\xbf";  // bytes that are not UTF-8, and U+FFFF
  const std::string svg = case_svg(c);
  std::string why;
  EXPECT_TRUE(well_formed(svg, why)) << why;
  EXPECT_TRUE(test::xml_well_formed(svg, why)) << why;
  auto count = [&](const std::string& what) {
    size_t n = 0;
    for (size_t at = svg.find(what); at != std::string::npos; at = svg.find(what, at + 1)) ++n;
    return n;
  };
  EXPECT_EQ(count("<polygon class=\"block"), c.blocks.size());
  EXPECT_EQ(count("class=\"block support\""), 2u);
  EXPECT_EQ(count("<line class=\"joint\""), detect_interfaces(c, c.prd.contact_tolerance).size());
  EXPECT_NE(svg.find("class=\"load\""), std::string::npos);
  EXPECT_NE(svg.find("class=\"motion\""), std::string::npos);
  EXPECT_NE(svg.find("v&lt;3&gt; &amp; &quot;friends&quot;\\x1b"), std::string::npos);
}

TEST(CasesShow, CommandWritesTheFile) {
  Scratch dir("show");
  const std::string out = (dir.path / "c.svg").string();
  EXPECT_EQ(test::run(std::string(MASONRY_EXE) + " cases show " + MASONRY_SOURCE_DIR + "/cases/tilting-block.json --svg " + out + " 2>/dev/null"), 0);
  std::string why;
  EXPECT_TRUE(well_formed(test::read(out), why)) << why;
  // Import through the command, with the notes on stderr.
  const std::string cs = (dir.path / "t.json").string(), err = (dir.path / "err").string();
  EXPECT_EQ(test::run(std::string(MASONRY_EXE) + " cases import " + kDrawings + "tilting-block.dxf --layers " + kDrawings + "layers.json --merge " +
                      kDrawings + "tilting-block.fragment.json --out " + cs + " 2>" + err),
            0);
  EXPECT_EQ(load_case(cs).blocks.size(), 2u);
  EXPECT_EQ(test::run(std::string(MASONRY_EXE) + " cases import " + kDrawings + "tilting-block.dxf --out " + cs + " 2>" + err), 2);
  const std::string e = test::read(err);
  EXPECT_NE(e.find("tilting-block.dxf: layer 'MASONRY', entity 2C"), std::string::npos) << e;
}

// `--svg -` is standard output, as `masonry cases NAME --out -` is: it wrote a file named "-".
TEST(CasesShow, SvgDashWritesToStandardOutput) {
  Scratch dir("show-stdout");
  const std::string out = (dir.path / "out.svg").string(), err = (dir.path / "err").string();
  EXPECT_EQ(test::run("cd " + dir.path.string() + " && " + MASONRY_EXE + " cases show " + MASONRY_SOURCE_DIR + "/cases/tilting-block.json --svg - >" +
                      out + " 2>" + err),
            0);
  std::string why;
  EXPECT_TRUE(test::xml_well_formed(test::read(out), why)) << why;
  EXPECT_NE(test::read(out).find("<svg"), std::string::npos);
  EXPECT_EQ(test::read(err), "");
  EXPECT_FALSE(std::filesystem::exists(dir.path / "-"));
}

}  // namespace
}  // namespace masonry
