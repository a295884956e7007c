// breastfit serve ...: runs breastfit-serve (serve_main.cpp), the workstation's program, found next
// to this binary, with the same arguments (its --help included). The workstation is a program of
// its own so that its HTTP library and what that loads (TLS, compression) are not loaded by every
// other command.
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "breastfit/core/errors.h"
#include "commands.h"

namespace breastfit::cli {
namespace fs = std::filesystem;

void register_serve_launcher(CLI::App& app, int& exit_code) {
  auto* sub = app.add_subcommand(
      "serve", "The workstation: a local web page to open a scan, place landmarks, fit, see the drawings and export");
  sub->prefix_command();  // every argument after `serve` (its --help too) goes to breastfit-serve
  sub->set_help_flag();
  sub->callback([sub] {
    const fs::path program = fs::read_symlink("/proc/self/exe").parent_path() / "breastfit-serve";
    std::vector<std::string> args{program.string(), "serve"};
    for (const std::string& a : sub->remaining()) args.push_back(a);
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    std::cout.flush();
    std::cerr.flush();
    ::execv(program.c_str(), argv.data());  // returns only when it could not run the program
    throw IoError(program.string(), std::string("cannot run the workstation's program (installed next to breastfit): ") +
                                        std::strerror(errno));
  });
}

}  // namespace breastfit::cli
