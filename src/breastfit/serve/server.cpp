#include "breastfit/serve/server.h"

// The only file of the library that includes cpp-httplib (Debian's compiled library: the header
// declares, libcpp-httplib.so implements).
#include <httplib.h>

#include <atomic>
#include <chrono>
#include <fstream>
#include <map>
#include <thread>
#include <mutex>
#include <nlohmann/json.hpp>

#include "breastfit/core/errors.h"
#include "breastfit/io/landmarks_io.h"
#include "breastfit/io/markups.h"
#include "breastfit/mesh/units.h"
#include "breastfit/model/template_library.h"
#include "breastfit/pipeline/register_outputs.h"
#include "breastfit/serve/request_guard.h"
#include "breastfit/serve/scan_session.h"
#include "breastfit/serve/session_json.h"
#include "breastfit/serve/workspace.h"
#include "breastfit/transfer/surface_map.h"

namespace breastfit::serve {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

const char* kTokenHeader = "X-Breastfit-Token";
const char* kCookie = "breastfit_token";

void send_json(httplib::Response& res, int status, const json& j) {
  res.status = status;
  res.set_content(j.dump(), "application/json");
}

void send_error(httplib::Response& res, int status, const std::string& message) {
  send_json(res, status, {{"error", message}});
}

// 409 for a job request while another job of the scan runs.
void send_busy(httplib::Response& res, const ScanSession& s) {
  const std::string job = s.status().job == "suggest" ? "landmark suggestion" : "fit";
  send_error(res, 409, "a " + job + " of this scan is already running (started from another window?): wait for it or cancel it");
}

std::string cookie_token(const httplib::Request& req) {
  const std::string cookies = req.get_header_value("Cookie");
  const std::string key = std::string(kCookie) + "=";
  size_t pos = 0;
  while ((pos = cookies.find(key, pos)) != std::string::npos) {
    if (pos == 0 || cookies[pos - 1] == ' ' || cookies[pos - 1] == ';') {
      const size_t start = pos + key.size();
      const size_t end = cookies.find(';', start);
      return cookies.substr(start, end == std::string::npos ? std::string::npos : end - start);
    }
    pos += key.size();
  }
  return {};
}

std::string mime_type(const fs::path& p) {
  std::string ext = p.extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext == ".html") return "text/html; charset=utf-8";
  if (ext == ".js" || ext == ".mjs") return "text/javascript; charset=utf-8";
  if (ext == ".css") return "text/css; charset=utf-8";
  if (ext == ".json") return "application/json";
  if (ext == ".png") return "image/png";
  if (ext == ".jpg" || ext == ".jpeg") return "image/jpeg";
  if (ext == ".svg") return "image/svg+xml";
  return "application/octet-stream";
}

std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  if (!in) throw IoError(p.string(), "cannot be read");
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

json parse_body(const httplib::Request& req) {
  try {
    return json::parse(req.body);
  } catch (const json::exception&) {
    throw InvalidInput("the request body is not JSON");
  }
}

std::string string_field(const json& j, const char* key) {
  if (!j.is_object() || !j.contains(key) || !j[key].is_string())
    throw InvalidInput(std::string("the request needs a string field '") + key + "'");
  return j[key].get<std::string>();
}

bool bool_field(const json& j, const char* key) {
  return j.is_object() && j.contains(key) && j[key].is_boolean() && j[key].get<bool>();
}

// The request's "landmarks" (mm) as markups.
Markups landmark_markups(const json& body) {
  Markups m;
  m.points = landmarks_from_json(body.is_object() ? body.value("landmarks", json::array()) : json::array()).points;
  return m;
}

// Landmark files are written in the scan's own units.
io::MarkupsWriteOptions markups_options(const ScanSession& s) {
  io::MarkupsWriteOptions w;
  w.units = s.scan().units == mesh::Units::Metres ? "m" : "mm";
  return w;
}

}  // namespace

