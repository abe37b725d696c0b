// Writing an output to the path a user named, the one way every program of handlab does.
#pragma once

#include <functional>
#include <ostream>
#include <stdexcept>
#include <string>
#include <string_view>

namespace handlab::util {

// An output that cannot be written where it was asked; the message names the path and why.
class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Writes what `write` streams to `path`, as a user expects of what the path names:
//   "-"                         standard output;
//   a new path or regular file  a temporary file beside it, renamed over it once complete (a
//                               failed or killed run never leaves half a file; a replaced
//                               file keeps its permissions);
//   a character device or FIFO  written through (/dev/null stays the device it is);
//   one of the process' open descriptors (/dev/stdout, /dev/fd/N, /proc/self/fd/N)
//                               written to that descriptor;
//   a symbolic link             followed to its target, to which the rules above apply.
// A directory, a block device, a socket or a missing folder is refused with OutputError; so is
// any failure while writing, which leaves no temporary file behind.
void write_output(const std::string& path, const std::function<void(std::ostream&)>& write);

// Whether write_output writes `path` through as a stream (standard output, a device, a pipe,
// one of the process' descriptors) rather than as a file it names: such an output has no
// extension to choose a format by.
bool is_stream_output(const std::string& path);

// The same for bytes made in memory (a PNG, a PDF).
void write_output_bytes(const std::string& path, std::string_view bytes);

// Makes the folder `path` (and its parents) for outputs, or accepts one that is there;
// refuses with OutputError naming what is in the way (a file of that name, no permission).
void make_output_folder(const std::string& path);

}  // namespace handlab::util
