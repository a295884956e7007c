#pragma once
/// \file The command line's program: its subcommands registered on one CLI11 app, parsed and run,
/// errors turned into one-line messages and exit codes (exit_codes.h). Shared by `breastfit`
/// (main.cpp) and `breastfit-serve` (serve_main.cpp).
#include <span>

#include "commands.h"

namespace breastfit::cli {

/// Runs the command line `argv` with `commands` as the subcommands; returns the exit code.
int run_app(int argc, char** argv, std::span<const RegisterFn> commands);

}  // namespace breastfit::cli
