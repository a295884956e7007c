#pragma once
/// \file A set of output files that appears in its directory as a whole or not at all.
///
/// A command that writes several files into DIR (breastfit register, synth, demo) writes them
/// into a staging directory next to DIR (same parent, hence the same file system:
/// `.DIR.breastfit-tmp-<pid>-<n>`) and, when all are written, swaps it with DIR in one step:
///  - without a previous DIR, the staging directory is renamed to DIR;
///  - otherwise every file in DIR outside the set's names (the user's own files) is hard-linked
///    into the staging directory (same inodes; subdirectories recreated, symbolic links copied),
///    the staging directory gets DIR's permissions, and the two are exchanged atomically (Linux
///    renameat2 RENAME_EXCHANGE); the old directory, now under the staging name, is removed.
/// So DIR always holds the complete previous set or the complete new one, whenever the process
/// is killed; files of the previous set that this run did not write are gone with the swap.
/// Where the swap cannot be used — DIR is a symbolic link, the working directory is DIR or
/// inside it (a shell there would be left in the removed directory), DIR holds a special file or
/// the file system has no hard links or exchange — the files are moved one by one instead:
///  1. the set's completion marker (for register: report.json) is removed from DIR, so the
///     previous set is no longer complete;
///  2. every file of the set's names that this run did not write is removed from DIR (a stale
///     file of the previous run);
///  3. the written files are renamed into DIR (rename over an existing file is atomic), the
///     marker last.
/// Then whenever the marker exists in DIR, every file of the set in DIR belongs to the run that
/// wrote the marker; a run killed during step 1-3 leaves a set without the marker, which
/// readers refuse as incomplete. A run that fails before commit() leaves DIR untouched. Files in
/// DIR outside the set's names are never touched (nor lost). Staging directories left by killed
/// runs into the same DIR are removed by the next run (two runs into the same DIR at the same
/// time are not supported). The guarantee is against an interrupted process, not a power loss
/// (no fsync).
///
/// Loose files in a shared directory (`render`'s PNGs under a prefix, `map`'s markups and
/// confidence, `batch`'s cohort.csv/.html) use Staging::InsideDir: the staging directory is
/// `DIR/.<marker>.breastfit-tmp-<pid>-<n>`, inside DIR (which may be the working directory, whose
/// parent need not be writable), only staging directories of the same marker are leftovers, and
/// the files are always moved one by one (a shared directory is never swapped).
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

  /// Puts the written files into `dir` (created when missing) as described in the file comment.
  /// \throws IoError when a file cannot be removed or moved; std::logic_error without the marker
  void commit();

  const std::filesystem::path& dir() const { return dir_; }
  const std::filesystem::path& staging_dir() const { return staging_; }

 private:
  /// The one-step swap (see the file comment); false when it cannot be used, `dir` unchanged.
  bool swap_in();

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
