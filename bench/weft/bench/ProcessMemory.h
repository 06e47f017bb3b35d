#pragma once
// This process's memory as Linux reports it in /proc/self (benchmarks only: `weft bench contact`
// reads each run's peak, `weft bench soak` samples the resident set as a long run goes on).

namespace weft::bench {

// Resets the kernel's peak-RSS mark (VmHWM) of this process by writing "5" to
// /proc/self/clear_refs; false where that is not supported.
bool resetPeakMemory();
// VmHWM, the peak resident set since the last reset, in MB; 0 when unavailable.
double peakMemoryMb();
// VmRSS, the resident set now, in MB; 0 when unavailable.
double residentMemoryMb();

}  // namespace weft::bench
