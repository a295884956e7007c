// PLACEHOLDER: replaced by the owner of the 'inspect' subcommand.
#include "breastfit/core/errors.h"
#include "commands.h"

namespace breastfit::cli {
void register_inspect(CLI::App& app, int& exit_code) {
  auto* sub = app.add_subcommand("inspect", "(not built yet)");
  sub->callback([] { throw InvalidInput("'inspect' is not implemented yet"); });
}
}  // namespace breastfit::cli
