// Every seed of one fuzz target's corpus (test/fuzz/corpus/<target>/, HEX_SLAM_FUZZ_CORPUS) run
// through that target's LLVMFuzzerTestOneInput, built by the default compiler without libFuzzer:
// the harnesses keep compiling in every build (only scripts/fuzz links libFuzzer), and an input
// a fuzzer once crashed on, saved into the corpus, stays a regression test of the default suite.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace {

TEST(FuzzCorpusReplay, EverySeedRunsToTheEnd) {
  const std::filesystem::path corpus(HEX_SLAM_FUZZ_CORPUS);
  ASSERT_TRUE(std::filesystem::is_directory(corpus)) << corpus;
  int seeds = 0;
  for (const auto& entry : std::filesystem::directory_iterator(corpus)) {
    if (!entry.is_regular_file()) continue;
    std::ifstream in(entry.path(), std::ios::binary);
    const std::vector<char> bytes((std::istreambuf_iterator<char>(in)),
                                  std::istreambuf_iterator<char>());
    SCOPED_TRACE(entry.path().string());
    // A broken promise aborts (fuzz_check.h) and fails the whole test binary.
    EXPECT_EQ(0, LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(bytes.data()),
                                        bytes.size()));
    ++seeds;
  }
  EXPECT_GT(seeds, 0) << "no seeds in " << corpus;
}

}  // namespace
