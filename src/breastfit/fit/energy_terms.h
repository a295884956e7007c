#pragma once
/// \file The table of the registration's energy terms (energy_term.h), in evaluation order.
/// Everything per term — λ options and their JSON keys, command-line flags, the energies in
/// report.json — is derived from this table by name.
#include <memory>
#include <string_view>
#include <vector>

#include "breastfit/fit/energy_term.h"

namespace breastfit::fit {

/// Every term, in evaluation order.
const std::vector<TermSpec>& energy_terms();
/// The spec named `name`, or nullptr.
const TermSpec* find_energy_term(std::string_view name);
/// "data, reverse, ..." (for messages).
std::string energy_term_names();

}  // namespace breastfit::fit
