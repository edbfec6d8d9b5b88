#include "cli.h"

#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <memory>
#include <new>
#include <sstream>
#include <utility>
#include <vector>

#include "atomic_file.h"
#include "report.h"
#include "run_loop.h"
#include "saved_run.h"
#include "scene_writer.h"
#include "scene_fields.h"
#include "scene_file.h"
#include "scene_loader.h"
#include "scene_world.h"
#include "summary.h"

#ifndef CYCLONE_VERSION
#define CYCLONE_VERSION "unknown"
#endif

namespace cyclone::scene {

namespace fs = std::filesystem;

const char *const kHelpText =
    "cyclone-world: run a cyclone scene file (JSON) and tell what happened.\n"
    "\n"
    "Usage:\n"
    "  cyclone-world run SCENE.json [options]     step the scene; print a one-line result\n"
    "  cyclone-world report SCENE.json [options]  step the scene; print a short report: bodies,\n"
    "                                             steps, ms per step (median/mean/max), when\n"
    "                                             everything fell asleep, drift of the highest\n"
    "                                             dynamic body, deepest penetration\n"
    "  cyclone-world help | --help | -h           this text\n"
    "  cyclone-world --version                    the version\n"
    "\n"
    "Options of run and report (also as --option=VALUE):\n"
    "  --steps N           steps to take, 0..100000000; overrides settings.steps (default 600)\n"
    "  --dt S              fixed step in seconds, in [1e-06, 1]; overrides settings.dt\n"
    "                      (default 1/60)\n"
    "  --summary OUT.json  write the run's summary (JSON): scene, steps, dt, wall_seconds,\n"
    "                      step_ms, metrics, the final state of every body\n"
    "  --trace OUT.csv     write a per-step trace (CSV), one row per dynamic body:\n"
    "                      step,time,body,px,py,pz,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz,awake\n"
    "  --every K           trace only every K-th step (steps K-1, 2K-1, ... counted from 0)\n"
    "                      and the last step; K >= 1, default 1\n"
    "  --save-state FILE   write the world's state after the last step (binary), to resume\n"
    "                      the run from with --load-state\n"
    "  --load-state FILE   resume a run of this scene saved by --save-state: its steps,\n"
    "                      events and trace rows are numbered on from the saved run's\n"
    "  --save-scene FILE   write a scene file of the world after the last step (poses,\n"
    "                      velocities, sleep, joints as they are; the events still to come)\n"
    "  --quiet             no result line on stdout (run) and no progress on stderr\n"
    "  --strict            refuse (exit 2) a scene with a field the format does not have,\n"
    "                      instead of warning about it (one line each on stderr, e.g.\n"
    "                      bodies[0].positon: unknown field; did you mean \"position\"?)\n"
    "\n"
    "A scene holds settings, bodies, springs and events: docs/scene-format.md is the\n"
    "contract. Events of step k act at the start of step k. Beyond the contract's checks,\n"
    "coordinates and sizes must lie within 1e12 m, iterations and sub-steps within 1000,\n"
    "and the JSON may nest at most 64 levels. Output files are written whole or not at\n"
    "all. Progress goes to stderr only when stderr is a terminal.\n"
    "\n"
    "Exit status:\n"
    "  0  the run completed\n"
    "  2  bad command line, or a scene that cannot be run: one line on stderr,\n"
    "     FILE: PATH: message (e.g. tower.json: bodies[3].mass: must be finite and > 0,\n"
    "     got -1), and no output file written\n"
    "  3  a body's state became NaN or infinite, or one more step would carry a body\n"
    "     beyond 1e12 m: the run stops, stderr says where, and the summary (and trace)\n"
    "     are written with \"non_finite\": true\n";

namespace {

constexpr std::int64_t kMaxEvery = kMaxSteps;

[[noreturn]] void usage(const std::string &problem) {
    throw UsageError("cyclone-world: " + oneLine(problem) + " (see cyclone-world --help)");
}

std::int64_t parseCount(const std::string &flag, const std::string &text, std::int64_t min, std::int64_t max) {
    const std::string range = std::to_string(min) + ".." + std::to_string(max);
    if (text.empty() || text.size() > 18 || text.find_first_not_of("0123456789") != std::string::npos) {
        usage(flag + " needs a whole number in " + range + ", got '" + text + "'");
    }
    const std::int64_t value = std::stoll(text);
    if (value < min || value > max) usage(flag + " needs a whole number in " + range + ", got " + text);
    return value;
}

double parseStep(const std::string &flag, const std::string &text) {
    char *end = nullptr;
    errno = 0;
    const double value = text.empty() ? 0 : std::strtod(text.c_str(), &end);
    if (text.empty() || *end != '\0' || !(value >= kMinStep && value <= kMaxStep)) {
        usage(flag + " needs a finite number of seconds in [1e-06, 1] (kMinStep, kMaxStep), got '" + text + "'");
    }
    return value;
}

std::string sceneStem(const std::string &path) {
    std::string stem = path.substr(path.find_last_of('/') == std::string::npos ? 0 : path.find_last_of('/') + 1);
    const std::string extension = ".json";
    if (stem.size() > extension.size() && stem.compare(stem.size() - extension.size(), extension.size(), extension) == 0) {
        stem.resize(stem.size() - extension.size());
    }
    return stem;
}

// Progress on one terminal line, at most a few times a second.
class Progress {
public:
    explicit Progress(std::ostream &err) : err_(err) {}
    ~Progress() {
        if (shown_) err_ << "\r\033[K" << std::flush;
    }
    void operator()(std::int64_t done, std::int64_t total) {
        const auto now = std::chrono::steady_clock::now();
        if (now - last_ < std::chrono::milliseconds(250)) return;
        last_ = now;
        shown_ = true;
        err_ << "\rcyclone-world: step " << done << "/" << total << " ("
             << (total ? 100 * done / total : 100) << "%)" << std::flush;
    }

private:
    std::ostream &err_;
    std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
    bool shown_ = false;
};

int refuse(std::ostream &err, const std::string &file, const std::string &place, const std::string &message) {
    err << oneLine(file) << ": " << oneLine(place) << ": " << oneLine(message) << "\n";
    return kExitRefused;
}

// Whether two paths name one file: the same real path once symbolic links, "." and ".."
// are resolved (weakly_canonical also resolves the existing part of a path to a file not
// yet there), or two hard links to one existing file.
bool sameFile(const std::string &a, const std::string &b) {
    std::error_code error;
    if (fs::equivalent(a, b, error) && !error) return true;
    std::error_code errorA, errorB;
    const fs::path realA = fs::weakly_canonical(fs::absolute(a, errorA), errorA);
    const fs::path realB = fs::weakly_canonical(fs::absolute(b, errorB), errorB);
    if (errorA || errorB) return a == b;
    return realA == realB;
}

// The output files a run asked for, written whole at its end; none opened: not asked.
struct Outputs {
    std::unique_ptr<AtomicFile> summary;
    std::unique_ptr<AtomicFile> trace;
    std::unique_ptr<AtomicFile> state;
    std::unique_ptr<AtomicFile> scene;
    std::unique_ptr<TraceWriter> traceRows;  ///< Writes into `trace`.
};

// Opens the outputs `invocation` names; throws std::exception when one cannot be.
Outputs openOutputs(const Invocation &invocation) {
    Outputs outputs;
    if (!invocation.summary.empty()) outputs.summary = std::make_unique<AtomicFile>(invocation.summary);
    if (!invocation.saveState.empty()) outputs.state = std::make_unique<AtomicFile>(invocation.saveState);
    if (!invocation.saveScene.empty()) outputs.scene = std::make_unique<AtomicFile>(invocation.saveScene);
    if (!invocation.trace.empty()) {
        outputs.trace = std::make_unique<AtomicFile>(invocation.trace);
        outputs.traceRows = std::make_unique<TraceWriter>(outputs.trace->stream());
    }
    return outputs;
}

// Writes the summary, the saved state and the saved scene after a run of `result` from
// `firstStep`, then renames every output into place; throws std::exception on a failure.
void writeOutputs(Outputs &outputs, const std::string &text, const Scene &scene, const SceneWorld &built,
                  const RunResult &result, std::int64_t firstStep) {
    if (outputs.summary) outputs.summary->stream() << summaryText(summaryJson(scene, built, result));
    if (outputs.state) {
        const std::vector<std::uint8_t> state = savedRunBytes(text, firstStep + result.steps, built.world);
        outputs.state->stream().write(reinterpret_cast<const char *>(state.data()), static_cast<std::streamsize>(state.size()));
    }
    if (outputs.scene) outputs.scene->stream() << sceneAsItIs(text, scene, built, firstStep + result.steps);
    // All closed whole before any is renamed: a failed write leaves none.
    const std::initializer_list<AtomicFile *> files = {outputs.summary.get(), outputs.trace.get(), outputs.state.get(),
                                                       outputs.scene.get()};
    for (AtomicFile *f : files)
        if (f) f->close();
    for (AtomicFile *f : files)
        if (f) f->commit();
}

// Tells how the run went: the report or the result line on `out`, the warnings and a
// non-finite end on `err`; returns the exit status.
int tellResult(const Invocation &invocation, const Scene &scene, const SceneWorld &built, const RunResult &result,
               std::ostream &out, std::ostream &err) {
    const std::string &file = invocation.scene;
    if (invocation.command == Invocation::Command::Report) {
        writeReport(out, file, scene, built, result);
    } else if (!invocation.quiet) {
        out << resultLine(scene, built, result) << "\n";
    }
    if (result.firstPairBudgetStep) {
        err << oneLine(file) << ": step " << *result.firstPairBudgetStep << ": warning: more bodies overlapped than "
            << built.world.settings().maxPairs << " pairs; the excess pairs were dropped (in "
            << result.pairBudgetSteps << " of " << result.steps << " steps), so some bodies passed through others\n";
    }
    if (result.nonFinite) {
        err << oneLine(file) << ": " << oneLine(result.nonFiniteWhat) << "; run stopped"
            << (invocation.summary.empty() ? "" : ", summary has \"non_finite\": true") << "\n";
        return kExitNonFinite;
    }
    return kExitOk;
}

int runLoaded(const std::string &text, const Invocation &invocation, std::ostream &out, std::ostream &err,
              bool progress) {
    const std::string &file = invocation.scene;
    std::unique_ptr<SceneFile> loaded;
    try {
        loaded = std::make_unique<SceneFile>(text, sceneStem(file), invocation.strict);
    } catch (const SceneError &error) {
        return refuse(err, file, error.path(), error.message());
    }
    Scene &scene = loaded->scene();
    std::unique_ptr<SceneWorld> built;
    try {
        if (invocation.steps) scene.steps = *invocation.steps;
        if (invocation.dt) scene.dt = *invocation.dt;
        built = std::make_unique<SceneWorld>(buildWorld(scene));
    } catch (const SceneError &error) {
        return refuse(err, file, loaded->place(error.path()), error.message());
    }
    std::int64_t firstStep = 0;
    if (!invocation.loadState.empty()) {
        try {
            firstStep = resumeSavedRun(readSavedRun(invocation.loadState), text, built->world);
        } catch (const SavedRunError &error) {
            return refuse(err, invocation.loadState, "state", error.what());
        }
    }
    Outputs outputs;
    try {
        outputs = openOutputs(invocation);
    } catch (const std::exception &error) {
        err << "cyclone-world: " << oneLine(error.what()) << "\n";
        return kExitRefused;
    }
    // Told once the scene is sure to run, so that a refusal stays one line.
    loaded->writeWarnings(err, file);

    RunOptions options;
    options.steps = scene.steps;
    options.firstStep = firstStep;
    options.dt = scene.dt;
    options.traceEvery = invocation.every;
    options.trace = outputs.traceRows.get();
    std::unique_ptr<Progress> meter;
    if (progress && !invocation.quiet) {
        meter = std::make_unique<Progress>(err);
        options.progress = [&meter](std::int64_t done, std::int64_t total) { (*meter)(done, total); };
    }
    RunResult result;
    try {
        result = runScene(scene, *built, options);
    } catch (const SceneError &error) {
        meter.reset();
        return refuse(err, file, loaded->place(error.path()), error.message());
    } catch (const std::exception &error) {
        meter.reset();
        return refuse(err, file, "run", error.what());
    }
    meter.reset();
    try {
        writeOutputs(outputs, text, scene, *built, result, firstStep);
    } catch (const std::exception &error) {
        err << "cyclone-world: " << oneLine(error.what()) << "\n";
        return kExitRefused;
    }
    return tellResult(invocation, scene, *built, result, out, err);
}

// The command that `name` (the first argument) names.
Invocation::Command commandNamed(const std::string &name) {
    if (name == "help" || name == "--help" || name == "-h") return Invocation::Command::Help;
    if (name == "--version") return Invocation::Command::Version;
    if (name == "run") return Invocation::Command::Run;
    if (name == "report") return Invocation::Command::Report;
    usage("unknown command '" + name + "'; commands: run, report, help");
}

// Whether option `flag`, given without "=VALUE", takes the next argument as its value.
bool takesValue(const std::string &flag) {
    return flag == "--steps" || flag == "--dt" || flag == "--summary" || flag == "--trace" || flag == "--every" ||
           flag == "--save-state" || flag == "--load-state" || flag == "--save-scene";
}

// The options with a value that were given already (those naming a file are told by it).
struct SeenOptions {
    bool steps = false;
    bool dt = false;
    bool every = false;
};

// Sets option `flag` of `invocation` to `value`; refuses (UsageError) an unknown option,
// a bad value, or an option given twice.
void setOption(Invocation &invocation, const std::string &flag, const std::string &value, SeenOptions &seen) {
    const auto once = [&](bool &given) {
        if (given) usage(flag + " given twice");
        given = true;
    };
    bool seenSummary = !invocation.summary.empty(), seenTrace = !invocation.trace.empty();
    bool seenSave = !invocation.saveState.empty(), seenLoad = !invocation.loadState.empty();
    bool seenScene = !invocation.saveScene.empty();
    if (flag == "--steps") {
        once(seen.steps);
        invocation.steps = parseCount(flag, value, 0, kMaxSteps);
    } else if (flag == "--dt") {
        once(seen.dt);
        invocation.dt = parseStep(flag, value);
    } else if (flag == "--every") {
        once(seen.every);
        invocation.every = parseCount(flag, value, 1, kMaxEvery);
    } else if (flag == "--summary" || flag == "--trace") {
        once(flag == "--summary" ? seenSummary : seenTrace);
        if (value.empty()) usage(flag + " needs a file name");
        (flag == "--summary" ? invocation.summary : invocation.trace) = value;
    } else if (flag == "--save-scene") {
        once(seenScene);
        if (value.empty()) usage(flag + " needs a file name");
        invocation.saveScene = value;
    } else if (flag == "--save-state" || flag == "--load-state") {
        const bool save = flag == "--save-state";
        once(save ? seenSave : seenLoad);
        if (value.empty()) usage(flag + " needs a file name");
        (save ? invocation.saveState : invocation.loadState) = value;
    } else {
        usage("unknown option '" + flag + "'");
    }
}

}  // namespace

Invocation parseCommandLine(const std::vector<std::string> &args) {
    Invocation invocation;
    if (args.empty()) usage("missing command: run, report or help");
    const std::string &command = args[0];
    invocation.command = commandNamed(command);
    if (invocation.command == Invocation::Command::Help || invocation.command == Invocation::Command::Version)
        return invocation;
    SeenOptions seen;
    for (std::size_t i = 1; i < args.size(); ++i) {
        std::string arg = args[i];
        if (arg == "--help" || arg == "-h") {
            invocation.command = Invocation::Command::Help;
            return invocation;
        }
        if (arg.size() < 2 || arg.compare(0, 2, "--") != 0) {
            if (!invocation.scene.empty()) usage("one scene file only, got '" + invocation.scene + "' and '" + arg + "'");
            if (arg.empty()) usage("the scene file name is empty");
            invocation.scene = arg;
            continue;
        }
        if (arg == "--quiet" || arg == "--strict") {
            (arg == "--quiet" ? invocation.quiet : invocation.strict) = true;
            continue;
        }
        std::string value;
        const auto equals = arg.find('=');
        if (equals != std::string::npos) {
            value = arg.substr(equals + 1);
            arg.resize(equals);
        } else if (takesValue(arg)) {
            if (i + 1 >= args.size()) usage(arg + " needs a value");
            value = args[++i];
        }
        setOption(invocation, arg, value, seen);
    }
    if (invocation.scene.empty()) usage(command + " needs a scene file: cyclone-world " + command + " SCENE.json");
    if (!invocation.summary.empty() && invocation.summary == invocation.trace) {
        usage("--summary and --trace name the same file '" + invocation.summary + "'");
    }
    return invocation;
}

std::string readSceneFile(const std::string &path, std::uintmax_t maxBytes) {
    struct stat info {};
    if (::stat(path.c_str(), &info) != 0) throw std::runtime_error(std::string("cannot read: ") + std::strerror(errno));
    if (S_ISDIR(info.st_mode)) throw std::runtime_error("cannot read: is a directory");
    const std::string tooLarge = "cannot read: larger than " +
                                 (maxBytes == kMaxSceneBytes ? std::string("1 GiB") : std::to_string(maxBytes) + " bytes");
    if (S_ISREG(info.st_mode) && static_cast<std::uintmax_t>(info.st_size) > maxBytes) throw std::runtime_error(tooLarge);
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error(std::string("cannot read: ") + std::strerror(errno));
    // The read itself is bounded: a device or a pipe (/dev/zero, /dev/stdin) has no size
    // to check first. A NUL byte cannot be part of a JSON text, so reading stops after
    // the first one and the parser names the place where it sits.
    std::string text;
    std::vector<char> chunk(std::size_t{1} << 16);
    while (in) {
        in.read(chunk.data(), static_cast<std::streamsize>(chunk.size()));
        const auto got = static_cast<std::size_t>(in.gcount());
        const auto nul = std::find(chunk.begin(), chunk.begin() + static_cast<std::ptrdiff_t>(got), '\0');
        const auto kept = static_cast<std::size_t>(nul - chunk.begin()) + (nul != chunk.begin() + static_cast<std::ptrdiff_t>(got));
        if (text.size() + kept > maxBytes) throw std::runtime_error(tooLarge);
        text.append(chunk.data(), kept);
        if (kept < got) break;
    }
    if (in.bad()) throw std::runtime_error("cannot read: read error");
    return text;
}

void checkOutputPaths(const Invocation &invocation) {
    const std::pair<const char *, const std::string *> outputs[] = {
        {"--summary", &invocation.summary}, {"--trace", &invocation.trace}, {"--save-state", &invocation.saveState},
        {"--save-scene", &invocation.saveScene}};
    for (const auto &[flag, path] : outputs) {
        if (path->empty()) continue;
        std::error_code error;
        if (fs::is_directory(*path, error)) usage(std::string(flag) + " " + *path + " is a directory");
        if (!invocation.scene.empty() && sameFile(*path, invocation.scene)) {
            usage(std::string(flag) + " " + *path + " is the scene file " + invocation.scene + "; it would be overwritten");
        }
    }
    if (!invocation.summary.empty() && !invocation.trace.empty() && sameFile(invocation.summary, invocation.trace)) {
        usage("--summary " + invocation.summary + " and --trace " + invocation.trace + " name the same file");
    }
}

int runSceneText(const std::string &text, const Invocation &invocation, std::ostream &out, std::ostream &err,
                 bool progress) {
    try {
        checkOutputPaths(invocation);
        return runLoaded(text, invocation, out, err, progress);
    } catch (const UsageError &error) {
        err << error.what() << "\n";
        return kExitRefused;
    } catch (const std::bad_alloc &) {
        return refuse(err, invocation.scene, "(top level)", "out of memory");
    } catch (const std::exception &error) {
        return refuse(err, invocation.scene, "(top level)", error.what());
    } catch (...) {
        return refuse(err, invocation.scene, "(top level)", "unexpected error");
    }
}

int runCommandLine(const std::vector<std::string> &args, std::ostream &out, std::ostream &err, bool progress) {
    Invocation invocation;
    try {
        invocation = parseCommandLine(args);
    } catch (const UsageError &error) {
        err << error.what() << "\n";
        return kExitRefused;
    }
    switch (invocation.command) {
    case Invocation::Command::Help: out << kHelpText; return kExitOk;
    case Invocation::Command::Version: out << "cyclone-world " << CYCLONE_VERSION << "\n"; return kExitOk;
    case Invocation::Command::Run:
    case Invocation::Command::Report: break;
    }
    std::string text;
    try {
        text = readSceneFile(invocation.scene);
    } catch (const std::exception &error) {
        err << oneLine(invocation.scene) << ": " << oneLine(error.what()) << "\n";
        return kExitRefused;
    }
    return runSceneText(text, invocation, out, err, progress);
}

}  // namespace cyclone::scene
