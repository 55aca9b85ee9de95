// A user program: consumes stickslip through its CMake package and checks one real number.
#include <stickslip/stickslip.hpp>

#include <cstdio>
#include <cstring>

int main() {
  if (std::strcmp(stickslip::version_string(), STICKSLIP_VERSION_STRING) != 0) return 1;
  std::printf("stickslip %s consumed\n", stickslip::version_string());
  return 0;
}
