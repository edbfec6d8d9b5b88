// What the small bench tools (cyclone-stages, cyclone-drift) share: options given as
// "--name value" pairs, and a main that turns an exception into one line and status 2.
#pragma once

#include <cstdio>
#include <exception>
#include <string>

namespace cyclone::bench {

/// Reads the option at argv[i] and its value into `name` and `value`, moving i past both.
/// False, after one line on stderr, when the value is missing.
inline bool readOption(const char *tool, int argc, char **argv, int &i, std::string &name, std::string &value) {
    name = argv[i];
    if (i + 1 >= argc) {
        std::fprintf(stderr, "%s: %s needs a value\n", tool, name.c_str());
        return false;
    }
    value = argv[++i];
    return true;
}

/// Runs `run`; an exception becomes one line on stderr and exit status 2.
inline int guardedMain(const char *tool, int (*run)(int, char **), int argc, char **argv) {
    try {
        return run(argc, argv);
    } catch (const std::exception &e) {
        std::fprintf(stderr, "%s: %s\n", tool, e.what());
        return 2;
    }
}

}  // namespace cyclone::bench
