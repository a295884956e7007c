#include "breastfit/io/obj_texture.h"

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <vector>

#include "breastfit/core/errors.h"

namespace breastfit::io {
namespace {

// `line` without leading and trailing blanks (and the CR of CRLF files).
std::string trimmed(const std::string& line) {
  const size_t a = line.find_first_not_of(" \t\r");
  if (a == std::string::npos) return {};
  const size_t b = line.find_last_not_of(" \t\r");
  return line.substr(a, b - a + 1);
}

// The argument of `keyword` when `line` is that statement ("mtllib a b.mtl" → "a b.mtl"), else "".
std::string argument(const std::string& line, const std::string& keyword) {
  const std::string t = trimmed(line);
  if (t.size() <= keyword.size() || t.compare(0, keyword.size(), keyword) != 0 ||
      (t[keyword.size()] != ' ' && t[keyword.size()] != '\t'))
    return {};
  return trimmed(t.substr(keyword.size()));
}

bool is_number(const std::string& s) {
  char* end = nullptr;
  std::strtod(s.c_str(), &end);
  return !s.empty() && end == s.c_str() + s.size();
}

// The file name of a map_Kd argument: options (-s 1 1 1, -clamp on, -imfchan r, ...) skipped;
// the rest, words joined by one space, is the name.
std::string map_file(const std::string& arg) {
  std::istringstream in(arg);
  std::vector<std::string> words;
  for (std::string w; in >> w;) words.push_back(w);
  size_t i = 0;
  while (i < words.size() && words[i].size() > 1 && words[i][0] == '-' && !is_number(words[i])) {
    const bool one_word = words[i] == "-imfchan" || words[i] == "-type";
    ++i;
    if (one_word)
      ++i;
    else
      while (i < words.size() && (is_number(words[i]) || words[i] == "on" || words[i] == "off")) ++i;
  }
  std::string name;
  for (; i < words.size(); ++i) name += (name.empty() ? "" : " ") + words[i];
  return name;
}

}  // namespace

ObjTexture obj_texture(const std::filesystem::path& obj) {
  std::ifstream in(obj);
  if (!in) throw IoError(obj.string(), "cannot be read");
  ObjTexture out;
  std::string line;
  while (std::getline(in, line)) {
    const std::string lib = argument(line, "mtllib");
    if (!lib.empty()) {
      out.mtl = obj.parent_path() / lib;
      break;
    }
  }
  if (out.mtl.empty()) return out;
  std::ifstream mtl(out.mtl);
  if (!mtl) {
    out.problem = "its material library " + out.mtl.filename().string() + " is missing";
    return out;
  }
  while (std::getline(mtl, line)) {
    const std::string file = map_file(argument(line, "map_Kd"));
    if (!file.empty()) {
      out.image = out.mtl.parent_path() / file;
      return out;
    }
  }
  out.problem = "its material library " + out.mtl.filename().string() + " names no colour image (map_Kd)";
  return out;
}

}  // namespace breastfit::io
