// write_register_outputs' one-set rule (io/output_set.h) under kill -9: `breastfit register
// --force` is killed at every step of writing its outputs (each file closed in the staging
// directory, the swap of the staging and output directories, each file of the previous set
// removed afterwards, watched with inotify) and the output directory must then hold the complete
// previous set or the complete new one, never a mixed or incomplete set.
#include "breastfit/pipeline/register_outputs.h"

#include <gtest/gtest.h>

#include <cerrno>
#include <chrono>
#include <filesystem>
#include <map>
#include <string>
#include <thread>
#include <vector>

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/inotify.h>
#include <sys/wait.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "breastfit/core/errors.h"
#include "breastfit/transfer/fit_directory.h"
#include "support/test_paths.h"

extern char** environ;

namespace breastfit::pipeline {
namespace {

namespace fs = std::filesystem;

using Snapshot = std::map<std::string, std::string>;  // set file name → bytes

Snapshot snapshot(const fs::path& dir) {
  Snapshot s;
  for (const auto& name : register_output_names())
    if (fs::exists(dir / name)) s[name] = test::file_bytes(dir / name);
  return s;
}

void restore(const fs::path& dir, const Snapshot& s) {
  fs::remove_all(dir);
  fs::create_directories(dir);
  for (const auto& [name, bytes] : s) {
    FILE* f = std::fopen((dir / name).c_str(), "wb");
    ASSERT_NE(f, nullptr);
    ASSERT_EQ(std::fwrite(bytes.data(), 1, bytes.size(), f), bytes.size());
    std::fclose(f);
  }
}

/// Watches the output directory and its parent (where the staging directory appears, and then
/// that staging directory): one count per file written, removed or moved, and one for the
/// directory swapped into the output directory's name.
class WriteWatcher {
 public:
  explicit WriteWatcher(const fs::path& out) : out_(out) {
    fd_ = inotify_init1(IN_NONBLOCK | IN_CLOEXEC);
    parent_ = inotify_add_watch(fd_, out.parent_path().c_str(), IN_CREATE | IN_MOVED_TO | IN_ONLYDIR);
    inotify_add_watch(fd_, out.c_str(), IN_MOVED_TO | IN_DELETE | IN_CLOSE_WRITE);
  }
  ~WriteWatcher() { close(fd_); }
  bool ok() const { return fd_ >= 0 && parent_ >= 0; }

  /// Waits up to `ms` for events; returns how many file events arrived and appends, for each,
  /// whether it happened in the output directory (the commit) rather than in the staging one.
  int poll_events(int ms, std::vector<bool>* in_out) {
    pollfd p{fd_, POLLIN, 0};
    if (::poll(&p, 1, ms) <= 0) return 0;
    alignas(inotify_event) char buf[8192];
    int n = 0;
    for (ssize_t len; (len = read(fd_, buf, sizeof buf)) > 0;)
      for (char* e = buf; e < buf + len;) {
        const auto* ev = reinterpret_cast<const inotify_event*>(e);
        const std::string name = ev->len ? ev->name : "";
        if (ev->wd == parent_) {
          if ((ev->mask & IN_CREATE) && name.rfind("." + out_.filename().string() + ".breastfit-tmp-", 0) == 0) {
            staging_ = inotify_add_watch(fd_, (out_.parent_path() / name).c_str(), IN_CLOSE_WRITE);
            ++n;  // the staging directory
            in_out->push_back(false);
          } else if ((ev->mask & IN_MOVED_TO) && name == out_.filename().string()) {
            ++n;  // the new set swapped in
            in_out->push_back(true);
          }
        } else if (!(ev->mask & IN_IGNORED)) {
          ++n;
          in_out->push_back(ev->wd != staging_);
        }
        e += sizeof(inotify_event) + ev->len;
      }
    return n;
  }

