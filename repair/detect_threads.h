// How many threads a whole-body detection may use to measure faces and edges. The
// measures are independent per element and each is computed by the same function
// whatever thread runs it, so the problems found — and so the report and the output of
// beautify — are the same for any number (Detect.OneAndTwoThreadsFindTheSame,
// Pipeline.OneAndTwoThreadsGiveTheSameBytes).
#pragma once

namespace kintsugi {

// The number in force: set_detect_threads's, else the environment's KINTSUGI_THREADS (a
// whole number from 1 to 64), else the machine's hardware threads (at most 8).
int detect_threads();
// n ≥ 1 sets it; 0 goes back to the default above.
void set_detect_threads(int n);

}  // namespace kintsugi
