#include "breastfit/fit/energy_terms.h"

#include <string>

#include "breastfit/fit/blendshape_prior.h"
#include "breastfit/fit/continuity_term.h"
#include "breastfit/fit/data_term.h"
#include "breastfit/fit/joint_prior.h"
#include "breastfit/fit/landmark_term.h"
#include "breastfit/fit/reverse_term.h"
#include "breastfit/fit/scale_prior.h"
#include "breastfit/fit/sliding_landmark_term.h"

namespace breastfit::fit {

const std::vector<TermSpec>& energy_terms() {
  // One line per term: adding a term to the registration is adding its spec here.
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
