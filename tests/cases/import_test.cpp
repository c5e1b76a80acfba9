// Importing drawings (masonry cases import) and drawing cases (masonry cases show). Expected
// values: the generator's or hand-written case that the drawing reproduces (the same capacities on
// both methods), and the refusals' one-line messages naming the drawing, layer and entity.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "common.hpp"
#include "dem/dem.hpp"
#include "cases/dxf.hpp"
#include "cases/generators.hpp"
#include "prd/prd.hpp"
#include "cases/show.hpp"

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
  o << "0\nSECTION\n2\nHEADER\n9\n$INSUNITS\n70\n" << insunits << "\n0\nENDSEC\n0\nSECTION\n2\nENTITIES\n";
  int handle = 0x40;
  for (const Poly& p : polys) {
    o << "0\nLWPOLYLINE\n5\n" << std::hex << std::uppercase << handle++ << std::dec << "\n8\n" << p.layer << "\n90\n" << p.v.size()
      << "\n70\n" << (p.closed ? 1 : 0) << "\n";
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
  if (o.density == 0) o.density = 2000;
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
      {std::string("\x7f" "ELF\x02\x01\x01\0\0\0", 10) + std::string(300, '\x03'), "not a DXF drawing"},
      {dxf({ground, rect("MASONRY", 0, 0, 1, 1)}, 0), "$INSUNITS"},
      {dxf({ground, rect("MASONRY", 0, 0, 1, 1)}, 6, "0\nCIRCLE\n5\n99\n8\nMASONRY\n10\n0\n20\n2\n40\n0.5\n"), "CIRCLE on layer 'MASONRY' (handle 99)"},
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
      if (open.empty() || open.back() != tag.substr(1)) return why = "</" + tag.substr(1) + "> closes " + (open.empty() ? "nothing" : open.back()), false;
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
  const std::string svg = case_svg(c);
  std::string why;
  EXPECT_TRUE(well_formed(svg, why)) << why;
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
  EXPECT_EQ(test::run(std::string(MASONRY_EXE) + " cases show " + MASONRY_SOURCE_DIR + "/cases/tilting-block.json --svg " + out +
                      " 2>/dev/null"),
            0);
  std::string why;
  EXPECT_TRUE(well_formed(test::read(out), why)) << why;
  // Import through the command, with the notes on stderr.
  const std::string cs = (dir.path / "t.json").string(), err = (dir.path / "err").string();
  EXPECT_EQ(test::run(std::string(MASONRY_EXE) + " cases import " + kDrawings + "tilting-block.dxf --layers " + kDrawings +
                      "layers.json --merge " + kDrawings + "tilting-block.fragment.json --out " + cs + " 2>" + err),
            0);
  EXPECT_EQ(load_case(cs).blocks.size(), 2u);
  EXPECT_EQ(test::run(std::string(MASONRY_EXE) + " cases import " + kDrawings + "tilting-block.dxf --out " + cs + " 2>" + err), 2);
  const std::string e = test::read(err);
  EXPECT_NE(e.find("tilting-block.dxf: layer 'MASONRY', entity 2C"), std::string::npos) << e;
}

}  // namespace
}  // namespace masonry
