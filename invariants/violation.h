// The violation record lives in the kernel (kernel/violation.h), whose operators check
// themselves; this header keeps the old include path working for callers above it.
#pragma once

#include "kernel/violation.h"
