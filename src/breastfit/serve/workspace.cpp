#include "breastfit/serve/workspace.h"

#include <algorithm>
#include <system_error>

#include "breastfit/core/errors.h"

namespace breastfit::serve {
namespace fs = std::filesystem;
namespace {

bool inside(const fs::path& root, const fs::path& p) {
  auto r = root.begin();
  auto q = p.begin();
  for (; r != root.end(); ++r, ++q)
    if (q == p.end() || *r != *q) return false;
  return true;
}

}  // namespace

Workspace::Workspace(const fs::path& root) {
  std::error_code ec;
  if (!fs::is_directory(root, ec)) throw IoError(root.string(), "the workspace is not an existing directory");
  root_ = fs::canonical(root, ec);
  if (ec) throw IoError(root.string(), "cannot resolve the workspace: " + ec.message());
}

fs::path Workspace::resolve(const std::string& relative) const {
  const auto refuse = [&](const std::string& why) {
    return InvalidInput("path '" + relative + "': " + why);
  };
  if (relative.empty()) throw refuse("empty");
  if (relative.find('\0') != std::string::npos) throw refuse("contains a NUL character");
  if (relative.find('\\') != std::string::npos) throw refuse("contains a backslash (use '/')");
  if (relative.front() == '/' || fs::path(relative).is_absolute() || fs::path(relative).has_root_name())
    throw refuse("absolute paths are refused: give a path inside the workspace");
  fs::path out = root_;
  for (const auto& part : fs::path(relative)) {
    const std::string s = part.string();
    if (s == "..") throw refuse("'..' is refused: give a path inside the workspace");
    if (s.empty() || s == ".") continue;
    out /= part;
  }
  if (out == root_) throw refuse("names the workspace itself, not a file in it");
  std::error_code ec;
  const fs::path real = fs::weakly_canonical(out, ec);
  if (ec) throw refuse("cannot be resolved: " + ec.message());
  if (!inside(root_, real) || real == root_) throw refuse("leads out of the workspace (a symbolic link?)");
  return real;
}

fs::path Workspace::existing_file(const std::string& relative) const {
  const fs::path p = resolve(relative);
  std::error_code ec;
  if (!fs::exists(p, ec)) throw InvalidInput("path '" + relative + "': no such file in the workspace");
  if (!fs::is_regular_file(p, ec)) throw InvalidInput("path '" + relative + "': not a file");
  return p;
}

std::string Workspace::relative(const fs::path& path) const {
  return path.lexically_relative(root_).generic_string();
}

std::vector<std::string> Workspace::list_files(size_t limit) const {
  std::vector<std::string> out;
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(root_, fs::directory_options::skip_permission_denied, ec);
       !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (!name.empty() && name[0] == '.') {
      if (it->is_directory(ec)) it.disable_recursion_pending();
      continue;
    }
    if (it->is_symlink(ec)) {
      const fs::path real = fs::weakly_canonical(it->path(), ec);
      if (ec || !inside(root_, real)) {
        ec.clear();
        continue;
      }
      it.disable_recursion_pending();  // no loops through links
    }
    if (it->is_regular_file(ec)) out.push_back(relative(it->path()));
    if (out.size() >= limit) break;
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace breastfit::serve
