// cyclone-world: runs scene files. Everything but argument plumbing lives in cli.cpp.
#include <unistd.h>

#include <exception>
#include <iostream>
#include <string>
#include <vector>

#include "cli.h"

int main(int argc, char **argv) {
    try {
        std::vector<std::string> args(argv + 1, argv + argc);
        return cyclone::scene::runCommandLine(args, std::cout, std::cerr, ::isatty(STDERR_FILENO) == 1);
    } catch (const std::exception &error) {
        std::cerr << "cyclone-world: " << error.what() << "\n";
    } catch (...) {
        std::cerr << "cyclone-world: unexpected error\n";
    }
    return cyclone::scene::kExitRefused;
}
