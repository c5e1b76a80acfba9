// Which masonry made a file or a report: the project's version (CMakeLists.txt, project VERSION)
// and the git commit the build was made from, recorded in results.json, comparison.json and every
// report, and printed by `masonry --version`.
#pragma once

#include <string>

namespace masonry {

const char* version_number();  // "0.1.0"
// `git describe` of the sources at build time ("96c2a98a1b2c", "-dirty" when tracked files had
// changes); empty where unknown (no git, or a source archive).
const char* version_commit();
// "masonry 0.1.0 (git 96c2a98a1b2c)", or "masonry 0.1.0" without a commit: what files record.
inline std::string version_text() {
  const std::string commit = version_commit();
  return std::string("masonry ") + version_number() + (commit.empty() ? "" : " (git " + commit + ")");
}

}  // namespace masonry