struct Server::Impl {
  ServerOptions options;
  Workspace workspace;
  Workspace web;
  RequestGuard guard;
  std::shared_ptr<const model::RiggedModel> model;
  httplib::Server http;
  int port = 0;
  std::atomic<bool> stop_requested{false}, run_active{false};

  std::mutex sessions_mutex;
  std::map<std::string, std::shared_ptr<ScanSession>> sessions;  // id → session
  std::map<fs::path, std::string> session_of_path;
  std::map<std::string, std::vector<fs::path>> inputs;  // session id → the files it read (never overwritten)
  int next_id = 1;

  explicit Impl(ServerOptions o)
      : options(std::move(o)),
        workspace(options.workspace),
        web(options.web_root),
        guard(options.token.empty() ? random_token() : options.token, options.host, 0),
        model(options.model ? options.model
                            : std::make_shared<const model::RiggedModel>(model::load_default_template())) {
    if (!fs::is_regular_file(web.root() / "index.html"))
      throw IoError(options.web_root.string(), "the page's index.html is missing (is the web directory installed?)");
    port = options.port == 0 ? http.bind_to_any_port(options.host) : options.port;
    if (options.port != 0 && !http.bind_to_port(options.host, options.port)) port = -1;
    if (port <= 0)
      throw IoError(options.host + ":" + std::to_string(options.port), "cannot listen there (in use, or not an address of this machine)");
    guard = RequestGuard(guard.token(), options.host, port);
    http.set_payload_max_length(options.max_upload_bytes);
    routes();
  }

  // A textured OBJ's image when it is a file of the workspace (a library may name any path).
  // \throws InvalidInput naming the problem when it has none or it is not usable
  fs::path texture_image(const ScanSession& s) const {
    const io::ObjTexture& t = s.texture();
    if (t.image.empty())
      throw InvalidInput(s.name() + " has no texture" + (t.problem.empty() ? std::string() : ": " + t.problem));
    try {
      return workspace.existing_file(workspace.relative(t.image.lexically_normal()));
    } catch (const InvalidInput& e) {
      throw InvalidInput(s.name() + ": its texture image cannot be shown (" + e.what() + ")");
    }
  }

  std::shared_ptr<ScanSession> session(const httplib::Request& req) {
    std::lock_guard<std::mutex> lock(sessions_mutex);
    const auto it = sessions.find(req.matches[1].str());
    if (it == sessions.end()) throw InvalidInput("no open scan with id '" + req.matches[1].str() + "'");
    return it->second;
  }

  // Runs a handler, turning the library's errors into clear JSON answers (the server keeps serving).
  template <typename F>
  httplib::Server::Handler guarded(F f) {
    return [f](const httplib::Request& req, httplib::Response& res) {
      try {
        f(req, res);
      } catch (const InvalidInput& e) {
        send_error(res, 400, e.what());
      } catch (const IoError& e) {
        send_error(res, 400, e.what());
      } catch (const std::exception& e) {
        send_error(res, 500, std::string("internal error: ") + e.what());
      }
    };
  }

