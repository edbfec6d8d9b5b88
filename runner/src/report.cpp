#include "report.h"

#include <cstdio>
#include <optional>

#include "summary.h"

namespace cyclone::scene {

namespace {

std::string format(const char *pattern, double value) {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, pattern, value);
    return buffer;
}

std::string formatVector(const Vector3 &v) {
    char buffer[128];
    std::snprintf(buffer, sizeof buffer, "(%.4f, %.4f, %.4f)", v.x(), v.y(), v.z());
    return buffer;
}

// "Up" is against gravity; a world without gravity uses +y.
Vector3 upDirection(const Scene &scene) {
    const Vector3 &g = scene.world.gravity;
    const real scale = g.cwiseAbs().maxCoeff();
    if (!(scale > 0)) return Vector3::UnitY();
    return -(g / scale).normalized();
}

// The dynamic body still in the world that started highest.
std::optional<std::size_t> highestDynamicBody(const Scene &scene, const SceneWorld &built) {
    const Vector3 up = upDirection(scene);
    std::optional<std::size_t> highest;
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
        const BodySettings &body = scene.bodies[i].settings;
        if (body.motion != Motion::Dynamic || !built.world.contains(built.ids[i])) continue;
        if (!highest || up.dot(body.position) > up.dot(scene.bodies[*highest].settings.position)) highest = i;
    }
    return highest;
}

}  // namespace

void writeReport(std::ostream &out, const std::string &file, const Scene &scene, const SceneWorld &built,
                 const RunResult &result) {
    const World &world = built.world;
    std::size_t dynamicBodies = 0, kinematicBodies = 0, staticBodies = 0;
    for (const BodyId id : world.bodies()) {
        switch (world.motion(id)) {
        case Motion::Dynamic: ++dynamicBodies; break;
        case Motion::Kinematic: ++kinematicBodies; break;
        case Motion::Static: ++staticBodies; break;
        }
    }
    const StepTimes times = result.stepTimes.summary();
    out << "scene        " << scene.name << " (" << file << ")\n";
    // Kinematic bodies are named only when there are some, so that a scene without them
    // reads as it always has.
    out << "bodies       " << world.bodyCount() << " (" << dynamicBodies << " dynamic, "
        << (kinematicBodies ? std::to_string(kinematicBodies) + " kinematic, " : "") << staticBodies << " static)\n";
    out << "steps        " << result.steps << " x " << format("%g", result.dt * 1000.0) << " ms = "
        << format("%g", static_cast<double>(result.steps) * result.dt) << " s simulated in "
        << format("%.3f", result.wallSeconds) << " s\n";
    out << "ms per step  median " << format("%.3f", times.median) << ", mean " << format("%.3f", times.mean)
        << ", max " << format("%.3f", times.max) << "\n";
    if (result.firstAllAsleepStep) {
        const std::int64_t step = *result.firstAllAsleepStep;
        out << "asleep       everything asleep after step " << step << " (t = "
            << format("%.3f", static_cast<double>(step + 1) * result.dt) << " s)";
        const int awake = awakeDynamicBodies(world);
        if (awake > 0) out << "; " << awake << " awake again at the end";
        out << "\n";
    } else {
        out << "asleep       never: " << awakeDynamicBodies(world) << " of " << dynamicBodies
            << " dynamic bodies awake after the last step\n";
    }
    if (const auto top = highestDynamicBody(scene, built)) {
        const Vector3 start = scene.bodies[*top].settings.position;
        const Vector3 end = world.body(built.ids[*top]).getPosition();
        out << "top body     " << scene.bodies[*top].settings.name << " drifted " << format("%.4g", (end - start).norm())
            << " m: " << formatVector(start) << " -> " << formatVector(end) << "\n";
    } else {
        out << "top body     none (no dynamic body)\n";
    }
    out << "penetration  " << format("%.4g", world.stats().maxPenetration) << " m deepest in the last step, "
        << format("%.4g", result.maxPenetrationOfRun) << " m over the run\n";
    if (result.nonFinite) out << "NON-FINITE   " << result.nonFiniteWhat << "\n";
}

std::string resultLine(const Scene &scene, const SceneWorld &built, const RunResult &result) {
    const StepTimes times = result.stepTimes.summary();
    std::string line = scene.name + ": " + std::to_string(result.steps) + " steps, " +
                       std::to_string(built.world.bodyCount()) + " bodies, " + format("%.3f", times.mean) +
                       " ms/step (median " + format("%.3f", times.median) + ", max " + format("%.3f", times.max) +
                       "), ";
    if (result.firstAllAsleepStep) {
        line += "all asleep after step " + std::to_string(*result.firstAllAsleepStep);
    } else {
        line += std::to_string(awakeDynamicBodies(built.world)) + " awake at the end";
    }
    return line + ", KE " + format("%.4g", built.world.kineticEnergy()) + " J";
}

}  // namespace cyclone::scene
