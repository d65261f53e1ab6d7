// One libFuzzer target per entry point of tests/fuzz/fuzz_entry.h; the build compiles this file once
// per target with -DADASCULPT_FUZZ_TARGET="name" (CMakeLists.txt, sanitized clang builds; run by scripts/fuzz.sh).
// A ContractViolation or an exception of an undocumented type aborts, which libFuzzer reports as a
// crash and saves the input.
#include <cstdio>
#include <cstdlib>
#include <exception>

#include "fuzz_entry.h"

#ifndef ADASCULPT_FUZZ_TARGET
#error "compile with -DADASCULPT_FUZZ_TARGET=\"off|obj|stl|ply|load_mesh|session_file\""
#endif

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    adasculpt::fuzz::run_target(ADASCULPT_FUZZ_TARGET, data, size);
  } catch (const adasculpt::fuzz::ContractViolation& e) {
    std::fprintf(stderr, "fuzz[%s]: contract violation: %s\n", ADASCULPT_FUZZ_TARGET, e.what());
    std::abort();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fuzz[%s]: undocumented exception: %s\n", ADASCULPT_FUZZ_TARGET, e.what());
    std::abort();
  }
  return 0;
}
