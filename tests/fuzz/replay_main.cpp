// Replays fuzz inputs without libFuzzer: `stickslip_fuzz_replay <harness> <file or directory>...`
// feeds every file (directories: every regular file in them, sorted) to the harness's entry point
// and prints each file name before running it, so that a crash or a violation (which abort) names
// its input. Exit status 0 when every input passed. The CTest tests of label `fuzz` run it on each
// file of tests/fuzz/corpus/<harness>/ (tests/fuzz/CMakeLists.txt).
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

int stickslip_fuzz_contact(const std::uint8_t*, std::size_t);
int stickslip_fuzz_stepper(const std::uint8_t*, std::size_t);
int stickslip_fuzz_frame_modes(const std::uint8_t*, std::size_t);
int stickslip_fuzz_member_shapes(const std::uint8_t*, std::size_t);
int stickslip_fuzz_model(const std::uint8_t*, std::size_t);
int stickslip_fuzz_steady_state(const std::uint8_t*, std::size_t);
int stickslip_fuzz_separation(const std::uint8_t*, std::size_t);

namespace {

using Entry = int (*)(const std::uint8_t*, std::size_t);

struct Harness {
  const char* name;
  Entry entry;
};

constexpr Harness kHarnesses[] = {
    {"contact", stickslip_fuzz_contact},
    {"stepper", stickslip_fuzz_stepper},
    {"frame_modes", stickslip_fuzz_frame_modes},
    {"member_shapes", stickslip_fuzz_member_shapes},
    {"model", stickslip_fuzz_model},
    {"steady_state", stickslip_fuzz_steady_state},
    {"separation", stickslip_fuzz_separation},
};

int usage() {
  std::fprintf(stderr, "usage: stickslip_fuzz_replay <harness> <file or directory>...\nharnesses:");
  for (const Harness& h : kHarnesses) std::fprintf(stderr, " %s", h.name);
  std::fprintf(stderr, "\n");
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) return usage();
  const auto it = std::find_if(std::begin(kHarnesses), std::end(kHarnesses),
                               [&](const Harness& h) { return std::strcmp(h.name, argv[1]) == 0; });
  if (it == std::end(kHarnesses)) return usage();
  std::vector<std::filesystem::path> files;
  for (int a = 2; a < argc; ++a) {
    const std::filesystem::path p(argv[a]);
    if (std::filesystem::is_directory(p)) {
      std::vector<std::filesystem::path> in_dir;
      for (const auto& e : std::filesystem::directory_iterator(p))
        if (e.is_regular_file()) in_dir.push_back(e.path());
      std::sort(in_dir.begin(), in_dir.end());
      files.insert(files.end(), in_dir.begin(), in_dir.end());
    } else if (std::filesystem::is_regular_file(p)) {
      files.push_back(p);
    } else {
      std::fprintf(stderr, "stickslip_fuzz_replay: no such file or directory: %s\n", argv[a]);
      return 2;
    }
  }
  for (const auto& f : files) {
    std::ifstream s(f, std::ios::binary);
    const std::vector<char> bytes((std::istreambuf_iterator<char>(s)), std::istreambuf_iterator<char>());
    std::printf("%s: %s (%zu bytes)\n", it->name, f.string().c_str(), bytes.size());
    std::fflush(stdout);
    it->entry(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
  }
  std::printf("%s: %zu inputs passed\n", it->name, files.size());
  return 0;
}
