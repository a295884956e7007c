#include "run_app.h"

#include <iostream>

#include "breastfit/core/errors.h"
#include "breastfit/core/heap_reuse.h"
#include "command_support.h"
#include "exit_codes.h"

namespace breastfit::cli {
namespace {

/// A list option's captured default is "[]" when it starts empty: shown as no default at all
/// (its description says what an empty list means).
void hide_empty_list_defaults(CLI::App& app) {
  for (CLI::Option* o : app.get_options())
    if (o->get_default_str() == "[]") o->default_str("");
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) hide_empty_list_defaults(*sub);
}

}  // namespace

int run_app(int argc, char** argv, std::span<const RegisterFn> commands) {
  keep_freed_heap_memory();  // large scans: reuse freed memory (docs/PERFORMANCE.md)
  set_command_line(argc, argv);
  CLI::App app{"breastfit: rigged-template registration of breast scans and transfer of surgical drawings", "breastfit"};
  app.require_subcommand(1);
  // Every option shows its default in --help ("--size INT=1024"); subcommands inherit this.
  app.option_defaults()->always_capture_default();
  app.set_version_flag("--version", "breastfit 0.1.0");
  int exit_code = kExitOk;
  for (RegisterFn reg : commands) reg(app, exit_code);
  hide_empty_list_defaults(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? kExitOk : kExitUsage;
  } catch (const IoError& e) {
    std::cerr << "breastfit: error: " << e.what() << "\n";
    return kExitIoError;
  } catch (const InvalidInput& e) {
    std::cerr << "breastfit: error: " << e.what() << "\n";
    return kExitInvalidInput;
  } catch (const std::bad_alloc&) {
    std::cerr << "breastfit: error: out of memory\n";
    return kExitFailure;
  } catch (const std::exception& e) {
    std::cerr << "breastfit: internal error: " << e.what() << "\n";
    return kExitFailure;
  }
  return exit_code;
}

}  // namespace breastfit::cli
