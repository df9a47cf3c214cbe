// Entry point of the benchmark binary. Written out rather than linking benchmark::benchmark_main:
// libfuzzylite also exports a main() (its console tool), and which one the linker picks would
// depend on the link order.
#include <benchmark/benchmark.h>

BENCHMARK_MAIN();
