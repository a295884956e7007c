#include "breastfit/experiments/markdown_cells_json.h"

#include <cstdio>

namespace breastfit::experiments {

const nlohmann::json& json_at(const nlohmann::json& j, const std::vector<const char*>& path) {
  static const nlohmann::json null;
  const nlohmann::json* p = &j;
  for (const char* k : path) {
    if (!p->is_object() || !p->contains(k)) return null;
    p = &(*p)[k];
  }
  return *p;
}

std::string cell(const nlohmann::json& v, int digits) {
  if (!v.is_number()) return "–";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v.get<double>());
  return buf;
}

}  // namespace breastfit::experiments
