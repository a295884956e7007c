// HTTP-level tests of `breastfit serve`'s server: real requests with httplib::Client on
// 127.0.0.1 (an ephemeral port) against a workspace holding a synthetic case.
#include "breastfit/serve/server.h"

#include <httplib.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstring>
#include <functional>
#include <fstream>
#include <thread>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "breastfit/io/io.h"
#include "breastfit/io/markups.h"
#include "breastfit/pipeline/register_outputs.h"
#include "breastfit/synth/case_writer.h"
#include "breastfit/synth/synth_case.h"
#include "support/default_template.h"
#include "support/test_paths.h"

namespace breastfit::serve {
namespace {
namespace fs = std::filesystem;
using nlohmann::json;

// A workspace with one synthetic case (cases/a/scan.ply + landmarks.mrk.json), a second copy of
// it (cases/b), a file outside it and a page directory.
struct Fixture {
  fs::path dir = test::temp_dir();
  fs::path workspace = dir / "ws";
  fs::path web = dir / "web";
  std::vector<NamedPoint> landmarks_mm;
  Fixture() {
    synth::SynthOptions o;
    o.seed = 3;
    const synth::SynthCase c = synth::make_case(*test::default_template(), o);
    synth::write_case(workspace / "cases" / "a", c, false);
    synth::write_case(workspace / "cases" / "b", c, false);
    landmarks_mm = c.input_landmarks;
    fs::create_directories(web);
    std::ofstream(web / "index.html") << "<!doctype html><title>breastfit</title>";
    std::ofstream(dir / "secret.ply") << "not yours";
    fs::create_symlink(dir / "secret.ply", workspace / "escape.ply");
  }
};

Fixture& fixture() {
  static Fixture f;
  return f;
}

// A server on its own thread, stopped and joined at the end of the test.
struct RunningServer {
  std::unique_ptr<Server> server;
  std::thread thread;
  explicit RunningServer(ServerOptions o) {
    o.workspace = fixture().workspace;
    o.web_root = fixture().web;
    o.model = test::default_template();
    server = std::make_unique<Server>(std::move(o));
    thread = std::thread([this] { server->run(); });
  }
  ~RunningServer() {
    server->stop();
    thread.join();
  }
  httplib::Client client(bool with_token = true) const {
    httplib::Client c("127.0.0.1", server->port());
    c.set_read_timeout(60, 0);
    if (with_token) c.set_default_headers({{"X-Breastfit-Token", server->token()}});
    return c;
  }
};

// Options of a fit long enough to be caught running: no convergence test ends a stage early.
ServerOptions long_fit() {
  ServerOptions o;
  o.fit_options.solver.function_tolerance = 1e-300;
  o.fit_options.solver.gradient_tolerance = 0;
  o.fit_options.solver.parameter_tolerance = 0;
  for (auto* st : o.fit_options.stages()) st->max_iterations = 400;
  return o;
}

json body(const httplib::Result& r) { return json::parse(r->body); }

json landmarks_json() {
  json a = json::array();
  for (const auto& p : fixture().landmarks_mm)
    a.push_back({{"name", p.name}, {"position", {p.position.x(), p.position.y(), p.position.z()}}});
  return a;
}

std::string open_scan(httplib::Client& c, const std::string& path) {
  const auto r = c.Post("/api/scans", json{{"path", path}}.dump(), "application/json");
  EXPECT_TRUE(r);
  EXPECT_EQ(r->status, 200) << r->body;
  return body(r)["id"].get<std::string>();
}

json wait_fit(httplib::Client& c, const std::string& id) {
  for (int i = 0; i < 1200; ++i) {
    const auto r = c.Get(("/api/scans/" + id + "/fit").c_str());
    EXPECT_EQ(r->status, 200);
    json j = body(r);
    if (j["state"] != "running") return j;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  ADD_FAILURE() << "the fit did not end within 60 s";
  return {};
}

// A scan's event stream read to its end: each event's name and data.
std::vector<std::pair<std::string, json>> read_events(httplib::Client& c, const std::string& id,
                                                       const std::function<void(const std::string&)>& on_event = {}) {
  std::string text;
  std::vector<std::pair<std::string, json>> events;
  const auto r = c.Get(("/api/scans/" + id + "/events").c_str(), [&](const char* data, size_t n) {
    text.append(data, n);
    for (size_t end; (end = text.find("\n\n")) != std::string::npos; text.erase(0, end + 2)) {
      const std::string block = text.substr(0, end);
      if (block.rfind("event: ", 0) != 0) continue;  // a comment (": waiting")
      const size_t nl = block.find('\n');
      const std::string name = block.substr(7, nl - 7);
      EXPECT_EQ(block.compare(nl + 1, 6, "data: "), 0) << block;
      events.emplace_back(name, json::parse(block.substr(nl + 7)));
      if (on_event) on_event(name);
    }
    return true;
  });
  EXPECT_TRUE(r);
  if (r) {
    EXPECT_EQ(r->status, 200);
    EXPECT_EQ(r->get_header_value("Content-Type"), "text/event-stream");
  }
  return events;
}

TEST(Server, EveryRequestNeedsTheToken) {
  RunningServer s({});
  auto anonymous = s.client(false);
  for (const char* path : {"/", "/api/files", "/web/index.html"}) {
    const auto r = anonymous.Get(path);
    ASSERT_TRUE(r);
    EXPECT_EQ(r->status, 403) << path;
    EXPECT_NE(r->body.find("no access token"), std::string::npos) << r->body;
  }
  const auto wrong = anonymous.Get("/api/files?token=00000000000000000000000000000000");
  EXPECT_EQ(wrong->status, 403);
  EXPECT_NE(wrong->body.find("wrong access token"), std::string::npos);

  // The printed URL: the page is served and a cookie carries the token from then on.
  const auto page = anonymous.Get(("/?token=" + s.server->token()).c_str());
  ASSERT_EQ(page->status, 200);
  EXPECT_NE(page->body.find("breastfit"), std::string::npos);
  const std::string cookie = page->get_header_value("Set-Cookie");
  EXPECT_NE(cookie.find("HttpOnly"), std::string::npos);
  EXPECT_NE(cookie.find("SameSite=Strict"), std::string::npos);
  const auto with_cookie = anonymous.Get("/api/files", {{"Cookie", cookie.substr(0, cookie.find(';'))}});
  EXPECT_EQ(with_cookie->status, 200);
  auto c = s.client();
  const auto files = c.Get("/api/files");
  ASSERT_EQ(files->status, 200);
  const json list = body(files)["files"];
  EXPECT_NE(std::find(list.begin(), list.end(), "cases/a/scan.ply"), list.end());
  EXPECT_EQ(std::find(list.begin(), list.end(), "escape.ply"), list.end());  // a link leading out
}

TEST(Server, HostAndOriginMustBeThisServer) {
  RunningServer s({});
  auto c = s.client();
  // DNS rebinding: a page of evil.example whose name now resolves to 127.0.0.1.
  const auto rebound = c.Get("/api/files", {{"Host", "evil.example:" + std::to_string(s.server->port())}});
  EXPECT_EQ(rebound->status, 403);
  EXPECT_NE(rebound->body.find("Host"), std::string::npos);
  const auto cross = c.Get("/api/files", {{"Origin", "http://evil.example"}});
  EXPECT_EQ(cross->status, 403);
  const auto same = c.Get("/api/files", {{"Origin", "http://127.0.0.1:" + std::to_string(s.server->port())}});
  EXPECT_EQ(same->status, 200);
}

TEST(Server, PathsStayInTheWorkspace) {
  RunningServer s({});
  auto c = s.client();
  for (const std::string bad : {"../secret.ply", "/etc/passwd", "cases/../../secret.ply", "escape.ply"}) {
    const auto r = c.Post("/api/scans", json{{"path", bad}}.dump(), "application/json");
    EXPECT_EQ(r->status, 400) << bad;
    EXPECT_NE(body(r)["error"].get<std::string>().find("path '" + bad + "'"), std::string::npos) << r->body;
  }
  EXPECT_EQ(c.Get("/api/download?path=..%2Fsecret.ply")->status, 400);
  EXPECT_EQ(c.Get("/api/download?path=escape.ply")->status, 400);
  EXPECT_EQ(c.Post("/api/upload?name=..%2Fplanted.ply", "x", "application/octet-stream")->status, 400);
  EXPECT_FALSE(fs::exists(fixture().dir / "planted.ply"));
  // The page's files are confined to the web root the same way.
  EXPECT_NE(c.Get("/web/..%2F..%2Fsecret.ply")->status, 200);
  // The export directory too.
  const std::string id = open_scan(c, "cases/a/scan.ply");
  EXPECT_EQ(c.Post(("/api/scans/" + id + "/export").c_str(), json{{"dir", "../out"}}.dump(), "application/json")->status,
            400);
}

TEST(Server, UploadsAreLimitedAndNeverOverwrite) {
  ServerOptions o;
  o.max_upload_bytes = 1024;
  RunningServer s(o);
  auto c = s.client();
  const auto big = c.Post("/api/upload?name=uploads%2Fbig.ply", std::string(4096, 'x'), "application/octet-stream");
  ASSERT_TRUE(big);
  EXPECT_EQ(big->status, 413);
  EXPECT_NE(big->body.find("too large"), std::string::npos) << big->body;
  EXPECT_FALSE(fs::exists(fixture().workspace / "uploads" / "big.ply"));
  const auto small = c.Post("/api/upload?name=uploads%2Fsmall.txt", "hello", "application/octet-stream");
  EXPECT_EQ(small->status, 201) << small->body;
  const auto again = c.Post("/api/upload?name=uploads%2Fsmall.txt", "other", "application/octet-stream");
  EXPECT_EQ(again->status, 409);
  std::ifstream in(fixture().workspace / "uploads" / "small.txt");
  std::string text;
  in >> text;
  EXPECT_EQ(text, "hello");
}

TEST(Server, ABadFileGivesAMessageAndTheServerKeepsServing) {
  RunningServer s({});
  auto c = s.client();
  ASSERT_EQ(c.Post("/api/upload?name=bad%2Fhostile.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 99999999999\nend_header\n",
                   "application/octet-stream")->status, 201);
  const auto r = c.Post("/api/scans", json{{"path", "bad/hostile.ply"}}.dump(), "application/json");
  EXPECT_EQ(r->status, 400);
  EXPECT_NE(body(r)["error"].get<std::string>().find("hostile.ply"), std::string::npos) << r->body;
  EXPECT_EQ(c.Post("/api/scans", "{not json", "application/json")->status, 400);
  const std::string id = open_scan(c, "cases/a/scan.ply");
  const auto bad_landmarks = c.Post(("/api/scans/" + id + "/fit").c_str(),
                                    json{{"landmarks", {{{"name", "nipple_R"}, {"position", {1, "x", 3}}}}}}.dump(),
                                    "application/json");
  EXPECT_EQ(bad_landmarks->status, 400);
  EXPECT_EQ(c.Get("/api/files")->status, 200);
}

TEST(Server, OneFitPerScanAtATimeAndCancel) {
  RunningServer s(long_fit());
  auto a = s.client();
  auto b = s.client();  // a second window
  const std::string id = open_scan(a, "cases/b/scan.ply");
  EXPECT_EQ(open_scan(b, "cases/b/scan.ply"), id);  // the same session: read and indexed once
  const std::string fit = "/api/scans/" + id + "/fit";
  const auto started = a.Post(fit.c_str(), json{{"landmarks", landmarks_json()}}.dump(), "application/json");
  ASSERT_EQ(started->status, 202) << started->body;
  const auto refused = b.Post(fit.c_str(), json{{"landmarks", landmarks_json()}}.dump(), "application/json");
  EXPECT_EQ(refused->status, 409);
  EXPECT_NE(body(refused)["error"].get<std::string>().find("already running"), std::string::npos);
  const auto no_suggest = b.Post(("/api/scans/" + id + "/suggest").c_str(), "", "application/json");
  EXPECT_EQ(no_suggest->status, 409);
  EXPECT_NE(body(no_suggest)["error"].get<std::string>().find("a fit of this scan is already running"), std::string::npos);
  // Another scan is not blocked.
  const std::string other = open_scan(b, "cases/a/scan.ply");
  EXPECT_NE(other, id);
  EXPECT_EQ(b.Get(("/api/scans/" + other + "/fit").c_str())->status, 200);

  EXPECT_EQ(b.Post(("/api/scans/" + id + "/cancel").c_str(), "", "application/json")->status, 200);
  const json end = wait_fit(a, id);
  EXPECT_EQ(end["state"], "cancelled") << end.dump();
  EXPECT_LT(end["iterations"].get<int>(), 5 * 400);
  EXPECT_TRUE(end["result"].is_null());
  EXPECT_EQ(b.Post(fit.c_str(), "{}", "application/json")->status, 400);  // no landmarks
}

TEST(Server, FitWarmRefitAndExport) {
  RunningServer s({});
  auto c = s.client();
  const std::string id = open_scan(c, "cases/a/scan.ply");
  const std::string fit = "/api/scans/" + id + "/fit";
  ASSERT_EQ(c.Post(fit.c_str(), json{{"landmarks", landmarks_json()}}.dump(), "application/json")->status, 202);
  const json first = wait_fit(c, id);
  ASSERT_EQ(first["state"], "done") << first.dump();
  const json& r = first["result"];
  EXPECT_TRUE(r["usable"].get<bool>());
  EXPECT_EQ(r["status"], "ok");  // a synthetic torso is plausible
  EXPECT_FALSE(r["warm"].get<bool>());
  EXPECT_GE(r["drawings"].size(), 2u);
  EXPECT_EQ(r["drawings"][0]["colour"].get<std::string>().size(), 7u);
  EXPECT_EQ(r["model_landmarks"].size(), 12u);
  EXPECT_EQ(r["landmark_checks"].size(), 12u);
  EXPECT_EQ(r["fitted"]["distances_mm"].size() * 3, r["fitted"]["vertices"].size());

  // Move one landmark by 4 mm and re-fit from the previous parameters.
  json moved = landmarks_json();
  moved[0]["position"][2] = moved[0]["position"][2].get<double>() + 4.0;
  ASSERT_EQ(c.Post(fit.c_str(), json{{"landmarks", moved}, {"warm", true}}.dump(), "application/json")->status, 202);
  const json second = wait_fit(c, id);
  ASSERT_EQ(second["state"], "done") << second.dump();
  EXPECT_TRUE(second["result"]["warm"].get<bool>());
  EXPECT_TRUE(second["result"]["usable"].get<bool>());
  EXPECT_EQ(second["result"]["generation"], 2);

  // Export: the output set of `register`; an existing set is not overwritten without asking.
  const std::string exp = "/api/scans/" + id + "/export";
  const auto written = c.Post(exp.c_str(), json{{"dir", "fits/a"}}.dump(), "application/json");
  ASSERT_EQ(written->status, 200) << written->body;
  const fs::path out = fixture().workspace / "fits" / "a";
  for (const auto& name : pipeline::register_output_names()) EXPECT_TRUE(fs::exists(out / name)) << name;
  const Markups drawings = io::read_markups(out / "drawings.mrk.json");
  EXPECT_GE(drawings.curves.size(), 2u);
  const auto refused = c.Post(exp.c_str(), json{{"dir", "fits/a"}}.dump(), "application/json");
  EXPECT_EQ(refused->status, 409);
  EXPECT_TRUE(body(refused)["exists"].get<bool>());
  EXPECT_EQ(c.Post(exp.c_str(), json{{"dir", "fits/a"}, {"overwrite", true}}.dump(), "application/json")->status, 200);
  // Into the scan's own folder, whose landmarks.mrk.json was imported: an input is never
  // overwritten, even when the user confirms.
  ASSERT_EQ(c.Post(("/api/scans/" + id + "/landmarks/import").c_str(),
                   json{{"path", "cases/a/landmarks.mrk.json"}}.dump(), "application/json")->status, 200);
  const auto input = c.Post(exp.c_str(), json{{"dir", "cases/a"}, {"overwrite", true}}.dump(), "application/json");
  EXPECT_EQ(input->status, 400);
  EXPECT_NE(body(input)["error"].get<std::string>().find("landmarks.mrk.json"), std::string::npos) << input->body;
  EXPECT_FALSE(fs::exists(fixture().workspace / "cases" / "a" / "report.json"));
  const auto report = c.Get("/api/download?path=fits%2Fa%2Freport.html");
  EXPECT_EQ(report->status, 200);
  EXPECT_NE(report->body.find("<html"), std::string::npos);
}

// Standing <-> supine: two fitted scans of one patient; here the same synthetic scan twice, so the
// drawings mapped from one must land on the other's own drawings.
TEST(Server, MapsTheDrawingsOfAnotherFittedScan) {
  RunningServer s({});
  auto c = s.client();
  const std::string a = open_scan(c, "cases/a/scan.ply");
  const std::string b = open_scan(c, "cases/b/scan.ply");
  const std::string map = "/api/scans/" + b + "/map";
  const auto early = c.Post(map.c_str(), json{{"from", a}}.dump(), "application/json");
  EXPECT_EQ(early->status, 400);
  EXPECT_NE(body(early)["error"].get<std::string>().find("usable fit first"), std::string::npos) << early->body;
  json fits;
  for (const std::string& id : {a, b}) {
    ASSERT_EQ(c.Post(("/api/scans/" + id + "/fit").c_str(), json{{"landmarks", landmarks_json()}}.dump(),
                     "application/json")->status, 202);
    fits[id] = wait_fit(c, id);
    ASSERT_EQ(fits[id]["state"], "done");
  }
  const json list = body(c.Get("/api/scans"))["scans"];
  ASSERT_GE(list.size(), 2u);
  EXPECT_EQ(c.Post(map.c_str(), json{{"from", b}}.dump(), "application/json")->status, 400);  // itself
  const auto mapped = c.Post(map.c_str(), json{{"from", a}}.dump(), "application/json");
  ASSERT_EQ(mapped->status, 200) << mapped->body;
  const json curves = body(mapped)["curves"];
  const json own = fits[b]["result"]["drawings"];
  ASSERT_EQ(curves.size(), own.size());
  for (size_t k = 0; k < curves.size(); ++k) {
    EXPECT_EQ(curves[k]["name"], own[k]["name"]);
    EXPECT_EQ(curves[k]["colour"], own[k]["colour"]);
    // Every mapped point lies near B's own drawing of the same name.
    const auto& p = curves[k]["points"];
    const auto& q = own[k]["points"];
    double worst = 0;
    for (size_t i = 0; i < p.size(); i += 3) {
      double best = 1e9;
      for (size_t j = 0; j < q.size(); j += 3) {
        const Vec3 d(p[i].get<double>() - q[j].get<double>(), p[i + 1].get<double>() - q[j + 1].get<double>(),
                     p[i + 2].get<double>() - q[j + 2].get<double>());
        best = std::min(best, d.norm());
      }
      worst = std::max(worst, best);
    }
    EXPECT_LT(worst, 5.0) << curves[k]["name"];
    EXPECT_GT(curves[k]["confidence"]["high"].get<int>(), 0) << curves[k]["name"];
  }
}

// "Suggest": the landmarks found on the open scan, each near the synthetic truth, with a
// confidence; a fit asked meanwhile is refused; the suggested landmarks then fit.
TEST(Server, SuggestsTheLandmarks) {
  RunningServer s({});
  auto c = s.client();
  const std::string id = open_scan(c, "cases/a/scan.ply");
  const auto started = c.Post(("/api/scans/" + id + "/suggest").c_str(), "", "application/json");
  ASSERT_EQ(started->status, 202) << started->body;
  const auto busy = c.Post(("/api/scans/" + id + "/fit").c_str(), json{{"landmarks", landmarks_json()}}.dump(), "application/json");
  EXPECT_EQ(busy->status, 409);
  EXPECT_NE(body(busy)["error"].get<std::string>().find("landmark suggestion"), std::string::npos) << busy->body;
  const json end = wait_fit(c, id);
  ASSERT_EQ(end["state"], "done") << end.dump();
  EXPECT_EQ(end["job"], "suggest");
  EXPECT_TRUE(end["result"].is_null());
  const json& suggested = end["suggestion"]["landmarks"];
  ASSERT_EQ(suggested.size(), 12u);
  double sum = 0;
  for (const auto& l : suggested) {
    const auto truth = std::find_if(fixture().landmarks_mm.begin(), fixture().landmarks_mm.end(),
                                    [&](const NamedPoint& p) { return p.name == l["name"]; });
    ASSERT_NE(truth, fixture().landmarks_mm.end()) << l["name"];
    const Vec3 p(l["position"][0].get<double>(), l["position"][1].get<double>(), l["position"][2].get<double>());
    const double d = (p - truth->position).norm();
    EXPECT_LT(d, 70.0) << l["name"];  // the breast folds and tips are the hardest
    sum += d;
    EXPECT_GE(l["confidence"].get<double>(), 0.0);
    EXPECT_LE(l["confidence"].get<double>(), 1.0);
  }
  EXPECT_LT(sum / 12, 20.0);
  ASSERT_EQ(c.Post(("/api/scans/" + id + "/fit").c_str(), json{{"landmarks", suggested}}.dump(), "application/json")->status, 202);
  const json fitted = wait_fit(c, id);
  ASSERT_EQ(fitted["state"], "done") << fitted.dump();
  EXPECT_EQ(fitted["job"], "fit");
  EXPECT_TRUE(fitted["result"]["usable"].get<bool>());
  EXPECT_EQ(fitted["suggestion"]["landmarks"].size(), 12u);  // still there
}

TEST(Server, LandmarksImportAndSave) {
  RunningServer s({});
  auto c = s.client();
  const std::string id = open_scan(c, "cases/a/scan.ply");
  const auto imported = c.Post(("/api/scans/" + id + "/landmarks/import").c_str(),
                               json{{"path", "cases/a/landmarks.mrk.json"}}.dump(), "application/json");
  ASSERT_EQ(imported->status, 200) << imported->body;
  EXPECT_EQ(body(imported)["landmarks"].size(), 12u);
  const std::string save = "/api/scans/" + id + "/landmarks/export";
  const json req = {{"path", "placed/l.mrk.json"}, {"landmarks", body(imported)["landmarks"]}};
  ASSERT_EQ(c.Post(save.c_str(), req.dump(), "application/json")->status, 200);
  EXPECT_EQ(io::read_markups(fixture().workspace / "placed" / "l.mrk.json").points.size(), 12u);
  EXPECT_EQ(c.Post(save.c_str(), req.dump(), "application/json")->status, 409);
  // Download: the same file for the browser, nothing written; read back with the project's reader.
  const auto down = c.Post(("/api/scans/" + id + "/landmarks/download").c_str(),
                           json{{"name", "x/../mine.mrk.json"}, {"landmarks", body(imported)["landmarks"]}}.dump(),
                           "application/json");
  ASSERT_EQ(down->status, 200) << down->body;
  EXPECT_EQ(down->get_header_value("Content-Disposition"), "attachment; filename=\"mine.mrk.json\"");
  const Markups back = io::parse_markups(down->body, "the download").markups;
  ASSERT_EQ(back.points.size(), 12u);
  const json sent_all = body(imported)["landmarks"];
  for (size_t k = 0; k < 12; ++k) {
    const json& sent = sent_all[k];
    EXPECT_EQ(back.points[k].name, sent["name"]);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(back.points[k].position[i], sent["position"][i].get<double>(), 1e-6);
  }
  EXPECT_FALSE(fs::exists(fixture().workspace / "mine.mrk.json"));
  EXPECT_EQ(c.Post(("/api/scans/" + id + "/landmarks/download").c_str(), json{{"landmarks", 3}}.dump(), "application/json")->status,
            400);
  EXPECT_EQ(c.Post(save.c_str(), json{{"path", "cases/a/scan.ply"}, {"landmarks", json::array()}, {"overwrite", true}}.dump(),
                   "application/json")->status, 400);
}

// Progress and completion as Server-Sent Events: progress while the fit runs, then one end event
// with the result, and the stream ends; with nothing running, the end event at once.
TEST(Server, StreamsTheJobsProgressAndEnd) {
  RunningServer s({});
  auto c = s.client();
  const std::string id = open_scan(c, "cases/a/scan.ply");
  const auto idle = read_events(c, id);
  ASSERT_EQ(idle.size(), 1u);
  EXPECT_EQ(idle[0].first, "end");
  EXPECT_EQ(idle[0].second["state"], "idle");
  ASSERT_EQ(c.Post(("/api/scans/" + id + "/fit").c_str(), json{{"landmarks", landmarks_json()}}.dump(), "application/json")->status, 202);
  const auto events = read_events(c, id);
  ASSERT_GE(events.size(), 2u);
  EXPECT_EQ(events.front().first, "progress");
  EXPECT_EQ(events.front().second["job"], "fit");
  EXPECT_FALSE(events.front().second.contains("result"));  // progress only
  int last_iterations = 0;
  for (size_t k = 0; k + 1 < events.size(); ++k) {
    EXPECT_EQ(events[k].first, "progress");
    EXPECT_GE(events[k].second["iterations"].get<int>(), last_iterations);
    last_iterations = events[k].second["iterations"].get<int>();
  }
  EXPECT_EQ(events.back().first, "end");
  EXPECT_EQ(events.back().second["state"], "done");
  EXPECT_TRUE(events.back().second["result"]["usable"].get<bool>());
  EXPECT_GE(events.back().second["iterations"].get<int>(), last_iterations);
}

// A re-fit's stream: progress, then a "result" event with the fitted model and drawings (complete
// false, no distances and measurements yet), then the end with the whole result of the same re-fit.
TEST(Server, StreamsARefitsFirstResultBeforeItsEnd) {
  ServerOptions o;
  o.fit_options.refit.max_iterations = 20;  // long enough for the stream to see it run
  o.fit_options.refit.vertex_tolerance_mm = 0;
  RunningServer s(o);
  auto c = s.client();
  const std::string id = open_scan(c, "cases/a/scan.ply");
  const std::string fit = "/api/scans/" + id + "/fit";
  ASSERT_EQ(c.Post(fit.c_str(), json{{"landmarks", landmarks_json()}}.dump(), "application/json")->status, 202);
  ASSERT_EQ(wait_fit(c, id)["state"], "done");
  json moved = landmarks_json();
  moved[2]["position"][0] = moved[2]["position"][0].get<double>() + 10.0;
  ASSERT_EQ(c.Post(fit.c_str(), json{{"landmarks", moved}, {"warm", true}}.dump(), "application/json")->status, 202);
  const auto events = read_events(c, id);
  ASSERT_GE(events.size(), 2u);
  size_t k = 0;
  while (k < events.size() && events[k].first == "progress") ++k;
  ASSERT_LT(k + 1, events.size());
  ASSERT_EQ(events[k].first, "result");
  const json& first = events[k].second["result"];
  ASSERT_EQ(events[k + 1].first, "end");
  const json& whole = events[k + 1].second["result"];
  EXPECT_FALSE(first["complete"].get<bool>());
  EXPECT_TRUE(whole["complete"].get<bool>());
  EXPECT_TRUE(whole["warm"].get<bool>());
  EXPECT_EQ(first["generation"], whole["generation"]);
  EXPECT_EQ(first["fitted"]["vertices"], whole["fitted"]["vertices"]);
  EXPECT_EQ(first["drawings"], whole["drawings"]);
  EXPECT_LE(first["surface_ms"].get<double>(), whole["server_ms"].get<double>());
  EXPECT_EQ(first["surface_ms"], whole["surface_ms"]);
  EXPECT_TRUE(first["landmark_checks"].empty());
  EXPECT_TRUE(first["fitted"]["distances_mm"].empty());
  EXPECT_FALSE(whole["fitted"]["distances_mm"].empty());
  EXPECT_FALSE(whole["landmark_checks"].empty());
  EXPECT_EQ(events[k + 1].second["state"], "done");
}

// Cancel while the page listens: the stream ends with the cancellation. Stopping the server (as
// Ctrl-C does) with a stream open returns at once.
TEST(Server, CancelWhileStreamingAndStopWithAStreamOpen) {
  auto s = std::make_unique<RunningServer>(long_fit());
  auto c = s->client();
  auto canceller = s->client();
  const std::string id = open_scan(c, "cases/b/scan.ply");
  const std::string fit = "/api/scans/" + id + "/fit";
  ASSERT_EQ(c.Post(fit.c_str(), json{{"landmarks", landmarks_json()}}.dump(), "application/json")->status, 202);
  bool cancelled = false;
  const auto events = read_events(c, id, [&](const std::string&) {
    if (!cancelled) cancelled = canceller.Post(("/api/scans/" + id + "/cancel").c_str(), "", "application/json")->status == 200;
  });
  ASSERT_FALSE(events.empty());
  EXPECT_EQ(events.back().first, "end");
  EXPECT_EQ(events.back().second["state"], "cancelled") << events.back().second.dump();

  ASSERT_EQ(c.Post(fit.c_str(), json{{"landmarks", landmarks_json()}}.dump(), "application/json")->status, 202);
  std::atomic<int> seen{0};
  std::thread listener([&] {
    auto l = s->client();  // the stream is cut by the stop: its result is an error
    l.Get(("/api/scans/" + id + "/events").c_str(), [&](const char*, size_t) { ++seen; return true; });
  });
  while (seen == 0) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  const auto t0 = std::chrono::steady_clock::now();
  s.reset();  // stop() + join, with the stream open
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 5.0);
  listener.join();
}

// A textured OBJ (the synthetic scan with texture coordinates, its .mtl and image): the page gets
// the image and the coordinates per face corner; an image outside the workspace is refused and
// the scan shown shaded.
TEST(Server, ServesATexturedObjsImageAndCoordinates) {
  const fs::path dir = fixture().workspace / "textured";
  fs::create_directories(dir);
  TriangleMesh m = io::read_mesh(fixture().workspace / "cases" / "a" / "scan.ply");
  m.UV.resize(m.V.rows(), 2);
  for (Eigen::Index i = 0; i < m.V.rows(); ++i) m.UV.row(i) << (i % 7) / 7.0, (i % 5) / 5.0;
  m.FUV = m.F;
  io::write_mesh(dir / "plain.obj", m);
  std::ifstream in(dir / "plain.obj");
  const std::string obj((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::ofstream(dir / "scan.obj") << "mtllib scan.mtl\n" << obj;
  std::ofstream(dir / "out.obj") << "mtllib out.mtl\n" << obj;
  std::ofstream(dir / "scan.mtl") << "newmtl skin\nmap_Kd skin.png\n";
  std::ofstream(dir / "out.mtl") << "newmtl skin\nmap_Kd ../../secret.png\n";
  const std::string png = "\x89PNG\r\n\x1a\nnot decoded by the server";
  std::ofstream(dir / "skin.png", std::ios::binary) << png;

  RunningServer s({});
  auto c = s.client();
  const auto opened = c.Post("/api/scans", json{{"path", "textured/scan.obj"}}.dump(), "application/json");
  ASSERT_EQ(opened->status, 200) << opened->body;
  EXPECT_TRUE(body(opened)["textured"].get<bool>());
  const std::string id = body(opened)["id"];
  const auto image = c.Get(("/api/scans/" + id + "/texture").c_str());
  ASSERT_EQ(image->status, 200) << image->body;
  EXPECT_EQ(image->body, png);
  EXPECT_EQ(image->get_header_value("Content-Type"), "image/png");
  const auto uv = c.Get(("/api/scans/" + id + "/uv").c_str());
  ASSERT_EQ(uv->status, 200);
  const auto faces = body(opened)["faces"].get<size_t>();
  ASSERT_EQ(uv->body.size(), faces * 3 * 2 * sizeof(float));
  float u = 0;  // corner 1 of face 0
  std::memcpy(&u, uv->body.data() + 2 * sizeof(float), sizeof u);
  EXPECT_FLOAT_EQ(u, static_cast<float>((m.F(0, 1) % 7) / 7.0));

  const auto outside = c.Post("/api/scans", json{{"path", "textured/out.obj"}}.dump(), "application/json");
  ASSERT_EQ(outside->status, 200) << outside->body;
  EXPECT_FALSE(body(outside)["textured"].get<bool>());
  EXPECT_NE(body(outside)["warnings"].dump().find("shown shaded"), std::string::npos) << outside->body;
  EXPECT_EQ(c.Get(("/api/scans/" + body(outside)["id"].get<std::string>() + "/texture").c_str())->status, 400);
  const std::string ply = open_scan(c, "cases/a/scan.ply");
  EXPECT_EQ(c.Get(("/api/scans/" + ply + "/texture").c_str())->status, 400);
  EXPECT_EQ(c.Get(("/api/scans/" + ply + "/uv").c_str())->status, 400);
}

TEST(Server, StopEndsRun) {
  auto s = std::make_unique<RunningServer>(ServerOptions{});
  const int port = s->server->port();
  s.reset();  // stop() + join: returns
  httplib::Client c("127.0.0.1", port);
  c.set_connection_timeout(1, 0);
  EXPECT_FALSE(c.Get("/"));
}

}  // namespace
}  // namespace breastfit::serve
