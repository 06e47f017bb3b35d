// The sanitizer passes' self-check (docs/hardening.md): each argument makes one mistake the
// pass exists to find, so a sanitizer build that no longer reports it (flags lost, a runtime
// option that silences it, TSan blind to OpenMP) fails its test. Built and run only in
// sanitizer builds (WEFT_SANITIZE).
//
//   weft_sanitizer_selfcheck heap-overflow | signed-overflow | leak | openmp-race

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

namespace {

// volatile: keeps the compiler from proving the mistakes away.
volatile int gIndex = 8;
volatile int gBig = 2147483647;

int heapOverflow() {
  std::vector<int> v(8, 1);
  return v.data()[gIndex];  // one past the end
}

int signedOverflow() {
  const int big = gBig;
  return big + 1;
}

int leak() {
  int* p = new int[16];
  p[0] = gIndex;
  return p[0] == 8 ? 0 : 1;  // never deleted
}

int openmpRace() {
  int sum = 0;
#pragma omp parallel for num_threads(2)
  for (int i = 0; i < 100000; ++i) sum += i % 3;  // unsynchronised read-modify-write
  return sum == -1;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s heap-overflow|signed-overflow|leak|openmp-race\n", argv[0]);
    return 2;
  }
  if (!std::strcmp(argv[1], "heap-overflow")) return heapOverflow();
  if (!std::strcmp(argv[1], "signed-overflow")) return signedOverflow();
  if (!std::strcmp(argv[1], "leak")) return leak();
  if (!std::strcmp(argv[1], "openmp-race")) return openmpRace();
  std::fprintf(stderr, "unknown mistake %s\n", argv[1]);
  return 2;
}