  void routes() {
    http.set_pre_routing_handler([this](const httplib::Request& req, httplib::Response& res) {
      std::string token = req.get_param_value("token");
      if (token.empty()) token = req.get_header_value(kTokenHeader);
      if (token.empty()) token = cookie_token(req);
      if (const auto why = guard.refuse(req.get_header_value("Host"), req.get_header_value("Origin"), token)) {
        send_error(res, 403, *why);
        return httplib::Server::HandlerResponse::Handled;
      }
      if (req.has_param("token"))  // the printed URL: the page's later requests carry the cookie
        res.set_header("Set-Cookie", std::string(kCookie) + "=" + guard.token() + "; Path=/; HttpOnly; SameSite=Strict");
      res.set_header("Cache-Control", "no-store");
      res.set_header("X-Content-Type-Options", "nosniff");
      return httplib::Server::HandlerResponse::Unhandled;
    });
    http.set_error_handler([this](const httplib::Request&, httplib::Response& res) {
      if (res.status == 413)
        send_error(res, 413, "the file is too large: the limit is " + std::to_string(options.max_upload_bytes >> 20) +
                                 " MB (breastfit serve --max-upload-mb)");
      else if (res.body.empty())
        send_error(res, res.status, "no such page or request");
    });

    http.Get("/api/files", guarded([this](const httplib::Request&, httplib::Response& res) {
      send_json(res, 200, {{"workspace", workspace.root().filename().string()}, {"files", workspace.list_files()}});
    }));

    http.Post("/api/upload", guarded([this](const httplib::Request& req, httplib::Response& res) {
      const std::string name = req.get_param_value("name");
      const fs::path p = workspace.resolve(name);
      std::error_code ec;
      if (fs::exists(p, ec)) {
        send_error(res, 409, "'" + name + "' already exists in the workspace: choose another name");
        return;
      }
      fs::create_directories(p.parent_path(), ec);
      std::ofstream out(p, std::ios::binary);
      if (!out || !out.write(req.body.data(), static_cast<std::streamsize>(req.body.size())))
        throw IoError(name, "cannot be written in the workspace");
      send_json(res, 201, {{"path", workspace.relative(p)}, {"bytes", req.body.size()}});
    }));

    http.Post("/api/scans", guarded([this](const httplib::Request& req, httplib::Response& res) {
      const std::string rel = string_field(parse_body(req), "path");
      const fs::path p = workspace.existing_file(rel);
      std::lock_guard<std::mutex> lock(sessions_mutex);  // one open at a time: a scan is read once
      std::string id;
      if (const auto it = session_of_path.find(p); it != session_of_path.end()) {
        id = it->second;
      } else {
        auto s = std::make_shared<ScanSession>(std::to_string(next_id), p, rel, model, options.fit_options);
        id = std::to_string(next_id++);
        sessions[id] = s;
        session_of_path[p] = id;
        inputs[id] = {p};
      }
      const auto& s = *sessions[id];
      std::vector<std::string> warnings = s.scan().warnings;
      bool textured = false;
      if (!s.texture().image.empty() || !s.texture().problem.empty()) {
        try {
          texture_image(s);
          textured = true;
        } catch (const InvalidInput& e) {
          warnings.push_back(std::string(e.what()) + ": shown shaded");
        }
      }
      send_json(res, 200,
                {{"id", id},
                 {"name", s.name()},
                 {"vertices", s.scan().mesh_mm.V.rows()},
                 {"faces", s.scan().mesh_mm.F.rows()},
                 {"units", std::string(mesh::units_name(s.scan().units))},
                 {"point_cloud", s.scan().was_point_cloud},
                 {"warnings", warnings},
                 {"textured", textured},
                 {"body_frame", to_json(s.body_frame())},
                 {"landmark_names", [this] {
                    json a = json::array();
                    for (const auto& l : model->landmarks) a.push_back(l.name);
                    return a;
                  }()}});
    }));

    http.Get("/api/scans", guarded([this](const httplib::Request&, httplib::Response& res) {
      json list = json::array();
      std::lock_guard<std::mutex> lock(sessions_mutex);
      for (const auto& [id, s] : sessions) {
        const FitStatus st = s->status();
        list.push_back({{"id", id}, {"name", s->name()}, {"fitted", st.outcome && st.outcome->result.usable()}});
      }
      send_json(res, 200, {{"scans", list}});
    }));

    // Standing <-> supine: the drawings of another fitted scan (A) mapped onto this one (B)
    // through the two fits (transfer::map_markups), projected onto this scan.
    http.Post(R"(/api/scans/(\d+)/map)", guarded([this](const httplib::Request& req, httplib::Response& res) {
      const std::string from = string_field(parse_body(req), "from");
      const auto b = session(req);
      std::shared_ptr<ScanSession> a;
      {
        std::lock_guard<std::mutex> lock(sessions_mutex);
        const auto it = sessions.find(from);
        if (it == sessions.end()) throw InvalidInput("no open scan with id '" + from + "'");
        a = it->second;
      }
      if (a == b) throw InvalidInput("map from another scan: this is the same one");
      const FitStatus sa = a->status(), sb = b->status();
      for (const auto* st : {&sa, &sb})
        if (!st->outcome || !st->outcome->result.usable())
          throw InvalidInput("both scans need a usable fit first ('" + (st == &sa ? a->name() : b->name()) + "' has none)");
      transfer::MapOptions mo;
      mo.projection.reject_scan_border = !b->scan().was_point_cloud;
      const auto& ra = sa.outcome->result;
      const auto& rb = sb.outcome->result;
      transfer::MapResult mapped;
      if (!b->with_target([&](const fit::ScanTarget& scan) {
            mapped = transfer::map_markups(ra.drawings_mm, ra.fitted_mm, rb.fitted_mm, &scan, mo);
          })) {
        send_error(res, 409, "this scan is being fitted: map when the fit has ended");
        return;
      }
      json j = mapped_drawings_json(mapped);
      j["from"] = a->name();
      send_json(res, 200, j);
    }));

    http.Get(R"(/api/scans/(\d+)/mesh)", guarded([this](const httplib::Request& req, httplib::Response& res) {
      res.set_content(scan_mesh_binary(session(req)->scan()), "application/octet-stream");
    }));

    // A textured scan: its image and its texture coordinates per face corner.
    http.Get(R"(/api/scans/(\d+)/texture)", guarded([this](const httplib::Request& req, httplib::Response& res) {
      const fs::path p = texture_image(*session(req));
      res.set_content(read_file(p), mime_type(p));
    }));
    http.Get(R"(/api/scans/(\d+)/uv)", guarded([this](const httplib::Request& req, httplib::Response& res) {
      const auto s = session(req);
      if (!s->scan().mesh_mm.has_texcoords()) throw InvalidInput(s->name() + " has no texture coordinates");
      res.set_content(scan_uv_binary(s->scan()), "application/octet-stream");
    }));

    http.Post(R"(/api/scans/(\d+)/fit)", guarded([this](const httplib::Request& req, httplib::Response& res) {
      const json body = parse_body(req);
      if (!body.is_object() || !body.contains("landmarks")) throw InvalidInput("the request needs 'landmarks'");
      LandmarkSet landmarks = landmarks_from_json(body["landmarks"]);
      const auto s = session(req);
      if (!s->start_fit(std::move(landmarks), bool_field(body, "warm")))
        send_busy(res, *s);
      else
        send_json(res, 202, {{"started", true}});
    }));

    // "Suggest": the 12 landmarks found on the open scan (a landmark-free fit), each with a
    // confidence; a job like a fit (one per scan at a time, progress, cancel).
    http.Post(R"(/api/scans/(\d+)/suggest)", guarded([this](const httplib::Request& req, httplib::Response& res) {
      const auto s = session(req);
      if (!s->start_suggest())
        send_busy(res, *s);
      else
        send_json(res, 202, {{"started", true}});
    }));

    http.Get(R"(/api/scans/(\d+)/fit)", guarded([this](const httplib::Request& req, httplib::Response& res) {
      const auto s = session(req);
      send_json(res, 200, to_json(s->status(), s->model()));
    }));

    // The scan's job (fit, re-fit or suggestion) as Server-Sent Events: "progress" events (job,
    // stage, iterations; at most one per 50 ms) while it runs, a "result" event with the whole
    // status and a re-fit's first result as its result (the fitted model and drawings, no distances:
    // "complete" false) when the stream saw the job run, then one "end" event with the whole status
    // (result and suggestion included), and the stream ends. It also ends when the
    // server stops (Ctrl-C never waits for a page) or the page goes away (a comment line every
    // 100 ms without news finds out).
    http.Get(R"(/api/scans/(\d+)/events)", guarded([this](const httplib::Request& req, httplib::Response& res) {
      const auto s = session(req);
      res.set_chunked_content_provider(
          "text/event-stream",
          [this, s, seen = ~uint64_t{0}, last = std::chrono::steady_clock::time_point{},
           shown = std::shared_ptr<const FitOutcome>{}, ran = false](size_t, httplib::DataSink& sink) mutable {
            using namespace std::chrono;
            FitStatus st = s->wait_status(seen, milliseconds(100));
            const bool news = st.version != seen;
            if (news && st.state == FitState::Running && steady_clock::now() < last + milliseconds(50)) {
              std::this_thread::sleep_until(last + milliseconds(50));  // progress at most every 50 ms
              st = s->status();
            }
            if (stop_requested || !sink.is_writable()) return false;
            ran = ran || st.state == FitState::Running;
            const bool first = ran && st.first && st.first != shown;  // the job's end follows on the next call
            FitStatus first_status;
            if (first) {
              shown = st.first;
              first_status = st;
              first_status.outcome = st.first;
            }
            const bool end = !first && st.state != FitState::Running;
            const std::string event = first   ? "event: result\ndata: " + to_json(first_status, *model).dump() + "\n\n"
                                      : end   ? "event: end\ndata: " + to_json(st, *model).dump() + "\n\n"
                                      : news  ? "event: progress\ndata: " + to_json(st, *model, false).dump() + "\n\n"
                                              : std::string(": waiting\n\n");
            seen = st.version;
            if (news) last = steady_clock::now();
            if (!sink.write(event.data(), event.size())) return false;
            if (end) sink.done();
            return true;
          });
    }));

    http.Post(R"(/api/scans/(\d+)/cancel)", guarded([this](const httplib::Request& req, httplib::Response& res) {
      session(req)->cancel();
      send_json(res, 200, {{"cancelling", true}});
    }));

    http.Post(R"(/api/scans/(\d+)/landmarks/import)", guarded([this](const httplib::Request& req, httplib::Response& res) {
      const std::string rel = string_field(parse_body(req), "path");
      const auto s = session(req);
      const fs::path p = workspace.existing_file(rel);
      const LandmarkSet read = io::read_landmarks(p);
      {
        std::lock_guard<std::mutex> lock(sessions_mutex);
        inputs[s->id()].push_back(p);
      }
      const LandmarkSet mm = io::landmarks_to_mm(read, s->scan().units);
      send_json(res, 200, {{"landmarks", landmarks_to_json(mm.points)}, {"warnings", read.warnings}});
    }));

    http.Post(R"(/api/scans/(\d+)/landmarks/export)", guarded([this](const httplib::Request& req, httplib::Response& res) {
      const json body = parse_body(req);
      const std::string rel = string_field(body, "path");
      const auto s = session(req);
      const fs::path p = workspace.resolve(rel);
      std::error_code ec;
      {
        std::lock_guard<std::mutex> lock(sessions_mutex);
        for (const auto& in : inputs[s->id()])
          if (p == in) throw InvalidInput("'" + rel + "' is one of the files this scan was opened with: choose another name");
      }
      if (fs::exists(p, ec) && !bool_field(body, "overwrite")) {
        send_json(res, 409, {{"error", "'" + rel + "' exists: overwrite it?"}, {"exists", true}});
        return;
      }
      fs::create_directories(p.parent_path(), ec);
      io::write_markups(p, landmark_markups(body), markups_options(*s));
      send_json(res, 200, {{"path", workspace.relative(p)}});
    }));

    // The landmarks as a 3D Slicer .mrk.json for the browser to download (nothing is written).
    http.Post(R"(/api/scans/(\d+)/landmarks/download)", guarded([this](const httplib::Request& req, httplib::Response& res) {
      const json body = parse_body(req);
      const auto s = session(req);
      std::string name = body.is_object() && body.contains("name") && body["name"].is_string()
                             ? fs::path(body["name"].get<std::string>()).filename().string()
                             : std::string();
      if (name.empty() || name.find('"') != std::string::npos) name = "landmarks.mrk.json";
      res.set_content(io::format_markups(landmark_markups(body), markups_options(*s)), "application/json");
      res.set_header("Content-Disposition", "attachment; filename=\"" + name + "\"");
    }));

    http.Post(R"(/api/scans/(\d+)/export)", guarded([this](const httplib::Request& req, httplib::Response& res) {
      const json body = parse_body(req);
      const std::string rel = string_field(body, "dir");
      const bool overwrite = bool_field(body, "overwrite");
      const auto s = session(req);
      const auto outcome = s->status().outcome;
      if (!outcome) throw InvalidInput("nothing to export yet: fit the scan first");
      const fs::path dir = workspace.resolve(rel);
      std::vector<fs::path> inputs;
      {
        std::lock_guard<std::mutex> lock(sessions_mutex);
        inputs = this->inputs[s->id()];
      }
      try {
        pipeline::check_output_dir(dir, overwrite, inputs);
      } catch (const IoError& e) {
        if (overwrite) throw;
        send_json(res, 409, {{"error", std::string(e.what()) + ": overwrite?"}, {"exists", true}});
        return;
      }
      if (outcome->result.usable())
        pipeline::write_register_outputs(dir, outcome->result, *model, overwrite, inputs);
      else
        pipeline::write_register_failure(dir, outcome->result, overwrite, inputs);
      json files = json::array();
      for (const auto& n : pipeline::register_output_names())
        if (fs::exists(dir / n)) files.push_back(workspace.relative(dir / n));
      send_json(res, 200, {{"dir", workspace.relative(dir)}, {"files", files}, {"usable", outcome->result.usable()}});
    }));

    http.Get("/api/download", guarded([this](const httplib::Request& req, httplib::Response& res) {
      const fs::path p = workspace.existing_file(req.get_param_value("path"));
      res.set_content(read_file(p), mime_type(p));
      res.set_header("Content-Disposition", "attachment; filename=\"" + p.filename().string() + "\"");
    }));

    // The page: index.html and its modules, confined to the web root.
    http.Get("/", guarded([this](const httplib::Request&, httplib::Response& res) {
      res.set_content(read_file(web.root() / "index.html"), "text/html; charset=utf-8");
    }));
    http.Get(R"(/web/(.+))", guarded([this](const httplib::Request& req, httplib::Response& res) {
      const fs::path p = web.existing_file(req.matches[1].str());
      res.set_content(read_file(p), mime_type(p));
    }));
  }
};

