// tests/fuzz/targets/fuzz_target.h — what every fuzz target here accepts: the input loads, or the
// project's InputError says why not (core/base/errors.h). Any other exception escapes
// LLVMFuzzerTestOneInput and aborts the process, which libFuzzer (and the replay test,
// tests/fuzz/replay_test.cpp) reports as a finding, as it does a crash, a hang or a sanitizer
// report.
#pragma once
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "core/base/errors.h"

namespace sl::fuzz {

// Runs `body` and returns libFuzzer's "input processed" (0) when it completes or throws
// InputError; any other exception propagates (std::terminate: a finding). With
// SHADOWLAB_FUZZ_VERBOSE set, says which of the two on stderr (to see what a corpus exercises).
template <typename Body>
int acceptLoadedOrInputError(Body&& body) {
  const bool verbose = std::getenv("SHADOWLAB_FUZZ_VERBOSE") != nullptr;
  try {
    body();
    if (verbose) std::fprintf(stderr, "fuzz input: loaded\n");
  } catch (const InputError& e) {
    if (verbose) std::fprintf(stderr, "fuzz input: InputError: %s\n", e.what());
  }
  return 0;
}

inline std::string bytesAsString(const std::uint8_t* data, std::size_t size) {
  return std::string(reinterpret_cast<const char*>(data), size);
}

}  // namespace sl::fuzz
