// `masonry cases`: the case generators and the standard scenes on the command line.
//   masonry cases --list
//   masonry cases NAME --out FILE [parameters]   (NAME --help lists the parameters)
//   masonry cases import DRAWING.dxf --out FILE [options]
//   masonry cases show CASE --svg FILE
#include <cmath>
#include <iostream>
#include <map>
#include <memory>

#include "app/command.hpp"
#include "cases/dxf.hpp"
#include "cases/generators.hpp"
#include "cases/show.hpp"
#include "model/results.hpp"

namespace masonry {

namespace {

constexpr double kDeg = M_PI / 180.0;

struct Generator {
  CLI::App* app = nullptr;
  std::string summary;
  std::function<Case()> make;
};

// Writes the case (or prints it for "-") after checking that it reads back as a valid case.
int emit(const Case& c, const std::string& out) {
  const std::string text = case_to_json(c);
  parse_case(text, out);  // the file must load: geometry, overlaps, connectivity
  if (out == "-") {
    std::cout << text;
  } else {
    write_file_atomic(out, text);
    std::cerr << "wrote " << out << " (" << c.blocks.size() << " blocks)\n";
  }
  return 0;
}

}  // namespace

void add_case_commands(CLI::App& app, Commands& out) {
  CLI::App* cmd = app.add_subcommand("cases", "Case generators and the standard scenes: write case files");
  cmd->require_subcommand(0, 1);
  auto list = std::make_shared<bool>(false);
  auto file = std::make_shared<std::string>();
  cmd->add_flag("--list", *list, "List the generators and standard scenes");
  auto gens = std::make_shared<std::vector<Generator>>();
  auto add_out = [&](CLI::App* g) { g->add_option("--out,-o", *file, "Case file to write ('-': standard output)")->required(); };

  {
    auto p = std::make_shared<CircularArch>();
    auto deg = std::make_shared<double>(p->embrace / kDeg);
    auto fixed = std::make_shared<bool>(false);
    CLI::App* g = cmd->add_subcommand("circular-arch", "Circular arch, radial joints, on two supports; right support spreading");
    add_out(g);
    g->add_option("--radius", p->radius, "Centreline radius R, m")->capture_default_str();
    g->add_option("--thickness", p->thickness, "Thickness t, m")->capture_default_str();
    g->add_option("--embrace-deg", *deg, "Angle of embrace, degrees")->capture_default_str();
    g->add_option("--voussoirs", p->voussoirs, "Number of voussoirs")->capture_default_str();
    g->add_option("--depth", p->depth, "Out-of-plane depth, m")->capture_default_str();
    g->add_option("--density", p->density, "Density, kg/m3")->capture_default_str();
    g->add_option("--step", p->step, "Support displacement per step, m")->capture_default_str();
    g->add_option("--max-steps", p->max_steps, "Largest number of steps")->capture_default_str();
    g->add_flag("--fixed", *fixed, "No support motion");
    gens->push_back({g, "circular arch (generator)", [=] {
                       CircularArch q = *p;
                       q.embrace = *deg * kDeg;
                       q.spreading = !*fixed;
                       return circular_arch(q);
                     }});
  }
  {
    auto p = std::make_shared<PointedArch>(standard_pointed_arch());
    auto deg = std::make_shared<double>(150.0);
    auto fixed = std::make_shared<bool>(false);
    CLI::App* g = cmd->add_subcommand(
        "pointed-arch",
        "Two-centred pointed arch (Romano & Ochsendorf parameters) on two supports; right support spreading. "
        "With the default parameters: the standard scene cases/pointed-arch.json");
    add_out(g);
    g->add_option("--rcirc", p->rcirc, "Centreline radius of the equivalent circular arch Rcirc, m")->capture_default_str();
    g->add_option("--eccentricity", p->eccentricity, "Eccentricity e of the two centres from the axis, m (Rpoint = Rcirc + e)")
        ->capture_default_str();
    g->add_option("--thickness", p->thickness, "Thickness t, m")->capture_default_str();
    g->add_option("--embrace-deg", *deg, "Angle of embrace (between the springing joints), degrees")->capture_default_str();
    g->add_option("--voussoirs", p->voussoirs, "Number of voussoirs (even: crown joint on the axis; odd: keystone)")
        ->capture_default_str();
    g->add_option("--depth", p->depth, "Out-of-plane depth, m")->capture_default_str();
    g->add_option("--density", p->density, "Density, kg/m3")->capture_default_str();
    g->add_option("--step", p->step, "Support displacement per step, m")->capture_default_str();
    g->add_option("--max-steps", p->max_steps, "Largest number of steps")->capture_default_str();
    g->add_flag("--fixed", *fixed, "No support motion");
    gens->push_back({g, "pointed arch (generator; defaults: the standard scene)", [=] {
                       PointedArch q = *p;
                       q.embrace = *deg * kDeg;
                       q.spreading = !*fixed;
                       // The defaults are the standard scene: keep its name and description.
                       Case c = pointed_arch(q);
                       if (case_to_json(c) == case_to_json(pointed_arch(standard_pointed_arch())))
                         return standard_case("pointed-arch");
                       return c;
                     }});
  }
  auto cathedral = [&](const std::string& name, const std::string& help, GothicCathedral defaults,
                       const std::string& standard) {
    auto p = std::make_shared<GothicCathedral>(defaults);
    CLI::App* g = cmd->add_subcommand(name, help);
    add_out(g);
    g->add_option("--nave-height", p->nave_height, "Intrados crown of the nave arch, m")->capture_default_str();
    g->add_option("--aisle-height", p->aisle_height, "Intrados crown of the aisle arches, m")->capture_default_str();
    g->add_option("--bay", p->bay, "Bay: out-of-plane depth of the arches (vaults), m")->capture_default_str();
    g->add_option("--nave-span", p->nave_span, "Clear span of the nave between the piers, m")->capture_default_str();
    g->add_option("--pier-width", p->pier_width, "Width of the nave pier shaft, m")->capture_default_str();
    g->add_option("--aisle-span", p->aisle_span, "Clear span of the aisle arch, m")->capture_default_str();
    g->add_option("--buttress-width", p->buttress_width, "Width of the outer buttress above the aisle springing, m")
        ->capture_default_str();
    g->add_option("--nave-springing", p->nave_springing, "Height of the nave arch's springing (pier top), m")->capture_default_str();
    g->add_option("--aisle-springing", p->aisle_springing, "Height of the aisle arch's springing, m")->capture_default_str();
    g->add_option("--nave-thickness", p->nave_thickness, "Nave arch thickness, m")->capture_default_str();
    g->add_option("--aisle-thickness", p->aisle_thickness, "Aisle arch thickness, m")->capture_default_str();
    g->add_option("--flyer-thickness", p->flyer_thickness, "Flying buttress thickness, m")->capture_default_str();
    g->add_option("--lower-flyer-head", p->lower_flyer_head, "Lower flyer: intrados height at the pier, m")->capture_default_str();
    g->add_option("--lower-flyer-foot", p->lower_flyer_foot, "Lower flyer: intrados height at the buttress, m")->capture_default_str();
    g->add_option("--upper-flyer-head", p->upper_flyer_head, "Upper flyer: intrados height at the pier, m")->capture_default_str();
    g->add_option("--upper-flyer-foot", p->upper_flyer_foot, "Upper flyer: intrados height at the buttress, m")->capture_default_str();
    g->add_option("--buttress-height", p->buttress_height, "Height of the outer buttress, m")->capture_default_str();
    g->add_option("--foundation-height", p->foundation_height, "Height of the support blocks, m")->capture_default_str();
    g->add_option("--pier-depth", p->pier_depth, "Out-of-plane depth of the piers, m")->capture_default_str();
    g->add_option("--buttress-depth", p->buttress_depth, "Out-of-plane depth of the buttresses, m")->capture_default_str();
    g->add_option("--flyer-depth", p->flyer_depth, "Out-of-plane depth of the flying buttresses, m")->capture_default_str();
    g->add_option("--density", p->density, "Density, kg/m3")->capture_default_str();
    g->add_option("--course", p->course, "Target course height of piers and buttresses, m")->capture_default_str();
    g->add_option("--nave-voussoirs", p->nave_voussoirs, "Voussoirs of the nave arch (even)")->capture_default_str();
    g->add_option("--aisle-voussoirs", p->aisle_voussoirs, "Voussoirs of each aisle arch (even)")->capture_default_str();
    g->add_option("--flyer-voussoirs", p->flyer_voussoirs, "Voussoirs of each flying buttress")->capture_default_str();
    g->add_option("--moving-support", p->moving_support, "Support that moves, 1..4 from the left (3: third pier)")
        ->capture_default_str();
    g->add_option("--settlement-step", p->settlement_step, "Settlement of that support per step, m (down)")
        ->capture_default_str();
    g->add_option("--rotation-step", p->rotation_step, "Counter-clockwise rotation per step about its centroid, rad")
        ->capture_default_str();
    g->add_option("--step", p->step, "Path parameter d per step, m")->capture_default_str();
    g->add_option("--max-steps", p->max_steps, "Largest number of steps")->capture_default_str();
    gens->push_back({g, help, [=] {
                       Case c = gothic_cathedral(*p);
                       // Unchanged defaults of a standard scene: the standard file, name and description included.
                       if (!standard.empty() && case_to_json(c) == case_to_json(gothic_cathedral(defaults)))
                         return standard_case(standard);
                       return c;
                     }});
  };
  cathedral("cathedral", "Gothic cathedral cross-section after the paper (Amiens); no motion unless asked", GothicCathedral{},
            "");
  cathedral("cathedral-settlement", "Standard scene: the cathedral, third pier settling 1 cm per step",
            standard_cathedral_settlement(), "cathedral-settlement");
  cathedral("cathedral-settlement-rotation",
            "Standard scene: the cathedral, third pier settling 1 cm and turning 0.001 rad per step",
            standard_cathedral_settlement_rotation(), "cathedral-settlement-rotation");

  {
    auto p = std::make_shared<BrickWall>();
    auto openings = std::make_shared<std::vector<std::string>>();
    CLI::App* g = cmd->add_subcommand(
        "wall", "Brick wall in running, stack or header bond, with openings under lintels or arches, on two ground blocks; "
                "one settles or turns (cases/README.md, 'Brick wall')");
    add_out(g);
    g->add_option("--bond", p->bond, "running, stack or header")
        ->transform(CLI::CheckedTransformer(
            std::map<std::string, WallBond>{{"running", WallBond::running}, {"stack", WallBond::stack}, {"header", WallBond::header}}))
        ->default_str("running");
    g->add_option("--courses", p->courses, "Number of courses")->capture_default_str();
    g->add_option("--bricks", p->bricks, "Units per course: stretchers, or headers in header bond")->capture_default_str();
    g->add_option("--brick-length", p->brick_length, "Stretcher length, m")->capture_default_str();
    g->add_option("--header-length", p->header_length, "Header face length (the brick's width), m; header bond")
        ->capture_default_str();
    g->add_option("--course-height", p->course_height, "Course height, m")->capture_default_str();
    g->add_option("--depth", p->depth, "Out-of-plane thickness of the wall, m")->capture_default_str();
    g->add_option("--density", p->density, "Density, kg/m3")->capture_default_str();
    g->add_option("--opening", *openings,
                  "An opening X,SILL,WIDTH,HEIGHT[,lintel|arch] (m from the wall's left end and base; sill and top move to the "
                  "nearest course joint; default top: lintel); repeatable");
    g->add_option("--lintel-bearing", p->lintel_bearing, "A lintel's bearing on each side of its opening, m")->capture_default_str();
    g->add_option("--arch-thickness", p->arch_thickness, "Thickness of an arch's ring, m")->capture_default_str();
    g->add_option("--arch-voussoirs", p->arch_voussoirs, "Voussoirs of each arch (0: about one per course height)")
        ->capture_default_str();
    g->add_option("--ground-height", p->ground_height, "Height of the two ground blocks, m")->capture_default_str();
    g->add_option("--ground-split", p->ground_split, "Where the ground splits, m from the wall's left end (default: the middle)");
    g->add_option("--moving", p->moving, "Which ground block moves: left, right or none")
        ->transform(CLI::CheckedTransformer(std::map<std::string, MovingGround>{
            {"none", MovingGround::none}, {"left", MovingGround::left}, {"right", MovingGround::right}}))
        ->default_str("right");
    g->add_option("--settlement-step", p->settlement_step, "Settlement of the moving ground per step, m (down)")->capture_default_str();
    g->add_option("--rotation-step", p->rotation_step,
                  "Counter-clockwise rotation of the moving ground per step, rad, about the split's top point")
        ->capture_default_str();
    g->add_option("--step", p->step, "Path parameter d per step, m")->capture_default_str();
    g->add_option("--max-steps", p->max_steps, "Largest number of steps")->capture_default_str();
    gens->push_back({g, "brick wall (generator)", [=] {
                       BrickWall q = *p;
                       for (const std::string& o : *openings) q.openings.push_back(parse_wall_opening(o));
                       return brick_wall(q);
                     }});
  }

  // Import a drawing.
  auto imp = std::make_shared<DxfImportOptions>();
  auto drawing = std::make_shared<std::string>();
  auto import_out = std::make_shared<std::string>();
  CLI::App* import_cmd = cmd->add_subcommand(
      "import", "A DXF drawing's closed polylines as a case: layer SUPPORT* supports, IGNORE* skipped, others free blocks "
                "(cases/README.md, 'Importing a drawing')");
  import_cmd->add_option("drawing", *drawing, "DXF drawing (ASCII)")->required();
  import_cmd->add_option("--out,-o", *import_out, "Case file to write ('-': standard output)")->required();
  import_cmd->add_option("--units", imp->units, "Drawing units: m, cm, mm, in, ft (default: the drawing's $INSUNITS)");
  import_cmd->add_option("--density", imp->density, "Density of free blocks, kg/m3 (layers file entries take precedence)");
  import_cmd->add_option("--depth", imp->depth, "Out-of-plane depth, m (default 1)")->capture_default_str();
  import_cmd->add_option("--layers", imp->layers_file, "JSON {\"layers\": {NAME: {density, depth, support}}}");
  import_cmd->add_option("--merge", imp->merge_file, "JSON fragment merged into the case: name, description, gravity, loads, motion, prd, dem");
  import_cmd->add_option("--name", imp->name, "Case name (default: the drawing's file name)");
  import_cmd->add_option("--arc-tolerance", imp->arc_tolerance, "Arcs (polyline bulges) become chords within this distance, m")
      ->capture_default_str();
  import_cmd->add_option("--snap", imp->snap, "Move vertices within this distance of another block onto it, m (default 0: off)");
  import_cmd->add_option("--near-joint", imp->near_joint, "Report blocks that come this close without touching, m")
      ->capture_default_str();
  // Draw a case.
  auto shown = std::make_shared<std::string>();
  auto svg = std::make_shared<std::string>();
  CLI::App* show_cmd = cmd->add_subcommand("show", "Draw a case as SVG: blocks and ids, supports hatched, joints, loads, support motion");
  show_cmd->add_option("case", *shown, "Case file (masonry-case/1)")->required();
  show_cmd->add_option("--svg", *svg, "SVG file to write")->required();

  out.push_back({cmd, [cmd, list, file, gens, import_cmd, imp, drawing, import_out, show_cmd, shown, svg]() -> int {
                   if (import_cmd->parsed()) {
                     const DxfImport r = import_dxf(*drawing, *imp);
                     for (const std::string& n : r.notes) std::cerr << "cases import: " << n << "\n";
                     return emit(r.c, *import_out);
                   }
                   if (show_cmd->parsed()) {
                     const Case c = load_case(*shown);
                     write_file_atomic(*svg, case_svg(c));
                     std::cerr << "wrote " << *svg << " (" << c.blocks.size() << " blocks)\n";
                     return 0;
                   }
                   if (*list) {
                     std::cout << "generators and standard scenes (masonry cases NAME --out FILE; NAME --help):\n";
                     for (const Generator& g : *gens) std::cout << "  " << g.app->get_name() << "\n      " << g.summary << "\n";
                     std::cout << "standard scenes checked in under cases/:\n";
                     for (const StandardCase& s : standard_cases())
                       std::cout << "  " << s.name << ".json: " << s.summary << "\n";
                     return 0;
                   }
                   for (const Generator& g : *gens)
                     if (g.app->parsed()) return emit(g.make(), *file);
                   std::cerr << "masonry cases: name a generator or give --list (see masonry cases --help)\n";
                   return 2;
                 }});
}

}  // namespace masonry
