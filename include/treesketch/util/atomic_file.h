// Writing outputs safely: everything is written to a temporary file beside the target and
// renamed over it only when the whole write succeeded, so a failure never leaves a truncated
// output and never touches an existing file. Temporary files are named `.NAME.tmpPID_N`; the
// ones of a process that died (killed mid-write) are removed by the next write to the same
// output, and a program that calls removeTempFilesOnSignals() removes its own on SIGINT,
// SIGTERM and SIGHUP.
#pragma once

#include <filesystem>
#include <functional>
#include <ostream>

namespace treesketch {

/// Calls `write` with a stream to a temporary file in the target's directory, flushes it and
/// renames it to `path`. A missing target directory is an OutputError naming it, unless
/// setCreateOutputDirectories(true) was called: then it is created (with its parents) first, and
/// only a directory that cannot be created (a regular file in the way, no permission) is an error.
/// If `write` throws or the stream fails, the temporary file is removed, `path` is left as it was,
/// and the exception (or an OutputError) propagates. Before writing, stale temporary files of
/// `path` (see removeStaleTempFiles) are removed. `binary` opens the stream in binary mode.
void writeFileAtomically(const std::filesystem::path& path, const std::function<void(std::ostream&)>& write,
                         bool binary = true);

/// Whether writeFileAtomically creates missing output folders (default false: the library does
/// not make folders behind a caller's back; the treesketch command turns it on at start, so its
/// outputs' folders are created when missing). Process-wide; thread-safe.
void setCreateOutputDirectories(bool create);

/// Throws OutputError if `output` names the same existing file as any of `inputs`: an input is
/// never overwritten.
void checkNotAnInput(const std::filesystem::path& output, std::initializer_list<std::filesystem::path> inputs);

/// Makes sure `path` can be written before any work is done: creates its missing parent folders,
/// then throws OutputError (naming the path and the reason) when `path` is an existing directory,
/// its folder is not a directory, or the folder is not writable by this process. An empty path
/// is ignored (an output that was not asked for).
void checkOutputWritable(const std::filesystem::path& path);

/// Removes the temporary files `.NAME.tmpPID_N` of `path` (NAME its file name) left in its folder
/// by a process PID that no longer runs (killed during a write). Files of running processes,
/// and any other file, are left alone. Returns how many were removed; never throws.
std::size_t removeStaleTempFiles(const std::filesystem::path& path);

/// Installs handlers for SIGINT, SIGTERM and SIGHUP (those whose action is still the default)
/// that unlink the temporary files of writes in progress and then re-raise the signal with its
/// default action, so the process ends as it would have. For programs (the CLI, the desktop
/// tool); the library never installs it by itself. Calling it again does nothing.
void removeTempFilesOnSignals();

}  // namespace treesketch
