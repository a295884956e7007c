// The command line as a whole (apps/cli/run_app.cpp and every subcommand it registers): each
// subcommand's --help is walked, found from `breastfit --help` itself (nested subcommands
// included), so commands added later are covered without touching this test.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <utility>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "support/test_paths.h"

namespace breastfit {
namespace {

/// One option or positional line of a CLI11 help text: its names and description.
struct HelpOption {
  std::vector<std::string> names;  // "-o", "--out", or a positional's name
  std::string head;                // names, type and default: "--seed UINT=7"
  std::string description;
};

/// The help text's sections: "Subcommands" names, "Options" and "Positionals" entries.
struct Help {
  std::vector<std::string> subcommands;
  std::vector<HelpOption> options;
};

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(' ');
  const auto e = s.find_last_not_of(' ');
  return b == std::string::npos ? "" : s.substr(b, e - b + 1);
}

/// Splits an entry line (without its indentation) into its head (names, type and default) and
/// the description after the first run of two or more spaces (empty when on the next line).
/// (CLI11 pads heads to a fixed column: a head one character short of it is followed by one
/// space and no description is found, which EveryHelpExitsZeroAndDescribesEveryOption reports.)
std::pair<std::string, std::string> split_entry(const std::string& body) {
  const auto gap = body.find("  ");
  return {body.substr(0, gap), gap == std::string::npos ? "" : trim(body.substr(gap))};
}

Help parse_help(const std::string& text) {
  Help h;
  std::istringstream in(text);
  std::string line, section;
  bool group_description = false;  // the line after "[Option Group: ...]" describes the group
  while (std::getline(in, line)) {
    const std::string t = trim(line);
    if (t.empty()) continue;
    if (line[0] != ' ') {
      if (t.rfind("[Option Group:", 0) == 0) {
        section = "Options";
        group_description = true;
      } else if (t.back() == ':') {
        section = t.substr(0, t.size() - 1);
      }
      continue;
    }
    if (t == "Options:") {
      group_description = false;
      continue;
    }
    const std::size_t indent = line.find_first_not_of(' ');
    if (section == "Subcommands" && indent == 2) {
      h.subcommands.push_back(t.substr(0, t.find(' ')));
    } else if ((section == "Options" && t[0] == '-') || (section == "Positionals" && indent == 2)) {
      const auto [head, description] = split_entry(t);
      HelpOption o;
      o.head = head;
      std::stringstream ns(head.substr(0, head.find(' ')));
      for (std::string n; std::getline(ns, n, ',');) o.names.push_back(n);
      o.description = description;
      h.options.push_back(o);
      group_description = false;
    } else if (group_description) {
      group_description = false;  // the group's own description
    } else if (!h.options.empty() && h.options.back().description.empty()) {
      h.options.back().description = t;  // a long head puts the description on the next line
    }
  }
  return h;
}

/// Every subcommand path ("register", "template info", ...) with its parsed help.
std::map<std::string, Help> walk(const std::string& path) {
  std::string text;
  EXPECT_EQ(test::run_cli(path + " --help", &text), 0) << path << " --help:\n" << text;
  std::map<std::string, Help> out;
  const Help h = parse_help(text);
  out[path] = h;
  for (const std::string& sub : h.subcommands) {
    const auto more = walk(path.empty() ? sub : path + " " + sub);
    out.insert(more.begin(), more.end());
  }
  return out;
}

TEST(Main, EveryHelpExitsZeroAndDescribesEveryOption) {
  if (test::cli_path().empty()) GTEST_SKIP() << "CLI not built";
  const auto helps = walk("");
  EXPECT_GE(helps.size(), 11u);  // the top level and at least ten subcommands
  ASSERT_TRUE(helps.count("register"));
  bool grouped = false;  // options inside "[Option Group: ...]" are parsed too
  for (const HelpOption& o : helps.at("register").options) grouped = grouped || o.names.back() == "--lambda-data";
  EXPECT_TRUE(grouped);
  for (const auto& [path, help] : helps) {
    for (const HelpOption& o : help.options) {
      EXPECT_FALSE(o.description.empty()) << "'" << path << "': option " << o.names.front() << " has no description";
    }
  }
}

// Every option taking a number (INT, UINT, FLOAT) or one of a set of words ("TEXT:{mm,m}")
// says what it is when not given: its default in the head ("--seed UINT=7", captured from the
// variable) or in its description ("(default 0.25)", "(default: all)"). Required options have
// none. File options (plain TEXT) may have no default: an absent file is no file.
TEST(Main, EveryNumberOrChoiceOptionShowsItsDefault) {
  if (test::cli_path().empty()) GTEST_SKIP() << "CLI not built";
  const auto helps = walk("");
  int checked = 0;
  for (const auto& [path, help] : helps) {
    for (const HelpOption& o : help.options) {
      if (o.names.front().rfind("-", 0) != 0) continue;  // a positional
      const std::string& h = o.head;
      const bool numeric = h.find(" INT") != std::string::npos || h.find(" UINT") != std::string::npos ||
                           h.find(" FLOAT") != std::string::npos;
      const bool choice = h.find(":{") != std::string::npos;
      if (!(numeric || choice) || h.find("REQUIRED") != std::string::npos) continue;
      ++checked;
      const bool shown = h.find('=') != std::string::npos || o.description.find("default") != std::string::npos;
      EXPECT_TRUE(shown) << "'" << path << "': " << h << " shows no default (" << o.description << ")";
      EXPECT_EQ(h.find("=[]"), std::string::npos) << "'" << path << "': " << h;
    }
  }
  EXPECT_GE(checked, 30);  // λ weights, --units, bench -n, demo --seed, volume --fill, ...
  // The ones users asked for by name.
  const std::vector<std::pair<std::string, std::string>> named{
      {"bench", "-n,--repeat INT:INT in [1 - 100]=5"}, {"demo", "--seed UINT=7"},
      {"volume", "--fill TEXT:{membrane,thin-plate}=membrane"}, {"map", "--max-distance FLOAT:POSITIVE=10"},
      {"register", "--units TEXT:{auto,mm,m}=auto"}};
  for (const auto& [path, head] : named) {
    ASSERT_TRUE(helps.count(path)) << path;
    bool found = false;
    for (const HelpOption& o : helps.at(path).options) found = found || o.head == head;
    EXPECT_TRUE(found) << "'" << path << "' has no option shown as " << head;
  }
}

TEST(Main, SameFlagsMeanTheSameInEverySubcommand) {
  if (test::cli_path().empty()) GTEST_SKIP() << "CLI not built";
  const auto helps = walk("");
  // One meaning per short letter across the whole command line, and the shared long options
  // always with their short letter.
  std::map<std::string, std::set<std::string>> long_of_short;  // "-o" -> {"--out"}
  const std::map<std::string, std::string> shared{
      {"--out", "-o"}, {"--quiet", "-q"}, {"--template", "-t"}, {"--landmarks", "-l"}};
  for (const auto& [path, help] : helps) {
    for (const HelpOption& o : help.options) {
      std::string short_name, long_name;
      for (const std::string& n : o.names) {
        if (n.rfind("--", 0) == 0) {
          long_name = n;
        } else if (n.size() == 2 && n[0] == '-') {
          short_name = n;
        }
      }
      if (!short_name.empty() && !long_name.empty()) long_of_short[short_name].insert(long_name);
      const auto it = shared.find(long_name);
      if (it != shared.end()) {
        EXPECT_EQ(short_name, it->second) << "'" << path << "': " << long_name << " should also be " << it->second;
      }
      EXPECT_NE(long_name, "--output") << "'" << path << "': use --out";
    }
  }
  for (const auto& [short_name, longs] : long_of_short) {
    EXPECT_EQ(longs.size(), 1u) << short_name << " means " << testing::PrintToString(longs);
  }
}

// `breastfit` loads neither the workstation's HTTP library nor the TLS and compression libraries
// it brings (~10 ms of CPU before main in every run); `breastfit serve` runs breastfit-serve,
// which does, from the same directory.
TEST(Main, TheWorkstationsLibrariesAreLoadedOnlyByTheWorkstation) {
  std::string loaded;
  // The dynamic loader lists what it would load, without running the program (as ldd does).
  ASSERT_EQ(test::run_shell("LD_TRACE_LOADED_OBJECTS=1 '" + test::cli_path().string() + "'", &loaded), 0);
  EXPECT_NE(loaded.find("libc.so"), std::string::npos) << loaded;
  for (const char* lib : {"httplib", "libssl", "libcrypto", "brotli"}) EXPECT_EQ(loaded.find(lib), std::string::npos) << loaded;
  const std::filesystem::path serve = test::cli_path().parent_path() / "breastfit-serve";
  std::string serve_loaded;
  ASSERT_EQ(test::run_shell("LD_TRACE_LOADED_OBJECTS=1 '" + serve.string() + "'", &serve_loaded), 0);
  EXPECT_NE(serve_loaded.find("httplib"), std::string::npos) << serve_loaded;
  std::string help;
  EXPECT_EQ(test::run_cli("serve --help", &help), 0) << help;
  EXPECT_NE(help.find("Usage: breastfit serve"), std::string::npos) << help;
  EXPECT_NE(help.find("--workspace"), std::string::npos) << help;
}

}  // namespace
}  // namespace breastfit
