// Reading an ASCII DXF drawing into what the import needs (cases/dxf.cpp): closed-polyline
// candidates, texts, $INSUNITS and what cannot be a block. Our own reader, not dxflib: dxflib
// trusts a polyline's vertex count (a count of 2^31 - 1 crashed it) and reads any text as a
// number ("abc" and "nan" as 0, "1,5" as 1.5, "0.4 junk" as 0.4) without telling its caller, so a
// malformed drawing became a wrong case. Here every group code's value is checked against its
// type in the DXF reference (strings, reals, 16-, 32- and 64-bit integers), every count against
// what follows it, and a drawing that breaks the reference is refused with one line naming the
// file's line, the entity's type, handle and layer, and the group code.
#pragma once

#include <string>
#include <vector>

namespace masonry {

struct DxfVertex {
  double x = 0, y = 0, bulge = 0;  // drawing units, in the world frame (an entity's mirrored frame taken back)
  size_t line = 0;                 // the file line of its group code 10
};

// An entity as messages name it: "LWPOLYLINE (handle 2C, layer 'MASONRY')".
struct DxfEntity {
  std::string type, handle, layer;  // handle "" where the drawing has none
  size_t line = 0;                  // the file line of its group code 0
  bool paper_space = false;         // group code 67 = 1: a sheet's layout, not the drawing
  bool off_plane = false;           // its extrusion direction (210/220/230) is not +-z
  std::string name() const;         // "TYPE (handle H, layer 'L')", printable
};

struct DxfPolyline {
  DxfEntity e;
  bool closed = false, mesh = false;
  std::vector<DxfVertex> v;
};

struct DxfText {
  DxfEntity e;
  std::string text;  // UTF-8 (a drawing's \U+XXXX escapes and 8-bit code page text converted; an MTEXT's formatting codes removed)
  double x = 0, y = 0;
};

struct DxfDrawing {
  int insunits = -1;  // $INSUNITS, -1: absent
  std::vector<DxfPolyline> polylines;
  std::vector<DxfText> texts;
  std::vector<DxfEntity> curves;   // CIRCLE, ARC, ELLIPSE, SPLINE, INSERT: cannot be blocks
  std::vector<DxfEntity> lines;    // LINE entities
  std::vector<DxfEntity> skipped;  // every other entity type (HATCH, DIMENSION, POINT, ...)
};

// Throws CaseError: "PATH:LINE: what", one line.
DxfDrawing read_dxf(const std::string& path);

}  // namespace masonry
