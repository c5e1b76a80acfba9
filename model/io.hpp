// Files and clocks, one definition each for every library of the harness.
#pragma once

#include <optional>
#include <string>

namespace masonry {

// The whole file as bytes; nothing when it cannot be opened (each caller says what the file was
// for in its own error).
std::optional<std::string> read_text(const std::string& path);
// The text of `path`, or, where only `path`.xz is there (or `path` itself ends in .xz), that file
// decompressed: the runs kept under reports/ are xz-compressed results.json (a sixth of the size).
// Nothing when neither can be opened; throws std::runtime_error naming the file when it is not
// valid xz.
std::optional<std::string> read_text_or_xz(const std::string& path);
// Writes a file atomically (temporary file, then rename), so a reader (or a later failure) never
// sees a half-written file. Throws std::runtime_error with errno's reason.
void write_file_atomic(const std::string& path, const std::string& text);
// CPU time of the calling thread, s: a run's own cost even when a sweep or a study runs many in
// parallel threads on fewer cores.
double thread_cpu_s();

}  // namespace masonry
