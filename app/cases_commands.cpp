// `masonry cases`: the case generators and the standard scenes on the command line.
//   masonry cases --list
//   masonry cases NAME --out FILE [parameters]   (NAME --help lists the parameters)
//   masonry cases import DRAWING.dxf --out FILE [options]
//   masonry cases show CASE --svg FILE   (FILE '-': standard output)
#include <deque>
#include <functional>
#include <iostream>
#include <map>
#include <memory>
#include <type_traits>
#include <variant>

#include "app/command.hpp"
#include "cases/dxf.hpp"
#include "cases/generators.hpp"
#include "cases/parameters.hpp"
#include "cases/show.hpp"
#include "cases/wall_fields.hpp"
#include "model/results.hpp"

namespace masonry {

namespace {

// A generator on the command line: one option per parameter of its table (parameters.hpp),
// bound to a slot whose initial value is the default, so --help shows it.
struct GeneratorCommand {
  CLI::App* app = nullptr;
  const CaseGenerator* generator = nullptr;  // a parameter-table generator, or
  std::string name, summary;                 // one with options of its own (the wall's openings, bond, ...)
  std::function<Case()> make;
  struct Slot {
    double number = 0;
    int integer = 0;
    bool flag = false;
  };
  std::deque<Slot> slots;  // a deque: CLI11 keeps pointers to the values
  std::vector<double> values() const {
    std::vector<double> v;
    for (size_t k = 0; k < slots.size(); ++k) {
      switch (generator->parameters[k].kind) {
        case ParameterKind::number: v.push_back(slots[k].number); break;
        case ParameterKind::integer: v.push_back(slots[k].integer); break;
        case ParameterKind::flag: v.push_back(slots[k].flag ? 1.0 : 0.0); break;
      }
    }
    return v;
  }
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
  auto gens = std::make_shared<std::deque<GeneratorCommand>>();
  for (const CaseGenerator& g : case_generators()) {
    GeneratorCommand& gc = gens->emplace_back();
    gc.generator = &g;
    gc.name = g.name;
    gc.summary = g.summary;
    gc.app = cmd->add_subcommand(g.name, g.summary);
    gc.app->add_option("--out,-o", *file, "Case file to write ('-': standard output)")->required();
    for (const GeneratorParameter& p : g.parameters) {
      GeneratorCommand::Slot& slot = gc.slots.emplace_back();
      const std::string flag = "--" + p.name;
      switch (p.kind) {
        case ParameterKind::number:
          slot.number = p.value;
          gc.app->add_option(flag, slot.number, parameter_help(p))->capture_default_str();
          break;
        case ParameterKind::integer:
          slot.integer = static_cast<int>(p.value);
          gc.app->add_option(flag, slot.integer, parameter_help(p))->capture_default_str();
          break;
        case ParameterKind::flag:
          slot.flag = p.value != 0;
          gc.app->add_flag(flag, slot.flag, parameter_help(p));
          break;
      }
    }
  }

  {
    auto p = std::make_shared<BrickWall>();
    auto openings = std::make_shared<std::vector<std::string>>();
    CLI::App* g = cmd->add_subcommand("wall",
                                      "Brick wall in running, stack or header bond, with openings under lintels or arches, on two ground blocks; "
                                      "one settles or turns (cases/README.md, 'Brick wall')");
    g->add_option("--out,-o", *file, "Case file to write ('-': standard output)")->required();
    for (const WallField& f : wall_fields()) {
      const std::string flag = std::string("--") + f.name;
      std::visit(
          [&](auto member) {
            using T = std::remove_reference_t<decltype(p.get()->*member)>;
            CLI::Option* o = g->add_option(flag, p.get()->*member, f.help);
            if constexpr (std::is_enum_v<T>)
              take_words(o, wall_words<T>())->default_str(wall_word(p.get()->*member));
            else if (f.show_default)
              o->capture_default_str();
          },
          f.member);
    }
    g->add_option(std::string("--") + kWallOpeningName, *openings, kWallOpeningHelp);
    GeneratorCommand& gc = gens->emplace_back();
    gc.app = g;
    gc.name = "wall";
    gc.summary = g->get_description();
    gc.make = [p, openings] {
      BrickWall q = *p;
      for (const std::string& o : *openings) q.openings.push_back(parse_wall_opening(o));
      return brick_wall(q);
    };
  }

