// Importing a drawing: the closed polylines of a DXF file become the blocks of a case
// (cases/README.md, "Importing a drawing"). The DXF is read by cases/dxf_reader.hpp, every value
// checked against the DXF reference; everything a case file must satisfy is then checked by the
// case loader, with messages that name the drawing's layer and entity handle.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "model/case.hpp"

namespace masonry {

struct DxfImportOptions {
  std::string units;              // "m", "cm", "mm", "in", "ft"; empty: the drawing's $INSUNITS
  std::optional<double> density;  // kg/m^3 of every free layer that the layers file does not set; none: not given
  double depth = 1.0;             // m, the same for depth
  std::string layers_file;        // JSON: {"layers": {"NAME": {"density": .., "depth": .., "support": true}}}
  std::string merge_file;         // JSON fragment merged into the case: name, description, gravity, loads, motion, prd, dem
  std::string name;               // case name; empty: the drawing's file name
  double arc_tolerance = 1e-3;    // m: largest distance between an arc (a polyline bulge) and its chords
  double snap = 0.0;              // m: vertices within this of another block's vertex or edge are moved onto it
  double near_joint = 1e-3;       // m: vertices this close to another block, but not touching it, are reported
};

struct DxfImport {
  Case c;
  std::vector<std::string> notes;  // what the import did or noticed (snaps, near joints, ignored entities)
};

// Throws CaseError with one line naming the drawing and, where it applies, the layer and the
// entity handle.
DxfImport import_dxf(const std::string& path, const DxfImportOptions& o);

}  // namespace masonry
