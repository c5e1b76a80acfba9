// The two methods a case runs by, as a type, with their names in files and for people. Text
// becomes a Method only where it is read (case, sweep, plan and catalogue files, flags,
// results.json) and a name only where it is written.
#pragma once

#include <optional>
#include <string>

namespace masonry {

enum class Method { prd, dem };
inline constexpr Method kMethods[] = {Method::prd, Method::dem};

// "prd" / "dem": the name in files, flags and results.json's "method".
const char* method_name(Method m);
// "PRD" / "DEM": for people.
const char* method_label(Method m);
// The method a name gives, or nothing for any other text.
std::optional<Method> parse_method(const std::string& name);

}  // namespace masonry
