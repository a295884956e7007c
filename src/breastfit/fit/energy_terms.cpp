#include "breastfit/fit/energy_terms.h"

#include <string>

namespace breastfit::fit {

// Each term is one file (<name>.cpp) defining its class and its spec.
TermSpec data_term_spec();
TermSpec reverse_term_spec();
TermSpec landmark_term_spec();
TermSpec sliding_landmark_term_spec();
TermSpec scale_prior_spec();
TermSpec blendshape_prior_spec();
TermSpec joint_prior_spec();
TermSpec continuity_term_spec();

const std::vector<TermSpec>& energy_terms() {
  // One line per term (and its declaration above): adding a term to the registration is adding it here.
  static const std::vector<TermSpec> table = {
      data_term_spec(),
      reverse_term_spec(),
      landmark_term_spec(),
      sliding_landmark_term_spec(),
      scale_prior_spec(),
      blendshape_prior_spec(),
      joint_prior_spec(),
      continuity_term_spec(),
  };
  return table;
}

const TermSpec* find_energy_term(std::string_view name) {
  for (const auto& t : energy_terms())
    if (t.name == name) return &t;
  return nullptr;
}

std::string energy_term_names() {
  std::string out;
  for (const auto& t : energy_terms()) out += (out.empty() ? "" : ", ") + std::string(t.name);
  return out;
}

}  // namespace breastfit::fit
