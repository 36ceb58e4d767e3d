// Error types thrown by the treesketch library for bad input files, bad options and failed
// outputs. Legitimate outcomes ("no circle found", "node skipped") are returned, not thrown.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>

namespace treesketch {

/// A file (or stream) that cannot be read as what was expected. The message always names the
/// source, the position (line or byte offset, when known) and what was expected.
class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& message) : std::runtime_error(message) {}
};

/// An output that could not be written (directory missing, disk full, permission...).
class OutputError : public std::runtime_error {
 public:
  explicit OutputError(const std::string& message) : std::runtime_error(message) {}
};

/// Options or arguments out of range or inconsistent (a negative thickness, an empty sketch...).
class OptionsError : public std::invalid_argument {
 public:
  explicit OptionsError(const std::string& message) : std::invalid_argument(message) {}
};

/// Input that was read correctly but from which no result can be made: a mesh with zero area, a
/// scan that hits nothing, a cloud with no circle to fit (all points equal or on one line). The
/// message names the input and what is degenerate about it.
class DegenerateInputError : public std::runtime_error {
 public:
  explicit DegenerateInputError(const std::string& message) : std::runtime_error(message) {}
};

/// "file:line: what" — the message of an InputError at a text line (1-based).
std::string atLine(const std::string& source, std::size_t line, const std::string& what);
/// "file: byte offset N: what" — the message of an InputError at a binary offset.
std::string atOffset(const std::string& source, std::uint64_t offset, const std::string& what);

}  // namespace treesketch
