// The codegen tests' own main: this suite depends on nothing but doctest, Vulkan and the
// fixture headers.
#define DOCTEST_CONFIG_IMPLEMENT_WITH_MAIN
#include <doctest/doctest.h>
