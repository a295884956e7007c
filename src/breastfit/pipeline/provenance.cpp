#include "breastfit/pipeline/provenance.h"

#include <ctime>

#include "breastfit/io/file_sha256.h"

#ifndef BREASTFIT_VERSION
#define BREASTFIT_VERSION "unknown"
#endif
#ifndef BREASTFIT_GIT_DESCRIBE
#define BREASTFIT_GIT_DESCRIBE ""
#endif

namespace breastfit::pipeline {

const InputFile* Provenance::input(const std::string& role) const {
  for (const InputFile& f : inputs) {
    if (f.role == role) return &f;
  }
  return nullptr;
}

std::string breastfit_version() {
  const std::string git = BREASTFIT_GIT_DESCRIBE;
  return git.empty() ? std::string(BREASTFIT_VERSION) : std::string(BREASTFIT_VERSION) + " (git " + git + ")";
}

std::string utc_now_iso8601() {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

InputFile hash_input(const std::string& role, const std::filesystem::path& path) {
  return {role, path.string(), io::file_sha256_hex(path)};
}

Provenance start_provenance(std::string command_line,
                            const std::vector<std::pair<std::string, std::filesystem::path>>& files) {
  Provenance p;
  p.version = breastfit_version();
  p.started_utc = utc_now_iso8601();
  p.command_line = std::move(command_line);
  for (const auto& [role, path] : files)
    if (!path.empty()) p.inputs.push_back(hash_input(role, path));
  return p;
}

std::string shell_command_line(const std::vector<std::string>& args) {
  std::string out;
  for (const std::string& a : args) {
    if (!out.empty()) out += ' ';
    const bool plain = !a.empty() && a.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                                         "0123456789-_./=:,+@%") == std::string::npos;
    if (plain) {
      out += a;
      continue;
    }
    out += '\'';
    for (char c : a) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    out += '\'';
  }
  return out;
}

}  // namespace breastfit::pipeline
