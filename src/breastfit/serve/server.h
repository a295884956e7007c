#pragma once
/// \file `breastfit serve`: the workstation's HTTP server (cpp-httplib). It serves the page
/// (web/) and a JSON API over the workspace: list files, upload, open a scan (read and indexed
/// once), suggest its landmarks, fit it with placed landmarks (one job per scan at a time,
/// progress streamed as Server-Sent Events, cancellable, warm-started re-fits), import/export landmarks and export the registration's output set.
/// Every request needs the token (query `token`, header `X-Breastfit-Token` or the cookie the
/// page gets) and a Host/Origin of this server (request_guard.h); every path is confined to the
/// workspace (workspace.h); nothing is overwritten unless the request says so.
#include <cstddef>
#include <filesystem>
#include <memory>
#include <string>

#include "breastfit/fit/fit_options.h"
#include "breastfit/model/rigged_model.h"

namespace breastfit::serve {

struct ServerOptions {
  std::filesystem::path workspace;       ///< the directory the page may read and write
  std::filesystem::path web_root;        ///< the page's files (index.html, app.js, vendor/three/...)
  std::string host = "127.0.0.1";        ///< listening address
  int port = 0;                          ///< 0: any free port
  std::string token;                     ///< empty: a random one
  size_t max_upload_bytes = 500u << 20;  ///< larger uploads are refused (413) with a message
  std::shared_ptr<const model::RiggedModel> model;  ///< the template (nullptr: the shipped default)
  fit::FitOptions fit_options;
};

class Server {
 public:
  /// Checks the workspace and web root, loads the template and binds the socket.
  /// \throws IoError when the workspace or web root is missing or the address cannot be bound
  explicit Server(ServerOptions options);
  ~Server();
  Server(const Server&) = delete;
  Server& operator=(const Server&) = delete;

  int port() const;
  const std::string& token() const;
  /// The URL to open: http://host:port/?token=...
  std::string url() const;

  /// Serves until stop() (blocks; call it on its own thread). Returns at once after stop().
  void run();
  /// Stops run() (from any thread, before or while it runs; e.g. on Ctrl-C). Running fits are
  /// cancelled.
  void stop();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Where the installed page is: `share/breastfit/web` next to the executable's `bin/`, else the
/// build tree's copy (compile-time path). Empty when neither has index.html.
std::filesystem::path default_web_root(const std::filesystem::path& executable);

}  // namespace breastfit::serve
