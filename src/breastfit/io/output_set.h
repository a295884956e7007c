#pragma once
/// \file A set of output files that appears in its directory as a whole or not at all.
///
/// A command that writes several files into DIR (breastfit register, synth, demo) writes them
/// into a staging directory next to DIR (same parent, hence the same file system:
/// `.DIR.breastfit-tmp-<pid>-<n>`) and moves them into DIR only when all are written:
///  1. the set's completion marker (for register: report.json) is removed from DIR, so the
///     previous set is no longer complete;
///  2. every file of the set's names that this run did not write is removed from DIR (a stale
///     file of the previous run);
///  3. the written files are renamed into DIR (rename over an existing file is atomic), the
///     marker last.
/// So whenever the marker exists in DIR, every file of the set in DIR belongs to the run that
/// wrote the marker; a run killed during step 1-3 leaves a set without the marker, which
/// readers refuse as incomplete. A run that fails before commit() leaves DIR untouched. Files in
/// DIR outside the set's names are never touched. Staging directories left by killed runs into
/// the same DIR are removed by the next run (two runs into the same DIR at the same time are not
/// supported). The guarantee is against an interrupted process, not a power loss (no fsync).
///
/// Loose files in a shared directory (`render`'s PNGs under a prefix, `map`'s markups and
/// confidence, `batch`'s cohort.csv/.html) use Staging::InsideDir: the staging directory is
/// `DIR/.<marker>.breastfit-tmp-<pid>-<n>`, inside DIR (which may be the working directory, whose
/// parent need not be writable), and only staging directories of the same marker are leftovers.
/// Before anything is moved, commit() checks that no written file's destination is a directory,
/// so that failure leaves DIR as it was too.
#include <filesystem>
#include <string>
#include <vector>

namespace breastfit::io {

/// Where the staging directory goes (see the file comment).
enum class Staging { NextToDir, InsideDir };

class OutputSet {
 public:
  /// Creates the staging directory (and DIR's parent when missing) and removes the staging
  /// directories of killed runs into `dir`.
  /// \param names   every file the set may hold, relative to `dir` ("truth/meta.json" allowed)
  /// \param marker  the completion marker, one of `names`; commit() needs it written
  /// \throws IoError when the staging directory cannot be created (or `dir` names no directory)
  OutputSet(std::filesystem::path dir, std::vector<std::string> names, std::string marker,
            Staging staging = Staging::NextToDir);
  /// Removes the staging directory (and anything written into it) unless committed.
  ~OutputSet();
  OutputSet(const OutputSet&) = delete;
  OutputSet& operator=(const OutputSet&) = delete;

  /// Where to write the file `name` (one of the names): in the staging directory, whose
  /// subdirectories are created as needed. \throws std::invalid_argument for an unknown name
  std::filesystem::path path(const std::string& name) const;

  /// Moves the written files into `dir` (created when missing) as described in the file comment.
  /// \throws IoError when a file cannot be removed or moved; std::logic_error without the marker
  void commit();

  const std::filesystem::path& dir() const { return dir_; }
  const std::filesystem::path& staging_dir() const { return staging_; }

 private:
  std::filesystem::path dir_, staging_;
  std::vector<std::string> names_;
  std::string marker_;
  Staging where_;
  bool committed_ = false;
};

/// The name prefix of the staging directories of `dir` (".DIR.breastfit-tmp-").
std::string staging_prefix(const std::filesystem::path& dir);

/// A set of loose files in one directory, named by their paths (all in the same directory,
/// e.g. "out/a_front.png", "out/a_side.png"), the marker last: an OutputSet with
/// Staging::InsideDir over their directory. \throws std::invalid_argument for paths in different
/// directories or an empty list; IoError as OutputSet.
OutputSet loose_file_set(const std::vector<std::filesystem::path>& files);

}  // namespace breastfit::io
