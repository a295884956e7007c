// breastfit serve [--workspace DIR] [--port N] [--host H] [--open]: the workstation — a local web
// page to open a scan, place landmarks, fit, look at the drawings and export (serve/server.h).
#include <pthread.h>
#include <signal.h>

#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <memory>
#include <thread>

#include "breastfit/core/errors.h"
#include "breastfit/serve/server.h"
#include "command_support.h"
#include "commands.h"

namespace breastfit::cli {
namespace fs = std::filesystem;

void register_serve(CLI::App& app, int& exit_code) {
  struct Args {
    std::string workspace = ".", host = "127.0.0.1", template_path, web_root;
    int port = 8470;
    double max_upload_mb = 500;
    bool open = false, allow_remote = false;
  };
  auto args = std::make_shared<Args>();
  auto* sub = app.add_subcommand(
      "serve", "The workstation: a local web page to open a scan, place landmarks, fit, see the drawings and export");
  sub->add_option("--workspace,-w", args->workspace,
                  "the only directory the page may read and write (scans, landmarks, exports); default: .");
  sub->add_option("--port,-p", args->port, "port (0: any free port)")->check(CLI::Range(0, 65535));
  sub->add_option("--host", args->host,
                  "listening address; anything but 127.0.0.1/localhost/::1 needs --allow-remote (patient data!)");
  sub->add_flag("--allow-remote", args->allow_remote,
                "allow --host to be an address other machines can reach (the token still protects it)");
  sub->add_option("--max-upload-mb", args->max_upload_mb, "largest file the page may upload, MB")
      ->check(CLI::PositiveNumber);
  sub->add_option("--template,-t", args->template_path, "the template; default: the shipped torso");
  sub->add_option("--web", args->web_root, "the page's directory; default: share/breastfit/web next to the binary");
  sub->add_flag("--open", args->open, "open the page in the default browser (xdg-open)");
  sub->callback([args, &exit_code] {
    const bool loopback = args->host == "127.0.0.1" || args->host == "localhost" || args->host == "::1";
    if (!loopback && !args->allow_remote)
      throw InvalidInput("--host " + args->host +
                         ": other machines could reach the server; add --allow-remote if that is what you want");
    serve::ServerOptions o;
    o.workspace = args->workspace;
    o.host = args->host == "localhost" ? "127.0.0.1" : args->host;
    o.port = args->port;
    o.max_upload_bytes = static_cast<size_t>(args->max_upload_mb * (1u << 20));
    o.web_root = args->web_root.empty() ? serve::default_web_root(fs::read_symlink("/proc/self/exe")) : fs::path(args->web_root);
    if (o.web_root.empty()) throw IoError("share/breastfit/web", "the workstation's page is not installed next to the binary (use --web DIR)");
    o.model = std::make_shared<const model::RiggedModel>(load_template(args->template_path));

    // Ctrl-C and SIGTERM are taken by a waiting thread (blocked here, before any thread starts).
    sigset_t signals;
    sigemptyset(&signals);
    sigaddset(&signals, SIGINT);
    sigaddset(&signals, SIGTERM);
    pthread_sigmask(SIG_BLOCK, &signals, nullptr);

    serve::Server server(o);
    if (!loopback)
      std::cerr << "WARNING: listening on " << o.host << ": other machines can reach this server; "
                << "anyone with the URL below can read and write the workspace\n";
    std::cout << "breastfit serve: workspace " << fs::canonical(o.workspace).string() << "\n"
              << "Open " << server.url() << "\n"
              << "(Ctrl-C stops the server)" << std::endl;
    if (args->open) {
      const std::string cmd = "xdg-open '" + server.url() + "' >/dev/null 2>&1 &";
      if (std::system(cmd.c_str()) != 0) std::cerr << "could not open a browser: open the URL above\n";
    }
    std::thread waiter([&server, signals] {
      int sig = 0;
      sigwait(&signals, &sig);
      server.stop();
    });
    server.run();
    std::cout << "breastfit serve: stopped" << std::endl;
    // run() also returns when the socket fails: wake the waiter so it can be joined.
    pthread_kill(waiter.native_handle(), SIGTERM);
    waiter.join();
    exit_code = 0;
  });
}

}  // namespace breastfit::cli