Server::Server(ServerOptions options) : impl_(std::make_unique<Impl>(std::move(options))) {}

Server::~Server() {
  stop();
  std::lock_guard<std::mutex> lock(impl_->sessions_mutex);
  impl_->sessions.clear();  // cancels and joins running fits
}

int Server::port() const { return impl_->port; }
const std::string& Server::token() const { return impl_->guard.token(); }

std::string Server::url() const {
  const std::string& h = impl_->options.host;
  return "http://" + (h.find(':') != std::string::npos ? "[" + h + "]" : h) + ":" + std::to_string(port()) +
         "/?token=" + token();
}

void Server::run() {
  impl_->run_active = true;
  if (!impl_->stop_requested) impl_->http.listen_after_bind();
  impl_->run_active = false;
}

void Server::stop() {
  impl_->stop_requested = true;
  {
    std::lock_guard<std::mutex> lock(impl_->sessions_mutex);
    for (auto& [id, s] : impl_->sessions) s->cancel();
  }
  // httplib's stop() does nothing before its loop runs: when run() has begun, wait for the loop.
  while (impl_->run_active && !impl_->http.is_running()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  impl_->http.stop();
}

fs::path default_web_root(const fs::path& executable) {
  std::error_code ec;
  const fs::path installed = fs::weakly_canonical(executable, ec).parent_path().parent_path() / "share" / "breastfit" / "web";
  if (fs::is_regular_file(installed / "index.html", ec)) return installed;
#ifdef BREASTFIT_BUILD_WEB_ROOT
  const fs::path built = BREASTFIT_BUILD_WEB_ROOT;
  if (fs::is_regular_file(built / "index.html", ec)) return built;
#endif
  return {};
}

}  // namespace breastfit::serve
