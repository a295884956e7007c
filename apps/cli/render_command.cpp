// PLACEHOLDER: replaced by the owner of the 'render' subcommand.
#include "breastfit/core/errors.h"
#include "commands.h"

namespace breastfit::cli {
void register_render(CLI::App& app, int& exit_code) {
  auto* sub = app.add_subcommand("render", "(not built yet)");
  sub->callback([] { throw InvalidInput("'render' is not implemented yet"); });
}
}  // namespace breastfit::cli
