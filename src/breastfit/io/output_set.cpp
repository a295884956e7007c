#include "breastfit/io/output_set.h"

#include <algorithm>
#include <atomic>
#include <stdexcept>
#include <cstdio>
#include <system_error>

#include <fcntl.h>
#include <unistd.h>

#include "breastfit/core/errors.h"

namespace breastfit::io {
namespace fs = std::filesystem;
namespace {

// `dir` as an absolute path without a trailing separator ("out/" and "out" are the same DIR).
fs::path normalized(const fs::path& dir) {
  fs::path p = fs::absolute(dir).lexically_normal();
  if (p.filename().empty()) p = p.parent_path();
  if (p.filename().empty() || p == p.root_path()) throw IoError(dir.string(), "is not a usable output directory");
  return p;
}

// The staging directories' parent and name prefix.
fs::path staging_parent(const fs::path& dir, Staging where) { return where == Staging::InsideDir ? dir : dir.parent_path(); }
std::string prefix_of(const fs::path& dir, const std::string& marker, Staging where) {
  return where == Staging::InsideDir ? "." + fs::path(marker).filename().string() + ".breastfit-tmp-" : staging_prefix(dir);
}

// Removes the staging directories that killed runs into `dir` left.
void remove_leftovers(const fs::path& dir, const std::string& marker, Staging where) {
  const std::string prefix = prefix_of(dir, marker, where);
  std::error_code ec;
  for (fs::directory_iterator it(staging_parent(dir, where), ec), end; !ec && it != end; it.increment(ec))
    if (it->path().filename().string().rfind(prefix, 0) == 0) {
      std::error_code rm;
      fs::remove_all(it->path(), rm);  // best effort: a leftover never blocks a run
    }
}

void remove_file(const fs::path& p) {
  std::error_code ec;
  fs::remove(p, ec);
  if (ec) throw IoError(p.string(), "cannot remove the previous output: " + ec.message());
}

void move_file(const fs::path& from, const fs::path& to) {
  std::error_code ec;
  fs::create_directories(to.parent_path(), ec);
  if (ec) throw IoError(to.parent_path().string(), "cannot create directory: " + ec.message());
  fs::rename(from, to, ec);
  if (ec) throw IoError(to.string(), "cannot move the output into place: " + ec.message());
}

// True when the process's working directory is `dir` or inside it: swapping `dir` would leave
// the working directory (normally the user's shell's) in the removed old directory.
bool cwd_inside(const fs::path& dir) {
  std::error_code ec;
  const fs::path cwd = fs::current_path(ec);
  if (ec) return true;
  for (fs::path p = cwd; !p.empty(); p = p.parent_path()) {
    if (fs::equivalent(p, dir, ec)) return true;
    if (p == p.root_path()) break;
  }
  return false;
}

// Hard-links into `to` every file under `from` that is not one of the set's `names` (files the
// user keeps in the output directory: same inodes, nothing copied), recreating subdirectories
// with their permissions and copying symbolic links. False when something cannot be carried
// over this way (a special file, a name taken in `to`, a file system without hard links).
bool carry_over(const fs::path& from, const fs::path& to, const std::vector<std::string>& names,
                const fs::path& rel = {}) {
  std::error_code ec;
  for (fs::directory_iterator it(from / rel, ec), end; it != end; it.increment(ec)) {
    if (ec) return false;
    const fs::path r = rel / it->path().filename();
    if (std::find(names.begin(), names.end(), r.generic_string()) != names.end()) continue;
    const fs::file_status st = it->symlink_status(ec);
    if (ec) return false;
    if (fs::is_symlink(st)) {
      fs::copy_symlink(it->path(), to / r, ec);
    } else if (fs::is_directory(st)) {
      if (!fs::is_directory(to / r, ec)) fs::create_directory(to / r, it->path(), ec);
      if (ec || !carry_over(from, to, names, r)) return false;
    } else if (fs::is_regular_file(st)) {
      fs::create_hard_link(it->path(), to / r, ec);
    } else {
      return false;
    }
    if (ec) return false;
  }
  return !ec;
}

// Swaps two directories in one step (Linux renameat2 RENAME_EXCHANGE); false where the system
// or the file system cannot.
bool exchange(const fs::path& a, const fs::path& b) {
#ifdef RENAME_EXCHANGE
  return ::renameat2(AT_FDCWD, a.c_str(), AT_FDCWD, b.c_str(), RENAME_EXCHANGE) == 0;
#else
  (void)a, (void)b;
  return false;
#endif
}

}  // namespace

std::string staging_prefix(const fs::path& dir) {
  return "." + normalized(dir).filename().string() + ".breastfit-tmp-";
}

OutputSet::OutputSet(fs::path dir, std::vector<std::string> names, std::string marker, Staging where)
    : dir_(normalized(dir)), names_(std::move(names)), marker_(std::move(marker)), where_(where) {
  if (std::find(names_.begin(), names_.end(), marker_) == names_.end())
    throw std::invalid_argument("OutputSet: the marker " + marker_ + " is not one of the names");
  std::error_code ec;
  if (fs::exists(dir_, ec) && !fs::is_directory(dir_, ec)) throw IoError(dir.string(), "exists and is not a directory");
  const fs::path parent = staging_parent(dir_, where_);
  fs::create_directories(parent, ec);
  if (ec) throw IoError(parent.string(), "cannot create directory: " + ec.message());
  remove_leftovers(dir_, marker_, where_);
  static std::atomic<int> counter{0};
  staging_ = parent / (prefix_of(dir_, marker_, where_) + std::to_string(::getpid()) + "-" + std::to_string(counter++));
  fs::remove_all(staging_, ec);
  fs::create_directory(staging_, ec);
  if (ec) throw IoError(staging_.string(), "cannot create the staging directory: " + ec.message());
}

OutputSet::~OutputSet() {
  std::error_code ec;
  fs::remove_all(staging_, ec);
}

fs::path OutputSet::path(const std::string& name) const {
  if (std::find(names_.begin(), names_.end(), name) == names_.end())
    throw std::invalid_argument("OutputSet: " + name + " is not one of the set's names");
  const fs::path p = staging_ / name;
  std::error_code ec;
  fs::create_directories(p.parent_path(), ec);
  if (ec) throw IoError(p.parent_path().string(), "cannot create directory: " + ec.message());
  return p;
}

void OutputSet::commit() {
  if (committed_) throw std::logic_error("OutputSet: committed twice");
  std::error_code ec;
  if (!fs::exists(staging_ / marker_, ec)) throw std::logic_error("OutputSet: " + marker_ + " was not written");
  for (const auto& name : names_)  // nothing is moved unless every file can be
    if (fs::exists(staging_ / name, ec) && fs::is_directory(dir_ / name, ec))
      throw IoError((dir_ / name).string(), "is a directory: the output file cannot replace it");
  if (where_ == Staging::NextToDir && swap_in()) {
    committed_ = true;
    fs::remove_all(staging_, ec);  // the previous set (and links to the carried-over files)
    return;
  }
  fs::create_directories(dir_, ec);
  if (ec) throw IoError(dir_.string(), "cannot create directory: " + ec.message());
  remove_file(dir_ / marker_);  // from here on, the set in dir_ is incomplete until the marker is back
  for (const auto& name : names_)
    if (!fs::exists(staging_ / name, ec)) remove_file(dir_ / name);
  for (const auto& name : names_)
    if (name != marker_ && fs::exists(staging_ / name, ec)) move_file(staging_ / name, dir_ / name);
  move_file(staging_ / marker_, dir_ / marker_);
  committed_ = true;
  fs::remove_all(staging_, ec);
}

bool OutputSet::swap_in() {
  std::error_code ec;
  const fs::file_status st = fs::symlink_status(dir_, ec);
  if (ec || !fs::exists(st)) {  // no previous directory: the staging directory becomes it
    std::error_code rn;
    fs::rename(staging_, dir_, rn);
    if (rn) return false;
    staging_.clear();  // nothing left to remove
    return true;
  }
  if (!fs::is_directory(st) || cwd_inside(dir_)) return false;
  if (!carry_over(dir_, staging_, names_)) return false;
  fs::permissions(staging_, st.permissions(), ec);  // a private output directory stays private
  return exchange(staging_, dir_);
}

OutputSet loose_file_set(const std::vector<fs::path>& files) {
  if (files.empty()) throw std::invalid_argument("loose_file_set: no files");
  const fs::path dir = fs::absolute(files.front()).lexically_normal().parent_path();
  std::vector<std::string> names;
  for (const auto& f : files) {
    const fs::path p = fs::absolute(f).lexically_normal();
    if (p.parent_path() != dir) throw std::invalid_argument("loose_file_set: " + f.string() + " is in another directory");
    names.push_back(p.filename().string());
  }
  return OutputSet(dir, names, names.back(), Staging::InsideDir);
}

}  // namespace breastfit::io
