#include "breastfit/io/output_set.h"

#include <algorithm>
#include <atomic>
#include <stdexcept>
#include <system_error>

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
  fs::create_directories(dir_, ec);
  if (ec) throw IoError(dir_.string(), "cannot create directory: " + ec.message());
  for (const auto& name : names_)  // nothing is moved unless every file can be
    if (fs::exists(staging_ / name, ec) && fs::is_directory(dir_ / name, ec))
      throw IoError((dir_ / name).string(), "is a directory: the output file cannot replace it");
  remove_file(dir_ / marker_);  // from here on, the set in dir_ is incomplete until the marker is back
  for (const auto& name : names_)
    if (!fs::exists(staging_ / name, ec)) remove_file(dir_ / name);
  for (const auto& name : names_)
    if (name != marker_ && fs::exists(staging_ / name, ec)) move_file(staging_ / name, dir_ / name);
  move_file(staging_ / marker_, dir_ / marker_);
  committed_ = true;
  fs::remove_all(staging_, ec);
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
