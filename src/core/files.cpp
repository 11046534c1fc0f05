#include "core/files.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cctype>
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

void writeAtomically(const std::string& path, const std::function<void(const std::string& temporary)>& write) {
  const std::string temporary = path + ".partial-" + std::to_string(::getpid());
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

FolderLock::FolderLock(const std::string& dir) {
  const std::string path = dir + "/.penumbra-lock";
  errno = 0;
  fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) throw Error(path, std::string("cannot create the folder's lock: ") + std::strerror(errno));
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    const int e = errno;
    ::close(fd_);
    fd_ = -1;
    if (e == EWOULDBLOCK)
      throw Error(dir, "another penumbra run is writing into this folder (it holds .penumbra-lock): wait for it, or "
                       "give another output folder");
    throw Error(path, std::string("cannot lock the folder: ") + std::strerror(e));
  }
}

FolderLock::~FolderLock() {
  if (fd_ >= 0) ::close(fd_);  // closing drops the lock
}

}  // namespace penumbra
