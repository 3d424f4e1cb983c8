// Filled in by a later commit of issue 8.
#include <gtest/gtest.h>
