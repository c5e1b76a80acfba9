#include "app/flags.hpp"

#include <sstream>

namespace masonry {

void CaseFlags::add(CLI::App* sub, const std::string& name, const std::string& key, Kind kind, const std::string& help) {
  Flag& f = flags_.emplace_back();
  f.name = name;
  f.key = key;
  f.kind = kind;
  const std::string text = help + " (case: " + key + ")";
  switch (kind) {
    case Kind::number: sub->add_option(name, f.number, text); break;
    case Kind::integer: sub->add_option(name, f.integer, text); break;
    case Kind::flag: sub->add_flag(name, f.on, text); break;
    case Kind::text: sub->add_option(name, f.text, text); break;
    case Kind::texts: sub->add_option(name, f.texts, text)->allow_extra_args(false); break;
  }
}

Case CaseFlags::apply(Case c) const {
  for (const Flag& f : flags_) {
    if (f.number) c = with_option(c, f.key, *f.number);
    if (f.integer) c = with_option(c, f.key, *f.integer);
    if (f.on) c = with_option(c, f.key, true);
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
    if (f.on) o << " " << f.name;
    if (f.text) o << " " << f.name << " " << *f.text;
    for (const std::string& t : f.texts) o << " " << f.name << " " << t;
  }
  return o.str();
}

}  // namespace masonry
