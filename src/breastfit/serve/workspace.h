#pragma once
/// \file The workstation's workspace: the one directory `breastfit serve` reads from and writes
/// into. Every path the page sends is relative to it and confined to it: absolute paths, `..`
/// components and symbolic links leading out of it are refused.
#include <filesystem>
#include <string>
#include <vector>

namespace breastfit::serve {

class Workspace {
 public:
  /// \throws IoError when `root` is not an existing directory
  explicit Workspace(const std::filesystem::path& root);

  /// The workspace directory (canonical: symbolic links resolved).
  const std::filesystem::path& root() const { return root_; }

  /// The path `relative` names inside the workspace (it need not exist yet). Accepts only
  /// relative paths of plain components ('/'-separated); the existing part of the result,
  /// symbolic links resolved, must stay inside the workspace.
  /// \throws InvalidInput naming `relative` and the problem (empty, absolute, `..`, a
  ///         backslash or NUL, leading out of the workspace)
  std::filesystem::path resolve(const std::string& relative) const;

  /// resolve() for a file that must exist and be a regular file (after symbolic links).
  /// \throws InvalidInput as resolve(), or when it does not exist or is not a file
  std::filesystem::path existing_file(const std::string& relative) const;

  /// `path` (inside the workspace) as the page names it: relative, '/'-separated.
  std::string relative(const std::filesystem::path& path) const;

  /// The regular files under the workspace (symbolic links leading out and hidden entries skipped),
  /// relative, sorted; at most `limit`.
  std::vector<std::string> list_files(size_t limit = 2000) const;

 private:
  std::filesystem::path root_;
};

}  // namespace breastfit::serve
