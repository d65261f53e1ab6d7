// Replays every saved fuzzer input through the fuzzed entry points (tests/fuzz/fuzz_entry.h): the
// regression inputs of tests/fuzz/regressions/<target>/ (crashes, leaks, UB and hangs found by
// scripts/fuzz.sh) and the seed corpora of tests/fuzz/corpus/<target>/. Each must either succeed with
// its guarantees intact or be refused with the documented exception; under the ASan/UBSan build a
// memory error or UB aborts the test. Files are read in name order; failures name the file.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "../fuzz/fuzz_entry.h"

namespace {

namespace fs = std::filesystem;

std::vector<fs::path> inputs(const std::string& kind, const std::string& target) {
  const fs::path dir = fs::path(ADASCULPT_SOURCE_DIR) / "tests" / "fuzz" / kind / target;
  std::vector<fs::path> files;
  if (!fs::is_directory(dir)) return files;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.is_regular_file() && e.path().filename().string()[0] != '.') files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

std::vector<uint8_t> bytes_of(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::vector<uint8_t>(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void replay(const std::string& kind, const std::string& target, size_t min_files) {
  const std::vector<fs::path> files = inputs(kind, target);
  EXPECT_GE(files.size(), min_files) << "tests/fuzz/" << kind << "/" << target;
  for (const fs::path& f : files) {
    SCOPED_TRACE(f.string());
    const std::vector<uint8_t> data = bytes_of(f);
    try {
      adasculpt::fuzz::run_target(target, data.data(), data.size());
    } catch (const adasculpt::fuzz::ContractViolation& e) {
      ADD_FAILURE() << f.filename() << ": contract violation: " << e.what();
    } catch (const std::exception& e) {
      ADD_FAILURE() << f.filename() << ": undocumented exception: " << e.what();
    }
  }
}

class ReliabilityFuzz : public ::testing::TestWithParam<std::string> {};

TEST_P(ReliabilityFuzz, RegressionInputs) { replay("regressions", GetParam(), 0); }
TEST_P(ReliabilityFuzz, SeedCorpus) { replay("corpus", GetParam(), 1); }

INSTANTIATE_TEST_SUITE_P(Targets, ReliabilityFuzz, ::testing::ValuesIn(adasculpt::fuzz::target_names()),
                         [](const ::testing::TestParamInfo<std::string>& i) { return i.param; });

// The readers stay strict about the documented exception type even without a build of the fuzzers.
TEST(ReliabilityFuzzEntry, UnknownTargetIsRefused) {
  const uint8_t b[1] = {0};
  EXPECT_THROW(adasculpt::fuzz::run_target("nope", b, 1), std::invalid_argument);
  EXPECT_EQ(adasculpt::fuzz::run_target("off", b, 0), adasculpt::fuzz::Outcome::Refused);
  EXPECT_EQ(adasculpt::fuzz::run_target("session_file", b, 0), adasculpt::fuzz::Outcome::Refused);
}

}  // namespace
