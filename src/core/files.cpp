#include "core/files.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <atomic>
#include <cctype>
#include <csignal>
#include <cerrno>
#include <cstdio>
#include <cstring>

#include "core/error.h"

namespace penumbra {

std::string fileNameComponent(const std::string& name, const std::string& fallback) {
  constexpr std::size_t kMaxLength = 100;
  std::string out;
  for (const char c : name) {
    if (out.size() == kMaxLength) break;
    const bool kept = std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || (c == '.' && !out.empty());
    out += kept ? c : '_';
  }
  return out.empty() ? fallback : out;
}

namespace {

// The temporaries being written, for the signal handler: fixed slots of plain characters, as a
// handler may only read memory and call async-signal-safe functions (unlink, signal, raise).
struct InFlight {
  std::atomic<int> state{0};  // 0 free, 1 being filled, 2 holds a path
  char path[4096];
};
InFlight gInFlight[32];
static_assert(std::atomic<int>::is_always_lock_free, "the signal handler reads the slots' state");

void removeInFlight(int sig) {
  for (InFlight& slot : gInFlight)
    if (slot.state.load(std::memory_order_acquire) == 2) ::unlink(slot.path);
  std::signal(sig, SIG_DFL);
  std::raise(sig);
}

// Registers `temporary` while it lives (a path too long for a slot, or more than 32 writes at
// once, is written unregistered: left behind by a signal, as before).
class InFlightTemporary {
 public:
  explicit InFlightTemporary(const std::string& temporary) {
    if (temporary.size() >= sizeof(InFlight::path)) return;
    for (InFlight& slot : gInFlight) {
      int expected = 0;
      if (!slot.state.compare_exchange_strong(expected, 1, std::memory_order_acquire)) continue;
      std::memcpy(slot.path, temporary.c_str(), temporary.size() + 1);
      slot.state.store(2, std::memory_order_release);
      slot_ = &slot;
      return;
    }
  }
  ~InFlightTemporary() {
    if (slot_) slot_->state.store(0, std::memory_order_release);
  }
  InFlightTemporary(const InFlightTemporary&) = delete;
  InFlightTemporary& operator=(const InFlightTemporary&) = delete;

 private:
  InFlight* slot_ = nullptr;
};

}  // namespace

void installInterruptCleanup() {
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) {
    struct sigaction action {};
    action.sa_handler = &removeInFlight;
    sigemptyset(&action.sa_mask);
    action.sa_flags = SA_RESETHAND;
    sigaction(sig, &action, nullptr);
  }
}

void writeAtomically(const std::string& path, const std::function<void(const std::string& temporary)>& write) {
  const std::string temporary = path + ".partial-" + std::to_string(::getpid());
  const InFlightTemporary inFlight(temporary);
  try {
    write(temporary);
  } catch (...) {
    std::remove(temporary.c_str());
    throw;
  }
  errno = 0;
  if (std::rename(temporary.c_str(), path.c_str()) != 0) {
    const int e = errno;
    std::remove(temporary.c_str());
    throw Error(path, std::string("cannot write: ") + std::strerror(e));
  }
}

void writeTextFile(const std::string& path, const std::string& text) {
  writeAtomically(path, [&](const std::string& temporary) {
    errno = 0;
    std::FILE* f = std::fopen(temporary.c_str(), "wb");
    if (!f) throw Error(path, std::string("cannot write: ") + std::strerror(errno));
    const bool written = std::fwrite(text.data(), 1, text.size(), f) == text.size();
    const int e = errno;
    const bool closed = std::fclose(f) == 0;
    if (!written || !closed) throw Error(path, std::string("cannot write: ") + std::strerror(written ? errno : e));
  });
}

namespace {

int openLockFile(const std::string& path, const char* what) {
  errno = 0;
  const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd < 0) throw Error(path, std::string("cannot create ") + what + ": " + std::strerror(errno));
  return fd;
}

}  // namespace

FolderLock::FolderLock(const std::string& dir) {
  const std::string path = dir + "/.penumbra-lock";
  fd_ = openLockFile(path, "the folder's lock");
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    const int e = errno;
    ::close(fd_);
    fd_ = -1;
    if (e == EWOULDBLOCK)
      throw Error(dir,
                  "another penumbra run is writing into this folder (it holds .penumbra-lock): wait for it, or "
                  "give another output folder");
    throw Error(path, std::string("cannot lock the folder: ") + std::strerror(e));
  }
}

FolderLock::~FolderLock() {
  if (fd_ >= 0) ::close(fd_);  // closing drops the lock
}

FileLock::FileLock(const std::string& path) : fd_(openLockFile(path, "a lock file")) {
  int rc;
  while ((rc = ::flock(fd_, LOCK_EX)) != 0 && errno == EINTR) {
  }
  if (rc != 0) {
    const int e = errno;
    ::close(fd_);
    throw Error(path, std::string("cannot lock: ") + std::strerror(e));
  }
}

FileLock::~FileLock() { ::close(fd_); }

}  // namespace penumbra
