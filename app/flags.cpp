#include "app/flags.hpp"

#include <algorithm>
#include <sstream>
#include <stdexcept>

namespace masonry {

OptionInfo CaseFlags::info(const std::string& key) {
  for (OptionInfo& i : option_infos())
    if (i.key == key) return std::move(i);
  throw std::logic_error("masonry: no option '" + key + "'");
}

void CaseFlags::add(CLI::App* sub, OptionCommand command) {
  for (const OptionInfo& i : option_infos()) {
    if (std::find(i.commands.begin(), i.commands.end(), command) == i.commands.end()) continue;
    const bool both = command == OptionCommand::compare;
    add(sub, i, both && i.section == "prd" ? "PRD: " : both && i.section == "dem" ? "DEM: " : "");
  }
}

CLI::Option* CaseFlags::add(CLI::App* sub, const OptionInfo& i, const std::string& prefix) {
  Flag& f = flags_.emplace_back();
  f.name = i.flag;
  f.key = i.key;
  // "Friction angle of the joints, deg (case: dem.friction_angle, default 35, in [0, 90]; 90: no slip limit)"
  std::string text = prefix + i.help + (*i.unit ? std::string(", ") + i.unit : "") + " (case: " + i.key;
  if (!i.default_text.empty()) text += ", default " + i.default_text;
  if (i.type == OptionType::number || i.type == OptionType::integer)
    text += ", in " + i.range_text;
  else if (i.type == OptionType::word)
    text += "; " + i.range_text;
  else if (i.type == OptionType::words)
    text += "; " + i.range_text + "; repeatable";
  if (*i.note) text += std::string("; ") + i.note;
  text += ")";
  switch (i.type) {
    case OptionType::number: return sub->add_option(f.name, f.number, text);
    case OptionType::integer: return sub->add_option(f.name, f.integer, text);
    case OptionType::boolean: return f.flag = sub->add_flag(f.name, f.on, text);
    case OptionType::word: return sub->add_option(f.name, f.text, text);
    case OptionType::words: return sub->add_option(f.name, f.texts, text)->allow_extra_args(false);
  }
  throw std::logic_error("masonry: an option of no type");
}

Case CaseFlags::apply(Case c) const {
  for (const Flag& f : flags_) {
    if (f.number) c = with_option(c, f.key, *f.number);
    if (f.integer) c = with_option(c, f.key, *f.integer);
    if (f.switch_given()) c = with_option(c, f.key, f.on);
    if (f.text) c = with_option(c, f.key, *f.text);
    if (!f.texts.empty()) c = with_option(c, f.key, f.texts);
  }
  return c;
}

std::string CaseFlags::command_line() const {
  std::ostringstream o;
  for (const Flag& f : flags_) {
    if (f.number) o << " " << f.name << " " << *f.number;
    if (f.integer) o << " " << f.name << " " << *f.integer;
    if (f.switch_given()) o << " " << f.name << (f.on ? "" : "=false");
    if (f.text) o << " " << f.name << " " << *f.text;
    for (const std::string& t : f.texts) o << " " << f.name << " " << t;
  }
  return o.str();
}

}  // namespace masonry
