// Outputs through a temporary file and rename; refusal of output == input.
#include "transport/output_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

namespace birotor {
namespace {

std::string FolderOf(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  if (slash == std::string::npos) return ".";
  return slash == 0 ? "/" : path.substr(0, slash);
}

// Makes the rename durable (best effort: some file systems refuse).
void SyncFolder(const std::string& folder) {
  const int fd = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

}  // namespace

bool CheckOutputIsNotInput(const std::string& output, const std::vector<std::string>& inputs, std::string* error) {
  struct stat out;
  if (::stat(output.c_str(), &out) != 0) return true;  // does not exist yet
  for (const std::string& input : inputs) {
    struct stat in;
    if (::stat(input.c_str(), &in) != 0) continue;
    if (in.st_dev == out.st_dev && in.st_ino == out.st_ino) {
      *error = "output " + output + " is the input " + input + " (same file); refusing to overwrite it";
      return false;
    }
  }
  return true;
}

bool CheckOutputs(const std::vector<std::string>& outputs, const std::vector<std::string>& inputs, std::string* error) {
  std::vector<std::string> given_inputs;
  for (const std::string& input : inputs) {
    if (!input.empty()) given_inputs.push_back(input);
  }
  for (size_t i = 0; i < outputs.size(); ++i) {
    if (outputs[i].empty()) continue;
    if (!CheckOutputIsNotInput(outputs[i], given_inputs, error)) return false;
    for (size_t j = i + 1; j < outputs.size(); ++j) {
      if (outputs[j].empty()) continue;
      std::error_code code;
      const bool same_path =
          std::filesystem::weakly_canonical(outputs[i], code) == std::filesystem::weakly_canonical(outputs[j], code);
      if (same_path || !CheckOutputIsNotInput(outputs[j], {outputs[i]}, error)) {
        *error = "outputs " + outputs[i] + " and " + outputs[j] + " are the same file";
        return false;
      }
    }
  }
  return true;
}

OutputFile::~OutputFile() { Abandon(); }

bool OutputFile::Open(const std::string& path, std::string* error) {
  Abandon();
  path_ = path;
  write_errno_ = 0;
  struct stat info;
  in_place_ = ::stat(path.c_str(), &info) == 0 && !S_ISREG(info.st_mode);
  if (in_place_) {
    if (S_ISDIR(info.st_mode)) {
      *error = "cannot write " + path + ": it is a folder";
      return false;
    }
    write_path_ = path;
    stream_ = std::fopen(path.c_str(), "w");
    if (stream_ == nullptr) {
      *error = "cannot write " + path + ": " + std::strerror(errno);
      return false;
    }
    return true;
  }
  std::string name = path + ".tmp.XXXXXX";
  const int fd = ::mkostemp(name.data(), O_CLOEXEC);
  if (fd < 0) {
    *error =
        "cannot write " + path + ": cannot create a temporary file in " + FolderOf(path) + ": " + std::strerror(errno);
    return false;
  }
  // mkstemp makes the file 0600; give it what a plain open would (0666 & ~umask).
  const mode_t mask = ::umask(0);
  ::umask(mask);
  ::fchmod(fd, 0666 & ~mask);
  write_path_ = name;
  stream_ = ::fdopen(fd, "w");
  if (stream_ == nullptr) {
    *error = "cannot write " + path + ": " + std::strerror(errno);
    ::close(fd);
    ::unlink(name.c_str());
    return false;
  }
  return true;
}

bool OutputFile::Write(const void* data, size_t size) {
  if (stream_ == nullptr) return false;
  if (size > 0 && std::fwrite(data, 1, size, stream_) != size) {
    if (write_errno_ == 0) write_errno_ = errno;
    return false;
  }
  return std::ferror(stream_) == 0;
}

bool OutputFile::Commit(std::string* error) {
  if (stream_ == nullptr) {
    *error = "cannot write " + path_ + ": not open";
    return false;
  }
  auto fail = [&](const char* what, int code) {
    *error = "writing " + path_ + " failed (" + what + "): " + std::strerror(code);
    if (stream_ != nullptr) std::fclose(stream_);
    stream_ = nullptr;
    if (!in_place_) ::unlink(write_path_.c_str());
    return false;
  };
  // After a failed write, fflush tries the buffered bytes again and sets
  // errno to the reason (ENOSPC on a full disk).
  errno = 0;
  const bool flushed = std::fflush(stream_) == 0;
  if (!flushed || std::ferror(stream_) != 0) {
    return fail("write", errno != 0 ? errno : (write_errno_ != 0 ? write_errno_ : EIO));
  }
  // A device or FIFO cannot be synced (EINVAL): only regular files need it.
  if (!in_place_ && ::fsync(::fileno(stream_)) != 0) return fail("fsync", errno);
  const int closed = std::fclose(stream_);
  stream_ = nullptr;
  if (closed != 0) return fail("close", errno);
  if (in_place_) return true;
  if (std::rename(write_path_.c_str(), path_.c_str()) != 0) return fail("rename", errno);
  SyncFolder(FolderOf(path_));
  return true;
}

void OutputFile::Abandon() {
  if (stream_ != nullptr) {
    std::fclose(stream_);
    stream_ = nullptr;
    if (!in_place_) ::unlink(write_path_.c_str());
  }
}

bool WriteFileAtomically(const std::string& path, const std::string& text, std::string* error) {
  OutputFile file;
  if (!file.Open(path, error)) return false;
  file.Write(text);
  return file.Commit(error);
}

}  // namespace birotor
