#include "params/regular_file.h"

#include <fcntl.h>
#include <sys/random.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>

namespace birotor {
namespace {

std::string Describe(mode_t mode) {
  if (S_ISLNK(mode)) return "a symbolic link";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISDIR(mode)) return "a folder";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

std::string Reason() { return std::strerror(errno); }

// Closes fd on every path out of a scope.
class Descriptor {
 public:
  explicit Descriptor(int fd) : fd_(fd) {}
  ~Descriptor() {
    if (fd_ >= 0) ::close(fd_);
  }
  Descriptor(const Descriptor&) = delete;
  Descriptor& operator=(const Descriptor&) = delete;
  int get() const { return fd_; }
  // Closes now; false when close reports an error (a late write failure).
  bool Close() {
    const int fd = fd_;
    fd_ = -1;
    return ::close(fd) == 0;
  }

 private:
  int fd_;
};

std::string Folder(const std::string& path) {
  const size_t slash = path.rfind('/');
  if (slash == std::string::npos) return ".";
  return slash == 0 ? "/" : path.substr(0, slash);
}

std::string BaseName(const std::string& path) {
  const size_t slash = path.rfind('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

// "<folder>/.<name>.<16 random hex>.tmp", created exclusively (never an
// existing file or link). -1 with *error after 16 collisions or on failure.
int CreateUniqueTemporary(const std::string& path, std::string* temp, std::string* error) {
  const std::string stem = Folder(path) + "/." + BaseName(path) + ".";
  for (int attempt = 0; attempt < 16; ++attempt) {
    uint64_t random = 0;
    if (getrandom(&random, sizeof(random), 0) != sizeof(random)) {
      random =
          (static_cast<uint64_t>(getpid()) << 32) ^ static_cast<uint64_t>(attempt) ^ reinterpret_cast<uintptr_t>(temp);
    }
    char suffix[24];
    std::snprintf(suffix, sizeof(suffix), "%016llx", static_cast<unsigned long long>(random));
    *temp = stem + suffix + ".tmp";
    const int fd = ::open(temp->c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600);
    if (fd >= 0) return fd;
    if (errno != EEXIST) {
      *error = "cannot create a temporary file in " + Folder(path) + ": " + Reason();
      return -1;
    }
  }
  *error = "cannot create a unique temporary file in " + Folder(path);
  return -1;
}

bool WriteAll(int fd, const std::string& text) {
  size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    done += static_cast<size_t>(n);
  }
  return true;
}

}  // namespace

bool ReadRegularFile(const std::string& path, size_t max_bytes, LinkPolicy links, std::string* text,
                     std::string* error) {
  // O_NONBLOCK: opening a FIFO with no writer returns at once instead of
  // waiting for one; fstat then refuses it.
  int flags = O_RDONLY | O_NONBLOCK | O_CLOEXEC;
  if (links == LinkPolicy::kRefuse) flags |= O_NOFOLLOW;
  Descriptor fd(::open(path.c_str(), flags));
  if (fd.get() < 0) {
    *error = path + ": " + (errno == ELOOP ? std::string("a symbolic link (refused)") : "cannot open: " + Reason());
    return false;
  }
  struct stat info {};
  if (::fstat(fd.get(), &info) != 0) {
    *error = path + ": cannot stat: " + Reason();
    return false;
  }
  if (!S_ISREG(info.st_mode)) {
    *error = path + ": " + Describe(info.st_mode) + ", not a regular file (refused)";
    return false;
  }
  if (static_cast<uint64_t>(info.st_size) > max_bytes) {
    *error = path + ": larger than " + std::to_string(max_bytes) + " bytes (" + std::to_string(info.st_size) +
             " bytes, refused)";
    return false;
  }
  // One byte more than allowed, in case the file grew since fstat.
  text->assign(max_bytes + 1, '\0');
  size_t done = 0;
  while (done < text->size()) {
    const ssize_t n = ::read(fd.get(), &(*text)[done], text->size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      *error = path + ": cannot read: " + Reason();
      return false;
    }
    if (n == 0) break;
    done += static_cast<size_t>(n);
  }
  if (done > max_bytes) {
    *error = path + ": larger than " + std::to_string(max_bytes) + " bytes (grew while read, refused)";
    return false;
  }
  text->resize(done);
  return true;
}

PathKind InspectPath(const std::string& path, FileAttributes* attributes, std::string* description) {
  struct stat info {};
  if (::lstat(path.c_str(), &info) != 0) {
    if (description) *description = "absent";
    return PathKind::kAbsent;
  }
  if (!S_ISREG(info.st_mode)) {
    if (description) *description = Describe(info.st_mode);
    return PathKind::kOther;
  }
  if (description) *description = "a regular file";
  if (attributes) {
    attributes->mode = info.st_mode & 07777;
    attributes->set_owner = true;
    attributes->uid = info.st_uid;
    attributes->gid = info.st_gid;
  }
  return PathKind::kRegular;
}

bool ReplaceRegularFile(const std::string& path, const std::string& text, const FileAttributes& attributes,
                        std::string* error) {
  std::string kind;
  if (InspectPath(path, nullptr, &kind) == PathKind::kOther) {
    *error = path + ": exists and is " + kind + "; only a regular file is replaced (refused, left alone)";
    return false;
  }
  std::string temp;
  Descriptor fd(CreateUniqueTemporary(path, &temp, error));
  if (fd.get() < 0) return false;
  std::string failure;
  if (!WriteAll(fd.get(), text)) {
    failure = "cannot write: " + Reason();
  } else if (attributes.set_owner && ::fchown(fd.get(), attributes.uid, attributes.gid) != 0) {
    failure = "cannot keep owner " + std::to_string(attributes.uid) + ":" + std::to_string(attributes.gid) +
              " (run as root or as the owner): " + Reason();
  } else if (::fchmod(fd.get(), attributes.mode) != 0) {  // after fchown, which clears set-id bits
    failure = "cannot set mode: " + Reason();
  } else if (::fsync(fd.get()) != 0) {
    failure = "cannot sync: " + Reason();
  } else if (!fd.Close()) {
    failure = "cannot close: " + Reason();
  } else if (::rename(temp.c_str(), path.c_str()) != 0) {
    failure = "cannot rename " + temp + " over it: " + Reason();
  }
  if (!failure.empty()) {
    ::unlink(temp.c_str());
    *error = path + ": " + failure + " (left unchanged)";
    return false;
  }
  // The rename itself reaches the disk with the folder.
  Descriptor folder(::open(Folder(path).c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC));
  if (folder.get() >= 0) ::fsync(folder.get());
  return true;
}

}  // namespace birotor
