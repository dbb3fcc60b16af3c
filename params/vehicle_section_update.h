// In-place update of the `vehicle:` section of a complete parameter file
// (the estimator's file, a scenario): every vehicle key's value is replaced
// by the new one, and everything else of the text (other sections, comments,
// trailing comments on the key lines, key order) is kept. Used by
// `birotor-identify --update-params` for one-step deployment.
#pragma once

#include <sys/types.h>

#include <string>
#include <vector>

#include "model/birotor_params.h"
#include "params/regular_file.h"

namespace birotor {

// The comment line that stamps an identification in the vehicle section:
// "  # identified <stamp>" right below `vehicle:`.
constexpr const char* kIdentificationStampPrefix = "# identified ";

// Returns `text` with the value of every key of the `vehicle:` section
// (VehicleKeys() plus gauge_scale and gauge_offset_rad) set to `params`, and
// the identification stamp line set to `stamp` (replaced when present,
// inserted below `vehicle:` otherwise; no stamp line when empty). False (with
// *error naming the key) when the section or one of its keys is missing.
bool UpdateVehicleSection(const std::string& text, const BirotorParams& params, const std::string& stamp,
                          std::string* updated, std::string* error);

// The same for a description in the N-arm form (docs/vehicle-description.md):
// `key` of every element of the vehicle section's `arms:` block list set to
// values[i], in arm order, every other byte kept (trailing comments too), and
// the stamp line as above. False (with *error naming the key) when the list
// does not have values.size() elements, or an element lacks the key or has
// it twice.
bool UpdateDescriptionArmValues(const std::string& text, const std::string& key, const std::vector<double>& values,
                                const std::string& stamp, std::string* updated, std::string* error);

// The identification stamp of a parameter file's vehicle section, or an
// empty string when it has none (or the file cannot be read).
std::string ReadIdentificationStamp(const std::string& file);

// A parameter file updated in place (birotor-identify --update-params),
// checked before the fit and written after it (docs/files.md):
//  - a symbolic link is updated through its target: `target` is the file at
//    the end of the links (realpath), replaced in its own folder, and the
//    link is kept; the backup is `<target>.bak`;
//  - the target must be a regular file of at most 1 MB (a FIFO or a device is
//    refused without waiting), in a folder the tool may write;
//  - `<target>.bak` may be absent or a regular file; anything else there (a
//    link to a block device, a FIFO) is refused and left alone;
//  - both files are written whole through a unique temporary file and a
//    rename (regular files only), with the target's mode and owner.
struct ParameterFileUpdate {
  std::string path;           // as given
  std::string target;         // the file replaced (path without links)
  std::string backup;         // target + ".bak"
  std::string text;           // the target's content when checked
  FileAttributes attributes;  // the target's mode and owner, given to both files
  dev_t device = 0;           // the target's identity, checked again at commit
  ino_t inode = 0;
};

// Checks path as above and reads it. False with a one-line *error otherwise.
bool PrepareParameterFileUpdate(const std::string& path, ParameterFileUpdate* update, std::string* error);

// Writes update.text to update.backup and updated_text over update.target.
// Refused (nothing written) when the target is no longer the file checked
// (another inode, other content) or the backup slot is no longer free.
bool CommitParameterFileUpdate(const ParameterFileUpdate& update, const std::string& updated_text, std::string* error);

}  // namespace birotor