  // Import a drawing.
  auto imp = std::make_shared<DxfImportOptions>();
  auto drawing = std::make_shared<std::string>();
  auto import_out = std::make_shared<std::string>();
  CLI::App* import_cmd =
      cmd->add_subcommand("import",
                          "A DXF drawing's closed polylines as a case: layer SUPPORT* supports, IGNORE* skipped, others free blocks "
                          "(cases/README.md, 'Importing a drawing')");
  import_cmd->add_option("drawing", *drawing, "DXF drawing (ASCII)")->required();
  import_cmd->add_option("--out,-o", *import_out, "Case file to write ('-': standard output)")->required();
  import_cmd->add_option("--units", imp->units, "Drawing units: m, cm, mm, in, ft (default: the drawing's $INSUNITS)");
  // Bound to a number, then handed on only when given: 0 is a density the import refuses, not "none".
  auto density = std::make_shared<double>(0.0);
  CLI::Option* density_opt = import_cmd->add_option("--density", *density, "Density of free blocks, kg/m3 (layers file entries take precedence)");
  import_cmd->add_option("--depth", imp->depth, "Out-of-plane depth, m (default 1)")->capture_default_str();
  import_cmd->add_option("--layers", imp->layers_file, "JSON {\"layers\": {NAME: {density, depth, support}}}");
  import_cmd->add_option("--merge", imp->merge_file, "JSON fragment merged into the case: name, description, gravity, loads, motion, prd, dem");
  import_cmd->add_option("--name", imp->name, "Case name (default: the drawing's file name)");
  import_cmd->add_option("--arc-tolerance", imp->arc_tolerance, "Arcs (polyline bulges) become chords within this distance, m")
      ->capture_default_str();
  import_cmd->add_option("--snap", imp->snap, "Move vertices within this distance of another block onto it, m (default 0: off)");
  import_cmd->add_option("--near-joint", imp->near_joint, "Report blocks that come this close without touching, m")->capture_default_str();
  // Draw a case.
  auto shown = std::make_shared<std::string>();
  auto svg = std::make_shared<std::string>();
  CLI::App* show_cmd = cmd->add_subcommand("show", "Draw a case as SVG: blocks and ids, supports hatched, joints, loads, support motion");
  show_cmd->add_option("case", *shown, "Case file (masonry-case/1)")->required();
  show_cmd->add_option("--svg", *svg, "SVG file to write ('-': standard output)")->required();

  out.push_back({cmd, [cmd, list, file, gens, import_cmd, imp, density, density_opt, drawing, import_out, show_cmd, shown, svg]() -> int {
                   if (import_cmd->parsed()) {
                     if (density_opt->count()) imp->density = *density;
                     const DxfImport r = import_dxf(*drawing, *imp);
                     for (const std::string& n : r.notes) std::cerr << "cases import: " << n << "\n";
                     return emit(r.c, *import_out);
                   }
                   if (show_cmd->parsed()) {
                     const Case c = load_case(*shown);
                     // "-" is standard output, as for the generators' --out (it wrote a file named "-").
                     if (*svg == "-") {
                       std::cout << case_svg(c);
                       return 0;
                     }
                     write_file_atomic(*svg, case_svg(c));
                     std::cerr << "wrote " << *svg << " (" << c.blocks.size() << " blocks)\n";
                     return 0;
                   }
                   if (*list) {
                     std::cout << "generators and standard scenes (masonry cases NAME --out FILE; NAME --help):\n";
                     for (const GeneratorCommand& g : *gens) std::cout << "  " << g.name << "\n      " << g.summary << "\n";
                     std::cout << "standard scenes checked in under cases/:\n";
                     for (const StandardCase& s : standard_cases()) std::cout << "  " << s.name << ".json: " << s.summary << "\n";
                     return 0;
                   }
                   for (const GeneratorCommand& g : *gens)
                     if (g.app->parsed()) return emit(g.make ? g.make() : g.generator->make(g.values()), *file);
                   std::cerr << "masonry cases: name a generator or give --list (see masonry cases --help)\n";
                   return 2;
                 }});
}

}  // namespace masonry
