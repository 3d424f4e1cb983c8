// Reading STEP and BREP files in a child process bounded in time and memory.
//
// OpenCASCADE's readers trust their input: a hostile or corrupt file can send them into
// an endless loop, a huge allocation or a crash, none of which kintsugi can catch in
// its own process. With bounds set (the kintsugi program sets them in apps/main.cpp), a
// read forks a child that reads the file with io::import_cad under RLIMIT_AS and hands
// the body back through a pipe as a native document; the parent kills it at the
// deadline. Every way it can end badly becomes an error naming the file. Without bounds
// set (the library, the Python package) io::import_cad runs in-process.
//
// The bounds come from the environment so that every verb shares them:
//   KINTSUGI_READ_TIMEOUT      seconds (default 300)
//   KINTSUGI_READ_MAX_MEMORY   bytes of address space, "512M", "4G" (default 16G; 0: none)
// Under AddressSanitizer no memory bound is set (its shadow memory needs terabytes of
// address space); the time bound still holds.
#pragma once

#ifdef KINTSUGI_HAVE_OCCT
#include "io/occt/exchange.h"
#endif

#include <cstdint>
#include <optional>
#include <string>

namespace kintsugi::cli {

struct ReadBounds {
  double seconds = 300;
  std::uint64_t max_memory = std::uint64_t(16) << 30;
};

// From KINTSUGI_READ_TIMEOUT and KINTSUGI_READ_MAX_MEMORY; nullopt and *error on a
// malformed value.
std::optional<ReadBounds> read_bounds_from_environment(std::string* error);
// Turns the child-process reads on for this process (single-threaded callers only: the
// child runs OpenCASCADE after fork without exec).
void bound_cad_reads(const ReadBounds& b);

#ifdef KINTSUGI_HAVE_OCCT
// io::import_cad, in a bounded child when bound_cad_reads was called. The warnings are
// not carried back from the child.
std::optional<io::CadImport> import_cad_bounded(const std::string& path, io::CadFormat f, std::string* error);
#endif

}  // namespace kintsugi::cli
