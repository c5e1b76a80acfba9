#include "model/method.hpp"

namespace masonry {

const char* method_name(Method m) { return m == Method::prd ? "prd" : "dem"; }
const char* method_label(Method m) { return m == Method::prd ? "PRD" : "DEM"; }

std::optional<Method> parse_method(const std::string& name) {
  if (name == "prd") return Method::prd;
  if (name == "dem") return Method::dem;
  return std::nullopt;
}

}  // namespace masonry