 private:
  fs::path out_;
  int fd_ = -1, parent_ = -1, staging_ = -1;
};

/// Starts `breastfit args...` (output to /dev/null); its pid.
pid_t spawn_cli(const std::vector<std::string>& args) {
  std::vector<std::string> all{test::cli_path().string()};
  all.insert(all.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : all) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&fa, 2, "/dev/null", O_WRONLY, 0);
  pid_t pid = -1;
  const int rc = posix_spawn(&pid, argv[0], &fa, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  return rc == 0 ? pid : -1;
}

/// Runs `args` and kills it with SIGKILL at the `kill_at`-th file event (never when 0);
/// true when it was killed before it exited. `events`: for each event seen, whether it was in
/// the output directory.
bool run_and_kill(const fs::path& out, const std::vector<std::string>& args, int kill_at,
                  std::vector<bool>* events = nullptr) {
  std::vector<bool> seen;
  if (!events) events = &seen;
  WriteWatcher watch(out);
  EXPECT_TRUE(watch.ok());
  const pid_t pid = spawn_cli(args);
  EXPECT_GT(pid, 0);
  if (pid <= 0) return false;
  int n = 0, status = 0;
  bool killed = false;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(2);
  while (true) {
    n += watch.poll_events(5, events);
    if (!killed && kill_at > 0 && n >= kill_at) {
      killed = ::kill(pid, SIGKILL) == 0;
    }
    const pid_t w = waitpid(pid, &status, WNOHANG);
    if (w == pid) break;
    if (std::chrono::steady_clock::now() > deadline) {
      ::kill(pid, SIGKILL);
      waitpid(pid, &status, 0);
      ADD_FAILURE() << "breastfit did not finish in 2 minutes";
      break;
    }
  }
  return killed && WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL;
}

/// Which runs may have written `bytes` as the set file `name`: the old one when it is
/// byte-identical to the old set's file, the new one when it is to the reference new run's
/// (report.json and report.html hold the time and the command line, so for them: complete and
/// with the new run's options). Both for a file the two runs write alike; neither for a partial or
/// foreign file.
struct Origins {
  bool old_run = false, new_run = false;
};
Origins origins_of(const std::string& name, const std::string& bytes, const Snapshot& old_set, const Snapshot& new_set) {
  Origins o;
  o.old_run = old_set.count(name) && old_set.at(name) == bytes;
  if (name == "report.json") {
    const auto j = nlohmann::json::parse(bytes, nullptr, false);
    o.new_run = !j.is_discarded() && bytes.find("--no-surface-detail") == std::string::npos;
  } else if (name == "report.html") {
    const bool complete = bytes.size() > 16 && bytes.find("</html>", bytes.size() - 16) != std::string::npos;
    o.new_run = complete && bytes.find("--no-surface-detail") == std::string::npos;
  } else {
    o.new_run = new_set.count(name) && new_set.at(name) == bytes;
  }
  return o;
}

TEST(RegisterOutputs, KilledAtAnyStepLeavesTheOldSetOrTheNewOne) {
  if (test::cli_path().empty()) GTEST_SKIP() << "CLI not built";
  if (const int fd = inotify_init1(IN_CLOEXEC); fd < 0) {
    GTEST_SKIP() << "inotify is not available here";
  } else {
    close(fd);
  }
  const fs::path root = test::temp_dir();
  const fs::path c = root / "case", out = root / "out", ref = root / "ref";
  ASSERT_EQ(test::run_cli("synth --quiet --seed 11 --out '" + c.string() + "'"), 0);
  const std::vector<std::string> inputs = {"register", (c / "scan.ply").string(), "--landmarks",
                                           (c / "landmarks.mrk.json").string(), "--quiet", "--threads", "1"};
  // The old set: another fit (no surface detail), no report.html; the new set: the default run.
  std::vector<std::string> old_args = inputs, new_args = inputs, ref_args = inputs;
  old_args.insert(old_args.end(), {"--no-surface-detail", "--no-report-html", "--out", out.string()});
  ref_args.insert(ref_args.end(), {"--out", ref.string()});
  new_args.insert(new_args.end(), {"--force", "--out", out.string()});
  auto run = [](const std::vector<std::string>& args) {
    const pid_t pid = spawn_cli(args);
    int status = -1;
    if (pid > 0) waitpid(pid, &status, 0);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  };
  ASSERT_EQ(run(old_args), 0);
  ASSERT_EQ(run(ref_args), 0);
  const Snapshot old_set = snapshot(out), new_set = snapshot(ref);
  ASSERT_EQ(old_set.size(), register_output_names().size() - 1);  // all but report.html
  ASSERT_EQ(new_set.size(), register_output_names().size());
  ASSERT_NE(old_set.at("fitted.ply"), new_set.at("fitted.ply"));

  // The file events of a whole run: the staging directory, each file written there, the swap,
  // then each file of the previous set removed. The kills: at the staging directory, halfway
  // through the writing, and at every event of the commit.
  std::vector<bool> events;
  restore(out, old_set);
  ASSERT_FALSE(run_and_kill(out, new_args, 0, &events));
  const int total = static_cast<int>(events.size());
  ASSERT_GE(total, static_cast<int>(register_output_names().size() + 2));
  std::vector<int> kill_points;
  for (int k = 1; k <= total; ++k)
    if (k == 1 || k == total / 4 || events[static_cast<size_t>(k - 1)]) kill_points.push_back(k);

  int old_complete = 0, new_complete = 0, incomplete = 0;
  for (const int k : kill_points) {
    restore(out, old_set);
    const bool killed = run_and_kill(out, new_args, k);
    const Snapshot now = snapshot(out);
    for (const auto& [name, bytes] : now) {
      const Origins o = origins_of(name, bytes, old_set, new_set);
      EXPECT_TRUE(o.old_run || o.new_run) << name << " is neither the old nor the new file (killed at event " << k << ")";
    }
    if (now.count("report.json")) {
      const Origins marker = origins_of("report.json", now.at("report.json"), old_set, new_set);
      ASSERT_NE(marker.old_run, marker.new_run) << k;
      const Snapshot& expected = marker.old_run ? old_set : new_set;
      EXPECT_EQ(now.size(), expected.size()) << "an incomplete set with report.json (killed at event " << k << ")";
      for (const auto& [name, bytes] : now) {
        const Origins o = origins_of(name, bytes, old_set, new_set);
        EXPECT_TRUE(marker.old_run ? o.old_run : o.new_run)
            << name << " is not from the run that wrote report.json: a mixed set (killed at event " << k << ")";
      }
      ++(marker.old_run ? old_complete : new_complete);
    } else {
      ADD_FAILURE() << "a set without report.json (killed at event " << k << ")";
      EXPECT_THROW(transfer::read_fit_directory(out), IoError) << k;  // at least refused
      ++incomplete;
    }
    if (!killed) break;  // the run finished before the k-th event: later ones cannot be reached
  }
  std::printf("%zu kills: %d old complete, %d new complete, %d without report.json (of %d events)\n",
              kill_points.size(), old_complete, new_complete, incomplete, total);
  EXPECT_GT(old_complete, 0);  // some kills landed while the outputs were being written
  EXPECT_GT(new_complete, 0);  // and some after the swap

  // A run after the kills removes their staging directories and writes the whole new set.
  ASSERT_FALSE(run_and_kill(out, new_args, 0));
  const Snapshot after = snapshot(out);
  EXPECT_EQ(after.size(), new_set.size());
  for (const auto& [name, bytes] : after) EXPECT_TRUE(origins_of(name, bytes, old_set, new_set).new_run) << name;
  for (const auto& e : fs::directory_iterator(root))
    EXPECT_EQ(e.path().filename().string().find(".breastfit-tmp-"), std::string::npos) << e.path();
}

}  // namespace
}  // namespace breastfit::pipeline
