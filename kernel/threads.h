// The threads kintsugi may use, as the user asked: the environment's KINTSUGI_THREADS.
#pragma once

namespace kintsugi {

// KINTSUGI_THREADS when it is a whole number from 1 to 64, else the machine's hardware
// threads (at most 8; at least 1). Read on each call: cheap next to the work it sizes.
int threads_from_environment();

}  // namespace kintsugi
