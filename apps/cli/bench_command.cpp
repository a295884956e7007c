// PLACEHOLDER: replaced by the owner of the 'bench' subcommand.
#include "breastfit/core/errors.h"
#include "commands.h"

namespace breastfit::cli {
void register_bench(CLI::App& app, int& exit_code) {
  auto* sub = app.add_subcommand("bench", "(not built yet)");
  sub->callback([] { throw InvalidInput("'bench' is not implemented yet"); });
}
}  // namespace breastfit::cli
