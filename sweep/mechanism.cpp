// The hinges at collapse of a sweep's run: what groups the samples by collapse mechanism.
#include <cctype>
#include <map>
#include <set>

#include "compare/compare.hpp"
#include "model/interfaces.hpp"
#include "sweep/sweep.hpp"

namespace masonry {

std::string hinges_at_collapse(const Case& c, const RunResult& r) {
  std::vector<std::string> labels;
  if (r.collapse) {
    // PRD's collapse mechanism: the corners its last LP's unbounded motion opens. A joint with
    // one open corner is a hinge about the other (named as compare/ names hinges); one with both
    // open separates.
    std::map<int, std::vector<int>> open;  // joint -> open corners
    for (const CornerRef& o : r.collapse->mechanism.open_corners) open[o.joint].push_back(o.corner);
    const std::vector<int> nth = pair_ordinals(r.joints);
    for (const auto& [joint, corners] : open) {
      if (joint < 0 || joint >= int(r.joints.size())) continue;
      const JointInfo& j = r.joints[joint];
      const int n = nth[size_t(joint)];
      if (corners.size() == 1) {
        labels.push_back(corner_name(c, j.i, j.j, 1 - corners[0], n));
      } else {
        // "v3/v4:open"; a further joint between the same blocks by its corners, "base/post:CDopen".
        labels.push_back(joint_name(c, j.i, j.j, n) + (n == 0 ? ":open" : "open"));
      }
    }
  }
  if (labels.empty()) {
    // The hinges of the last equilibrium (a PRD whose mechanism LP found none, a DEM); a DEM's
    // beyond the gaps it settled with (compare/'s rule: elastic redistribution opens gaps that
    // wide anywhere).
    const bool dem = known_method(r) == Method::dem;
    const std::vector<const StepRecord*> stable = stable_records(r);
    if (!stable.empty())
      for (const Hinge& h : hinges_of(c, r, *stable.back(), dem ? settled_gap(r) : 0.0)) labels.push_back(h.label);
    // A DEM that collapsed with no hinge open at its last equilibrium: those of the state its
    // failed hold was called a collapse in (compare/ reads its collapse mechanism there too). A
    // toppling block's heel may still be within the elastic gaps at its last equilibrium, and
    // the run read as a sliding one (a stack on a tilting slab, friction 17.5 and 20 degrees:
    // "none" beside the toppling runs at 12.5 and 15). Only then: the failed state is the fall
    // (a block drifted 2% of the scene), whose later hinges a structure with hinges already open
    // at its last equilibrium would add to its mechanism's.
    if (labels.empty() && dem)
      if (const std::optional<StepRecord> failed = collapse_state(r))
        for (const Hinge& h : hinges_of(c, r, *failed, settled_gap(r))) labels.push_back(h.label);
  }
  std::string s;
  for (const std::string& l : labels) s += (s.empty() ? "" : " ") + l;
  return s;
}

std::vector<std::string> hinge_labels(const std::string& hinges) {
  // Each label is BLOCK/BLOCK:A (a corner letter, model/interfaces.hpp) or :open (:CDopen), the
  // labels joined by one space. Ids may hold spaces (even begin with one) but never ':'
  // (model/case.cpp, id_fault), so a label ends at the word after its colon, and only the one
  // separating space is skipped.
  std::vector<std::string> out;
  size_t start = 0;
  while (start < hinges.size()) {
    const size_t colon = hinges.find(':', start);
    size_t end = colon == std::string::npos ? hinges.size() : hinges.find(' ', colon);
    if (end == std::string::npos) end = hinges.size();
    out.push_back(hinges.substr(start, end - start));
    start = end + 1;
  }
  return out;
}

std::vector<std::string> members_of(const std::string& hinges) {
  const auto member = [](std::string id) {
    size_t end = id.size();
    while (end > 0 && std::isdigit(static_cast<unsigned char>(id[end - 1]))) --end;
    if (end == id.size() || end == 0) return id;  // no number, or nothing but one
    if ((id[end - 1] == '-' || id[end - 1] == '_' || id[end - 1] == ' ') && end > 1) --end;  // "nave-06", "pier 2"
    return id.substr(0, end);
  };
  std::set<std::string> out;
  for (const std::string& h : hinge_labels(hinges)) {
    const size_t slash = h.find('/'), colon = h.rfind(':');
    if (slash == std::string::npos || colon == std::string::npos || colon < slash) {
      out.insert(h);
      continue;
    }
    const std::string a = member(h.substr(0, slash)), b = member(h.substr(slash + 1, colon - slash - 1));
    out.insert(a == b ? a : a + "/" + b);
  }
  return {out.begin(), out.end()};
}

std::string join_members(const std::vector<std::string>& members) {
  std::string s;
  for (const std::string& m : members) s += (s.empty() ? "" : ", ") + m;
  return s;
}

}  // namespace masonry
