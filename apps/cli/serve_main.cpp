// breastfit-serve: the workstation (`breastfit serve` runs it). A program of its own so that its
// HTTP library, and the TLS and compression libraries that library loads, are not loaded by every
// other command (they cost each `breastfit` run ~10 ms of CPU before main; docs/PERFORMANCE.md).
#include "commands.h"
#include "run_app.h"

int main(int argc, char** argv) {
  static constexpr breastfit::cli::RegisterFn kServe[] = {breastfit::cli::register_serve};
  return breastfit::cli::run_app(argc, argv, kServe);
}
