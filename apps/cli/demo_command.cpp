// PLACEHOLDER: replaced by the owner of the 'demo' subcommand.
#include "breastfit/core/errors.h"
#include "commands.h"

namespace breastfit::cli {
void register_demo(CLI::App& app, int& exit_code) {
  auto* sub = app.add_subcommand("demo", "(not built yet)");
  sub->callback([] { throw InvalidInput("'demo' is not implemented yet"); });
}
}  // namespace breastfit::cli
