// main() of a standalone study binary: PENUMBRA_BENCH_STUDY names the function (bench/studies.h).
#include "studies.h"

int main(int argc, char** argv) { return penumbra::bench::PENUMBRA_BENCH_STUDY(argc, argv, stdout); }
