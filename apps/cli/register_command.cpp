// PLACEHOLDER: replaced by the owner of the 'register' subcommand.
#include "breastfit/core/errors.h"
#include "commands.h"

namespace breastfit::cli {
void register_register(CLI::App& app, int& exit_code) {
  auto* sub = app.add_subcommand("register", "(not built yet)");
  sub->callback([] { throw InvalidInput("'register' is not implemented yet"); });
}
}  // namespace breastfit::cli
