// Every file a program writes goes through here, so that an output never
// destroys an input and a failure never leaves a partial file:
//  - an output that is the same file as an input (device and inode, so hard
//    and symbolic links are caught) is refused before anything is written;
//  - a regular (or new) output is written to a temporary file in the same
//    folder and renamed over the target only when every byte reached the
//    disk (fflush, fsync); on failure the temporary file is removed and an
//    existing target is untouched;
//  - an existing output that is not a regular file (/dev/null, /dev/stdout, a
//    FIFO) is written in place: renaming over a device would replace it.
#pragma once

#include <cstddef>
#include <cstdio>
#include <string>
#include <vector>

namespace birotor {

// False (with *error naming both paths) when `output` exists and is the same
// file as one of `inputs`. Inputs that do not exist are ignored.
bool CheckOutputIsNotInput(const std::string& output, const std::vector<std::string>& inputs, std::string* error);

// Every program's check before it writes: no output is an input, and no two
// outputs are the same file (same inode, or the same normalised path when
// they do not exist yet). Empty paths (options not given) are skipped.
bool CheckOutputs(const std::vector<std::string>& outputs, const std::vector<std::string>& inputs, std::string* error);

class OutputFile {
 public:
  OutputFile() = default;
  ~OutputFile();  // Abandon() unless committed
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  // Starts writing path (see the file comment). False (with *error) when the
  // temporary file cannot be created (missing or read-only folder).
  bool Open(const std::string& path, std::string* error);
  bool is_open() const { return stream_ != nullptr; }

  // The stream to write to (stdio buffering; errors are caught by Commit).
  std::FILE* stream() const { return stream_; }
  // Where the bytes go before Commit: the temporary file, or the target
  // itself when it is not a regular file. For programs (gnuplot) that write
  // the output themselves: let them write here, then Commit.
  const std::string& write_path() const { return write_path_; }
  const std::string& path() const { return path_; }

  // Appends bytes; false if the stream has failed (the failure sticks).
  bool Write(const void* data, size_t size);
  bool Write(const std::string& text) { return Write(text.data(), text.size()); }

  // Flushes, syncs, closes and renames the temporary file over the target.
  // False (with *error naming the target and the reason, e.g. "No space left
  // on device") when any write, the flush, the sync or the rename failed; the
  // temporary file is then removed.
  bool Commit(std::string* error);
  // Closes and removes the temporary file; the target keeps its old content.
  void Abandon();

 private:
  std::string path_;
  std::string write_path_;
  std::FILE* stream_ = nullptr;
  bool in_place_ = false;  // target is not a regular file: no temporary, no rename
  int write_errno_ = 0;    // errno of the first failed Write, for the message
};

// text to path through an OutputFile. False (with *error) on any failure.
bool WriteFileAtomically(const std::string& path, const std::string& text, std::string* error);

}  // namespace birotor
