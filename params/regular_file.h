// Reading and replacing the small files the daemons and tools keep (parameter
// files, the gauge state file, FILE.bak) without ever writing or waiting on
// anything else (docs/files.md):
//  - a read opens without blocking (a FIFO never hangs), checks with fstat on
//    the open descriptor that it is a regular file of at most max_bytes
//    (/dev/zero, a directory or a 2 GB file is refused before a byte is read)
//    and, when asked, refuses a symbolic link (O_NOFOLLOW);
//  - a replacement writes a temporary file with a unique name in the target's
//    folder, created with O_CREAT | O_EXCL | O_NOFOLLOW (a pre-planted link or
//    file of that name is never opened), sets its mode and owner, syncs it and
//    renames it over the target; an existing target that is not a regular
//    file (a link, a FIFO, a device, a folder) is refused and left alone.
#pragma once

#include <sys/types.h>

#include <cstddef>
#include <string>

namespace birotor {

enum class LinkPolicy { kFollow, kRefuse };

// Reads the whole regular file at path (at most max_bytes) into *text. False
// with a one-line *error naming the path and what it is ("a FIFO", "a
// symbolic link", "larger than N bytes") otherwise.
bool ReadRegularFile(const std::string& path, size_t max_bytes, LinkPolicy links, std::string* text,
                     std::string* error);

// Mode and owner a replaced file gets.
struct FileAttributes {
  mode_t mode = 0644;      // permission bits
  bool set_owner = false;  // chown to uid:gid (false: the writer's own)
  uid_t uid = 0;
  gid_t gid = 0;
};

// What lstat says of path: kAbsent, kRegular, or kOther (link, FIFO, device,
// folder, socket). *attributes (may be null) gets a regular file's mode and
// owner (set_owner true).
enum class PathKind { kAbsent, kRegular, kOther };
PathKind InspectPath(const std::string& path, FileAttributes* attributes, std::string* description);

// Replaces (or creates) the regular file path with text: unique temporary in
// the same folder, fchmod/fchown to attributes, fsync, rename, fsync of the
// folder. False with *error when path exists and is not a regular file, when
// the owner cannot be kept, or on any write failure; the target is then
// unchanged and the temporary removed.
bool ReplaceRegularFile(const std::string& path, const std::string& text, const FileAttributes& attributes,
                        std::string* error);

}  // namespace birotor
