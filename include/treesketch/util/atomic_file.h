// Writing outputs safely: everything is written to a temporary file beside the target and
// renamed over it only when the whole write succeeded, so a failure never leaves a truncated
// output and never touches an existing file.
#pragma once

#include <filesystem>
#include <functional>
#include <ostream>

namespace treesketch {

/// Calls `write` with a stream to a temporary file in the target's directory, flushes it and
/// renames it to `path`. A missing target directory is an OutputError naming it, unless
/// setCreateOutputDirectories(true) was called: then it is created (with its parents) first, and
/// only a directory that cannot be created (a regular file in the way, no permission) is an error. If `write` throws or
/// the stream fails, the temporary file is removed, `path` is left as it was, and the exception (or an OutputError)
/// propagates. `binary` opens the stream in binary mode.
void writeFileAtomically(const std::filesystem::path& path, const std::function<void(std::ostream&)>& write,
                         bool binary = true);

/// Whether writeFileAtomically creates missing output folders (default false: the library does
/// not make folders behind a caller's back; the treesketch command turns it on at start, so its
/// outputs' folders are created when missing). Process-wide; thread-safe.
void setCreateOutputDirectories(bool create);

/// Throws OutputError if `output` names the same existing file as any of `inputs`: an input is
/// never overwritten.
void checkNotAnInput(const std::filesystem::path& output, std::initializer_list<std::filesystem::path> inputs);

}  // namespace treesketch
