// What `timing.compute: charged` costs the loop per call: one read of the calling thread's CPU
// clock (two per call; two more for a Python method's own process). Prints ns per read.
//   g++ -O2 -std=c++20 tools/measure/reference_compute/clock_cost.cc -o /tmp/clock_cost && /tmp/clock_cost
#include <time.h>

#include <chrono>
#include <cstdio>

int main() {
  timespec ts{};
  long long sum = 0;
  const int n = 1000000;
  const auto t0 = std::chrono::steady_clock::now();
  for (int i = 0; i < n; ++i) {
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    sum += ts.tv_nsec;
  }
  const double ns = std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - t0).count() / n;
  std::printf("%.0f ns per CLOCK_THREAD_CPUTIME_ID read (checksum %lld)\n", ns, sum % 10);
}
