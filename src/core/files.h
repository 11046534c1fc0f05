// Output files. Names from input files in output paths: a downloaded scene must never choose
// where files go: its `name` (compare's default folder `out/<name>`, the LUT tool's file names)
// and its lights' names become one path component each, with nothing that could climb out of
// the folder. And every output written whole or not at all.
#pragma once

#include <functional>
#include <string>

namespace penumbra {

// `name` as one file-name component: letters, digits, '-', '_' and '.' kept, every other byte
// (a '/', a '\', a space, a control character, UTF-8) as '_', a leading '.' as '_' (no "..", no
// hidden file), at most 100 characters; `fallback` when nothing is left.
std::string fileNameComponent(const std::string& name, const std::string& fallback);

// Writes `path` through a temporary sibling ("<path>.partial-<pid>") that `write` fills and
// closes (throwing penumbra::Error on any failure), renamed into place only then: a reader never
// sees a half-written file, and a failed or interrupted write leaves the file that was there. On
// failure the temporary is removed; on Ctrl-C too, once installInterruptCleanup has run.
void writeAtomically(const std::string& path, const std::function<void(const std::string& temporary)>& write);
// `text` as the whole of `path`, atomically, every write and the close checked (a full disk is
// an error naming `path`, never an empty file).
void writeTextFile(const std::string& path, const std::string& text);

// Ctrl-C (SIGINT), SIGTERM and SIGHUP remove the temporaries of the writes in flight, then end
// the process as the signal would have (its exit status says so). main() installs it once.
void installInterruptCleanup();

// A run's hold on its output folder (an advisory lock, flock, on `<dir>/.penumbra-lock`), kept
// while the object lives and dropped by the system if the process dies: a second run into the
// same folder is refused naming it, rather than mixing its files into the first one's report.
class FolderLock {
 public:
  explicit FolderLock(const std::string& dir);
  ~FolderLock();
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;

 private:
  int fd_ = -1;
};

// An exclusive advisory lock (flock) on the file `path` (created if absent), waited for while
// another process holds it; kept while the object lives, dropped by the system if the process
// dies (a study's job: study/run.h).
class FileLock {
 public:
  explicit FileLock(const std::string& path);
  ~FileLock();
  FileLock(const FileLock&) = delete;
  FileLock& operator=(const FileLock&) = delete;

 private:
  int fd_ = -1;
};

}  // namespace penumbra
