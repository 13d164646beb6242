// The doctest main of every vplkit test program. After the tests it destroys the shared context
// while still able to fail: the layer reports leaked objects at vkDestroyDevice, outside any test
// case, and such a message makes the program (hence the ctest test that ran it) fail.

#define DOCTEST_CONFIG_IMPLEMENT
#include <doctest/doctest.h>

#include "support_state.hpp"

#include <cstdio>

int main(int argc, char** argv) {
    doctest::Context runner;
    runner.applyCommandLine(argc, argv);
    int result = runner.run();
    if (runner.shouldExit()) return result;

    vplkit::test::detail::destroy_shared_context();
    auto& s = vplkit::test::detail::state();
    std::lock_guard lock(s.mutex);
    if (!s.outside_tests.empty()) {
        std::fprintf(stderr, "vplkit test: %zu validation message(s) outside test cases (see above): failing\n",
                     s.outside_tests.size());
        if (result == 0) result = 1;
    }
    return result;
}
