// PLACEHOLDER: replaced by the owner of the 'synth' subcommand.
#include "breastfit/core/errors.h"
#include "commands.h"

namespace breastfit::cli {
void register_synth(CLI::App& app, int& exit_code) {
  auto* sub = app.add_subcommand("synth", "(not built yet)");
  sub->callback([] { throw InvalidInput("'synth' is not implemented yet"); });
}
}  // namespace breastfit::cli
