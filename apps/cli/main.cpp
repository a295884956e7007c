// breastfit: registers a rigged template torso to a 3D breast scan and transfers surgical drawings.
#include <iostream>

#include "breastfit/core/errors.h"
#include "breastfit/core/heap_reuse.h"
#include "command_support.h"
#include "commands.h"
#include "exit_codes.h"

int main(int argc, char** argv) {
  using namespace breastfit::cli;
  breastfit::keep_freed_heap_memory();  // large scans: reuse freed memory (docs/PERFORMANCE.md)
  set_command_line(argc, argv);
  CLI::App app{"breastfit: rigged-template registration of breast scans and transfer of surgical drawings"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "breastfit 0.1.0");
  int exit_code = kExitOk;
  for (RegisterFn reg : kCommands) reg(app, exit_code);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? kExitOk : kExitUsage;
  } catch (const breastfit::IoError& e) {
    std::cerr << "breastfit: error: " << e.what() << "\n";
    return kExitIoError;
  } catch (const breastfit::InvalidInput& e) {
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
