// PLACEHOLDER: replaced by the owner of the 'template' subcommand.
#include "breastfit/core/errors.h"
#include "commands.h"

namespace breastfit::cli {
void register_template(CLI::App& app, int& exit_code) {
  auto* sub = app.add_subcommand("template", "(not built yet)");
  sub->callback([] { throw InvalidInput("'template' is not implemented yet"); });
}
}  // namespace breastfit::cli
