#include "breastfit/cohort/cohort_case.h"

#include <algorithm>
#include <map>

#include "breastfit/core/errors.h"
#include "breastfit/io/io.h"

namespace breastfit::cohort {
namespace fs = std::filesystem;
namespace {

constexpr const char* kLandmarkSuffixes[] = {".mrk.json", ".json", ".csv", ".fcsv"};
constexpr const char* kScanNames[] = {"scan.ply", "scan.obj", "scan.stl"};

/// The first existing `prefix + suffix` of the landmark suffixes.
std::optional<fs::path> landmarks_beside(const fs::path& dir, const std::string& stem) {
  for (const char* suffix : kLandmarkSuffixes) {
    const fs::path p = dir / (stem + suffix);
    if (fs::is_regular_file(p)) return p;
  }
  return std::nullopt;
}

std::optional<fs::path> scan_in(const fs::path& dir) {
  for (const char* name : kScanNames)
    if (fs::is_regular_file(dir / name)) return dir / name;
  return std::nullopt;
}

std::string directory_name(const fs::path& dir) {
  fs::path p = fs::absolute(dir).lexically_normal();
  if (!p.has_filename()) p = p.parent_path();  // "cases/p001/"
  return p.filename().string();
}

}  // namespace

std::vector<CohortCase> resolve_case_argument(const fs::path& argument) {
  std::error_code ec;
  const fs::file_status st = fs::status(argument, ec);
  if (ec || !fs::exists(st)) throw IoError(argument.string(), "no such file or directory");
  if (fs::is_regular_file(st)) {
    if (!io::has_mesh_extension(argument))
      throw IoError(argument.string(), "not a scan (.ply .obj .stl) or a case directory");
    const std::string stem = argument.stem().string();
    return {CohortCase{stem, argument, landmarks_beside(argument.parent_path(), stem)}};
  }
  if (!fs::is_directory(st)) throw IoError(argument.string(), "not a scan file or a directory");
  if (const auto scan = scan_in(argument))
    return {CohortCase{directory_name(argument), *scan, landmarks_beside(argument, "landmarks")}};
  std::vector<fs::path> subdirs;
  for (const auto& entry : fs::directory_iterator(argument, ec))
    if (entry.is_directory() && scan_in(entry.path())) subdirs.push_back(entry.path());
  if (ec) throw IoError(argument.string(), "cannot list the directory: " + ec.message());
  if (subdirs.empty())
    throw IoError(argument.string(), "no scan.ply/.obj/.stl in the directory or in any of its sub-directories");
  std::sort(subdirs.begin(), subdirs.end());
  std::vector<CohortCase> cases;
  for (const fs::path& d : subdirs) cases.push_back({d.filename().string(), *scan_in(d), landmarks_beside(d, "landmarks")});
  return cases;
}

std::vector<CohortCase> resolve_cases(const std::vector<fs::path>& arguments) {
  if (arguments.empty()) throw InvalidInput("no cases given");
  std::vector<CohortCase> cases;
  std::map<std::string, fs::path> seen;
  for (const fs::path& a : arguments)
    for (CohortCase& c : resolve_case_argument(a)) {
      const auto [it, fresh] = seen.emplace(c.name, c.scan);
      if (!fresh)
        throw InvalidInput("two cases named '" + c.name + "' (" + it->second.string() + " and " + c.scan.string() +
                           "): their outputs would share a directory");
      cases.push_back(std::move(c));
    }
  return cases;
}

}  // namespace breastfit::cohort
