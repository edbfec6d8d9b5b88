// The report's summary: which setting to pick for what, with the figures of this run that
// say why.
#include <cmath>
#include <ostream>
#include <string>
#include <vector>

#include "accuracy_report.h"

namespace cyclone::accuracy {
namespace {

// The result of one configuration, or nullptr (a --quick run has fewer step sizes).
const Row *lookup(const std::vector<Row> &rows, const std::string &scene, const std::string &key,
                  const std::string &scheme, int substeps, double dt, int iterations = 3) {
    for (const Row &r : rows)
        if (r.scene == scene && r.key == key && integratorName(r.config) == scheme && r.config.substeps == substeps &&
            r.config.iterations == iterations && std::abs(r.config.dt - dt) < 1e-12)
            return &r;
    return nullptr;
}

std::string value(const Row *r) { return r ? number(r->error, 3) : "n/a"; }
std::string cost(const Row *r) { return r ? number(r->cpuMsPerSimSecond, 2) + " ms" : "n/a"; }

}  // namespace

void writeSummary(std::ostream &md, const std::vector<Row> &rows) {
    const double dt = 1.0 / 60;
    const auto at = [&](const std::string &scene, const std::string &key, const std::string &scheme, int substeps = 4,
                        double step = 1.0 / 60, int iterations = 3) {
        return lookup(rows, scene, key, scheme, substeps, step, iterations);
    };
    const std::string ne = "newton-euler", gyro = "newton-euler-gyroscopic", mc = "momentum-conserving",
                      implicit = "newton-euler-implicit", split = "splitting (bench only)",
                      explicitSprings = "newton-euler (explicit springs)",
                      noSpeculative = "newton-euler (no speculative contacts)";
    md << "\n## Which setting to pick\n\n"
       << "Figures at 1/60 s steps, 4 sub-steps and 3 iterations unless said; cost is CPU time per simulated "
       << "second.\n\n"
       << "| you simulate | pick | why (measured below) |\n|---|---|---|\n";
    md << "| most scenes: stacks, sliding, rolling, bouncing, thrown things | the defaults (`newton-euler`, 4 "
       << "sub-steps, 3 iterations) | first order (projectile " << value(at("projectile", "position", ne))
       << " m off after 2 s, " << value(at("projectile", "position", ne, 4, dt / 2))
       << " m at 1/120 s); sliding box " << value(at("sliding-box", "distance", ne, 1)) << " m short with 1 sub-step ("
       << cost(at("sliding-box", "distance", ne, 1)) << "), " << value(at("sliding-box", "distance", ne))
       << " m with 4 (" << cost(at("sliding-box", "distance", ne)) << "), "
       << value(at("sliding-box", "distance", ne, 4, dt, 10)) << " m with 4 and 10 iterations ("
       << cost(at("sliding-box", "distance", ne, 4, dt, 10)) << "); resting pyramid top box "
       << value(at("resting-pyramid", "drift", ne)) << " m from its start after 5 s |\n";
    const auto mm = [](const Row *r) { return r ? number(1000 * r->error, 3) + " mm" : std::string("n/a"); };
    const auto percent = [](const Row *r) { return r ? number(100 * r->error, 3) + " %" : std::string("n/a"); };
    md << "| things that land fast: drops, thrown objects, debris | speculative contacts on (the default) | deepest "
       << "penetration on landing (ball from 5 m, crate from 10 m, box onto a box from 6 m): "
       << mm(at("drops", "ball", ne)) << ", " << mm(at("drops", "crate", ne)) << ", " << mm(at("drops", "box-on-box", ne))
       << " (" << cost(at("drops", "ball", ne)) << "); switched off: " << mm(at("drops", "ball", noSpeculative)) << ", "
       << mm(at("drops", "crate", noSpeculative)) << ", " << mm(at("drops", "box-on-box", noSpeculative)) << " ("
       << cost(at("drops", "ball", noSpeculative)) << "), and still " << mm(at("drops", "ball", noSpeculative, 4, dt / 16))
       << ", " << mm(at("drops", "crate", noSpeculative, 4, dt / 16)) << ", "
       << mm(at("drops", "box-on-box", noSpeculative, 4, dt / 16)) << " at 1/960 s ("
       << cost(at("drops", "ball", noSpeculative, 4, dt / 16)) << ") |\n";
    md << "| chains, ropes, pendulums (joints) | the defaults (4 sub-steps) | largest joint gap over 10 s: hanging "
       << "20-link chain " << value(at("chain-20", "gap", ne)) << " m, with a 100 kg ball "
       << value(at("chain-20-heavy", "gap", ne)) << " m, that heavy chain swinging from horizontal "
       << value(at("chain-20-heavy-swing", "gap", ne)) << " m (" << cost(at("chain-20-heavy-swing", "gap", ne))
       << "; 1 sub-step: " << value(at("chain-20-heavy-swing", "gap", ne, 1)) << " m, "
       << cost(at("chain-20-heavy-swing", "gap", ne, 1)) << "); pendulum (1 m, 10 degrees) period "
       << percent(at("pendulum", "period", ne)) << " off the exact one, energy within "
       << percent(at("pendulum", "energy", ne)) << " over 10 s (1 sub-step: " << percent(at("pendulum", "period", ne, 1))
       << " and " << percent(at("pendulum", "energy", ne, 1)) << ") |\n";
    md << "| balls that must roll to a stop where they should (rolling friction) | the defaults | "
       << "deceleration against the closed form: " << percent(at("rolling-resistance", "deceleration", ne))
       << " off at 1/60 s with 4 sub-steps (10 iterations: "
       << percent(at("rolling-resistance", "deceleration", ne, 4, dt, 10)) << "), "
       << percent(at("rolling-resistance", "deceleration", ne, 1)) << " with 1; at 1/120 s "
       << percent(at("rolling-resistance", "deceleration", ne, 4, dt / 2)) << " with 4 sub-steps, "
       << percent(at("rolling-resistance", "deceleration", ne, 1, dt / 2)) << " with 1 (docs/solver.md, Rolling and "
       << "spinning resistance) |\n";
    md << "| asymmetric bodies spinning freely (tools, debris, satellites, the Dzhanibekov effect) | `" << mc << "` | "
       << "Dzhanibekov box over 10 s: angular momentum drift " << value(at("dzhanibekov", "momentum", mc))
       << " and energy drift " << value(at("dzhanibekov", "energy", mc)) << " (`" << gyro << "`: "
       << value(at("dzhanibekov", "momentum", gyro)) << " and " << value(at("dzhanibekov", "energy", gyro))
       << "); attitude error " << value(at("dzhanibekov", "attitude", mc)) << " rad, "
       << value(at("dzhanibekov", "attitude", mc, 4, dt / 2)) << " at 1/120 s (second order; `" << gyro << "`: "
       << value(at("dzhanibekov", "attitude", gyro)) << ", `" << ne << "`: "
       << value(at("dzhanibekov", "attitude", ne)) << "); cost " << cost(at("dzhanibekov", "attitude", mc))
       << " against " << cost(at("dzhanibekov", "attitude", gyro)) << " and " << cost(at("dzhanibekov", "attitude", ne))
       << " |\n";
    md << "| stiff springs, with the defaults | nothing to do | a spring beyond omega h = 0.8 gets the backward-Euler "
       << "force by itself: at omega dt = 10 the largest E / E0 is " << value(at("stiff-spring", "energy", ne, 4, 1.0 / 15))
       << " (explicit: " << value(at("stiff-spring", "energy", explicitSprings, 4, 1.0 / 15))
       << "); springs below it are untouched: at omega dt = 0.31 the energy kept after 2 s is "
       << value(at("stiff-spring", "kept", ne, 4, 1.0 / 480)) << ", as with explicit springs ("
       << value(at("stiff-spring", "kept", explicitSprings, 4, 1.0 / 480)) << ") |\n";
    md << "| springs that must hold still rather than ring | `" << implicit << "` | every spring backward Euler: "
       << "never gains energy, and damps: at omega dt = 2.5 it keeps " << value(at("stiff-spring", "kept", implicit))
       << " of its energy after 2 s |\n";
    md << "| an undamped oscillation that must keep its amplitude | explicit springs (`SpringSettings::force = "
       << "Explicit`) and sub-steps enough for omega h well below 2 | symplectic Euler keeps a modified energy: "
       << "largest E / E0 " << value(at("stiff-spring", "energy", explicitSprings, 4, 1.0 / 480))
       << " at omega dt = 0.31 |\n";
    md << "\nWhy `" << mc << "` uses the implicit midpoint rule rather than a splitting into rotations about the "
       << "body axes (`" << split << "` in the tables, run on its own, without a World around it): the "
       << "splitting keeps the energy only to O(h^2), a drift of " << value(at("dzhanibekov", "energy", split))
       << " on the Dzhanibekov box (" << mc << ": " << value(at("dzhanibekov", "energy", mc))
       << "). At the same step its attitude error is "
       << value(at("dzhanibekov", "attitude", split)) << " rad there (" << mc << ": "
       << value(at("dzhanibekov", "attitude", mc)) << ") and " << value(at("tumbling-box", "attitude", split))
       << " rad on the tumbling box (" << value(at("tumbling-box", "attitude", mc)) << "). It is cheaper: "
       << cost(at("dzhanibekov", "energy", split)) << " per simulated second alone, where " << mc
       << " costs " << cost(at("dzhanibekov", "energy", mc)) << " in the World against "
       << cost(at("dzhanibekov", "energy", ne)) << " for the seed's step.\n";
}

}  // namespace cyclone::accuracy
