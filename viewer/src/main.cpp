// cyclone-viewer: opens a scene file in a window and runs it live (see options.cpp for the
// command line, app.h for the window).
#include <cstdio>
#include <exception>
#include <stdexcept>

#include "app.h"
#include "json_document.h"
#include "options.h"

int main(int argc, char **argv) {
    using namespace cyclone::viewer;
    std::string error;
    const std::optional<Options> options = parseOptions(argc, argv, error);
    if (!options) {
        if (error.empty()) {
            std::fputs(usage(), stdout);
            return 0;
        }
        std::fprintf(stderr, "cyclone-viewer: %s\n%s", error.c_str(), usage());
        return 2;
    }
    try {
        App app(*options);
        return app.run();
    } catch (const std::invalid_argument &usageError) {
        std::fprintf(stderr, "cyclone-viewer: %s\n", usageError.what());
        return 2;
    } catch (const cyclone::scene::SceneError &sceneError) {
        std::fprintf(stderr, "cyclone-viewer: %s\n", sceneError.what());
        return 2;
    } catch (const std::exception &failure) {
        std::fprintf(stderr, "cyclone-viewer: %s\n", failure.what());
        return 1;
    }
}
