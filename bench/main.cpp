// cyclone-bench: runs the benchmark scenes through cyclone's World and through Bullet 3
// and prints a Markdown table (optionally CSV) of step times, memory, drift and
// penetration, with the ratio ours/Bullet per scene.
//
// Each (scene, engine) run happens in a forked child so that runs do not share a heap:
// the peak-RSS figure then belongs to that run alone, and an engine that crashes on one
// scene is reported instead of ending the benchmark. --in-process runs them in this
// process (for perf, callgrind or heaptrack).
#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

#include "alloc_counter.h"
#include "engine.h"
#include "scenes.h"
#include "statistics.h"

namespace cyclone::bench {
namespace {

constexpr real kStep = 1.0 / 60.0;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// Sub-steps over which cyclone's World spreads the velocity passes of a frame by default.
constexpr int kDefaultSubsteps = 1;

// Plain data so that a child can send it through a pipe as bytes.
struct RunResult {
    int bodies = 0;
    int steps = 0;
    double medianMs = kNaN;
    double p95Ms = kNaN;
    double p99Ms = kNaN;
    double meanMs = kNaN;
    double maxMs = kNaN;
    int contactsLast = 0;
    long long contactsTotal = 0;  // contact points summed over all steps
    double usPerContact = kNaN;   // total step time / contactsTotal
    long long peakHeapBytes = -1;
    long long peakRssBytes = -1;  // -1: the kernel refused to reset the peak
    long long stateBytes = -1;    // heap held by the engine after the last step (counted)
    double allocsPerStep = kNaN;  // over the second half of the run
    double driftM = kNaN;         // NaN: the scene tracks no body
    double penetrationM = kNaN;
    bool repeatsDiffer = false;  // a repeat ended with other contacts, drift or penetration
    bool ok = false;
    char error[512] = {};
};

struct Options {
    std::vector<std::string> scenes;
    std::vector<std::string> engines;
    int steps = 600;
    int repeats = 1;
    int substeps = kDefaultSubsteps;
    bool worldDefaults = false;  // --defaults: cyclone at WorldSettings' sub-steps and passes
    int threads = 1;
    int seed = 0;
    std::string csv;
    bool inProcess = false;
};

std::vector<std::string> availableEngines() {
    std::vector<std::string> engines{"cyclone"};
#ifdef CYCLONE_BENCH_HAVE_BULLET
    engines.push_back("bullet");
#endif
    return engines;
}

std::unique_ptr<Engine> makeEngine(const std::string &name, const Scene &scene) {
    if (name == "cyclone") return makeCycloneEngine(scene);
#ifdef CYCLONE_BENCH_HAVE_BULLET
    if (name == "bullet") return makeBulletEngine(scene);
#endif
    throw std::invalid_argument("makeEngine: engine \"" + name + "\" is not built in");
}

// A field of /proc/self/status in bytes ("VmRSS", "VmHWM"), or -1.
long long procStatusBytes(const char *field) {
    std::ifstream status("/proc/self/status");
    std::string line;
    const std::string prefix = std::string(field) + ":";
    while (std::getline(status, line)) {
        if (line.compare(0, prefix.size(), prefix) == 0) return std::atoll(line.c_str() + prefix.size()) * 1024;
    }
    return -1;
}

// Writing 5 to clear_refs sets the peak RSS (VmHWM) back to the current RSS.
bool resetPeakRss() {
    const int fd = open("/proc/self/clear_refs", O_WRONLY);
    if (fd < 0) return false;
    const bool ok = write(fd, "5", 1) == 1;
    close(fd);
    return ok;
}

struct Run {
    RunResult result;
    std::vector<double> times;  // ms per step
};

// Runs the scene and records what the run measures directly; the statistics of the
// step times are left to summarise(), once the repeats are combined.
Run runHere(const Scene &scene, const std::string &engineName, int steps) {
    Run run;
    RunResult &result = run.result;
    result.bodies = static_cast<int>(scene.bodies.size());
    result.steps = steps;
    run.times.reserve(static_cast<std::size_t>(steps));
    try {
        const bool rssReset = resetPeakRss();
        const long long rssBefore = procStatusBytes("VmRSS");
        resetAllocPeak();
        const long long heapBefore = allocCounters().liveBytes;

        std::unique_ptr<Engine> engine = makeEngine(engineName, scene);
        const Vector3 start = scene.tracked >= 0 ? engine->position(scene.tracked) : Vector3::Zero();
        long long allocsAtHalf = 0;
        for (int i = 0; i < steps; ++i) {
            if (i == steps / 2) allocsAtHalf = allocCounters().allocations;
            const auto t0 = std::chrono::steady_clock::now();
            engine->step(kStep);
            const auto t1 = std::chrono::steady_clock::now();
            run.times.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
            result.contactsTotal += engine->contacts();
        }
        const long long allocsAtEnd = allocCounters().allocations;

        result.contactsLast = engine->contacts();
        result.allocsPerStep =
            static_cast<double>(allocsAtEnd - allocsAtHalf) / static_cast<double>(steps - steps / 2);
        if (scene.tracked >= 0) result.driftM = (engine->position(scene.tracked) - start).norm();
        result.penetrationM = engine->deepestPenetration();
        result.peakHeapBytes = allocCounters().peakBytes - heapBefore;
        result.stateBytes = allocCounters().liveBytes - heapBefore;
        if (rssReset) result.peakRssBytes = procStatusBytes("VmHWM") - rssBefore;
        result.ok = true;
    } catch (const std::exception &e) {
        std::snprintf(result.error, sizeof result.error, "%s", e.what());
    }
    return run;
}

bool writeAll(int fd, const void *data, std::size_t size) {
    const char *bytes = static_cast<const char *>(data);
    while (size > 0) {
        const ssize_t n = write(fd, bytes, size);
        if (n <= 0) return false;
        bytes += n;
        size -= static_cast<std::size_t>(n);
    }
    return true;
}

bool readAll(int fd, void *data, std::size_t size) {
    char *bytes = static_cast<char *>(data);
    while (size > 0) {
        const ssize_t n = read(fd, bytes, size);
        if (n <= 0) return false;
        bytes += n;
        size -= static_cast<std::size_t>(n);
    }
    return true;
}

Run runIsolated(const Scene &scene, const std::string &engineName, int steps) {
    Run failed;
    failed.result.bodies = static_cast<int>(scene.bodies.size());
    failed.result.steps = steps;
    int fds[2];
    if (pipe(fds) != 0) {
        std::snprintf(failed.result.error, sizeof failed.result.error, "pipe failed: %s", std::strerror(errno));
        return failed;
    }
    std::fflush(nullptr);
    const pid_t pid = fork();
    if (pid < 0) {
        std::snprintf(failed.result.error, sizeof failed.result.error, "fork failed: %s", std::strerror(errno));
        close(fds[0]);
        close(fds[1]);
        return failed;
    }
    if (pid == 0) {
        close(fds[0]);
        const Run run = runHere(scene, engineName, steps);
        const bool sent = writeAll(fds[1], &run.result, sizeof run.result) &&
                          writeAll(fds[1], run.times.data(), run.times.size() * sizeof(double));
        _exit(sent ? 0 : 3);
    }
    close(fds[1]);
    Run run;
    bool received = readAll(fds[0], &run.result, sizeof run.result);
    if (received && run.result.ok) {
        run.times.resize(static_cast<std::size_t>(steps));
        received = readAll(fds[0], run.times.data(), run.times.size() * sizeof(double));
    }
    close(fds[0]);
    int status = 0;
    waitpid(pid, &status, 0);
    if (received) return run;
    if (WIFSIGNALED(status)) {
        std::snprintf(failed.result.error, sizeof failed.result.error, "crashed with signal %d (%s)",
                      WTERMSIG(status), strsignal(WTERMSIG(status)));
    } else {
        std::snprintf(failed.result.error, sizeof failed.result.error, "child exited with status %d and no result",
                      WIFEXITED(status) ? WEXITSTATUS(status) : -1);
    }
    return failed;
}

void summarise(RunResult &result, const std::vector<double> &times) {
    result.medianMs = median(times);
    result.p95Ms = percentile(times, 0.95);
    result.p99Ms = percentile(times, 0.99);
    double total = 0;
    for (double t : times) total += t;
    result.meanMs = total / static_cast<double>(times.size());
    result.maxMs = *std::max_element(times.begin(), times.end());
    // With less than a contact per step on average the figure is the cost of everything
    // else divided by a handful of contacts: not reported.
    if (result.contactsTotal >= static_cast<long long>(times.size()))
        result.usPerContact = total * 1000 / static_cast<double>(result.contactsTotal);
}

// Runs the scene `repeats` times through each engine, the engines taking turns so that
// a change in the load of the machine hits them alike. The scenes are deterministic,
// so step i does the same work in every repeat: the fastest time of each step is the
// one least disturbed by the rest of the machine. Memory, drift and penetration come
// from the first repeat; the others must agree with it. Returns one result per engine.
std::vector<RunResult> measure(const Scene &scene, const std::vector<std::string> &engines, const Options &options) {
    std::vector<Run> first(engines.size());
    std::vector<std::vector<double>> fastest(engines.size());
    std::vector<bool> failed(engines.size(), false);
    for (int r = 0; r < options.repeats; ++r) {
        for (std::size_t e = 0; e < engines.size(); ++e) {
            if (failed[e]) continue;
            std::cerr << "running " << scene.name << " / " << engines[e] << " (" << r + 1 << "/" << options.repeats
                      << ") ...\n";
            Run run = options.inProcess ? runHere(scene, engines[e], options.steps)
                                        : runIsolated(scene, engines[e], options.steps);
            if (r == 0 || !run.result.ok) {
                failed[e] = !run.result.ok;
                first[e] = run;
                fastest[e] = run.times;
                continue;
            }
            for (std::size_t i = 0; i < fastest[e].size(); ++i) fastest[e][i] = std::min(fastest[e][i], run.times[i]);
            const RunResult &a = first[e].result, &b = run.result;
            const bool same = a.contactsTotal == b.contactsTotal && a.penetrationM == b.penetrationM &&
                              (a.driftM == b.driftM || (std::isnan(a.driftM) && std::isnan(b.driftM)));
            if (!same) first[e].result.repeatsDiffer = true;
        }
    }
    std::vector<RunResult> results;
    for (std::size_t e = 0; e < engines.size(); ++e) {
        if (!failed[e]) summarise(first[e].result, fastest[e]);
        results.push_back(first[e].result);
    }
    return results;
}

// --- Output ------------------------------------------------------------------------------

std::string fixed(double value, int decimals) {
    if (std::isnan(value)) return "n/a";
    char text[64];
    std::snprintf(text, sizeof text, "%.*f", decimals, value);
    return text;
}

// Three decimals, or three significant digits below 0.1 ms (a sleeping scene steps in
// microseconds).
std::string milliseconds(double value) {
    if (std::isnan(value) || value >= 0.1) return fixed(value, 3);
    char text[64];
    std::snprintf(text, sizeof text, "%.3g", value);
    return text;
}

std::string mebibytes(long long bytes) { return bytes < 0 ? "n/a" : fixed(static_cast<double>(bytes) / 1048576.0, 2); }

std::string ratio(double ours, double theirs) {
    if (std::isnan(ours) || std::isnan(theirs) || ours < 0 || theirs < 0) return "n/a";
    if (theirs == 0) return ours == 0 ? "1" : "inf";
    return fixed(ours / theirs, 2);
}

double asDouble(long long bytes) { return bytes < 0 ? kNaN : static_cast<double>(bytes); }

struct Row {
    std::string scene;
    std::string engine;
    RunResult result;
};

void printTable(const std::vector<Row> &rows, const std::vector<std::string> &sceneOrder) {
    std::cout << "| scene | engine | bodies | median ms | p95 ms | p99 ms | slowest ms | contacts | µs/contact | peak heap MiB | "
                 "peak RSS Δ MiB | state B/body | allocs/step | top-box drift cm | deepest pen. mm |\n"
              << "|---|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|\n";
    for (const std::string &scene : sceneOrder) {
        const RunResult *ours = nullptr;
        const RunResult *bullet = nullptr;
        for (const Row &row : rows) {
            if (row.scene != scene) continue;
            const RunResult &r = row.result;
            if (!r.ok) {
                std::cout << "| " << scene << " | " << row.engine << " | " << r.bodies
                          << " | failed (see below) | | | | | | | | | | | |\n";
                continue;
            }
            (row.engine == "cyclone" ? ours : bullet) = &r;
            std::cout << "| " << scene << " | " << row.engine << " | " << r.bodies << " | " << milliseconds(r.medianMs)
                      << " | " << milliseconds(r.p95Ms) << " | " << milliseconds(r.p99Ms) << " | "
                      << milliseconds(r.maxMs) << " | " << r.contactsLast << " | " << fixed(r.usPerContact, 3)
                      << " | " << mebibytes(r.peakHeapBytes) << " | " << mebibytes(r.peakRssBytes) << " | "
                      << fixed(asDouble(r.stateBytes) / r.bodies, 0) << " | " << fixed(r.allocsPerStep, 2) << " | "
                      << fixed(r.driftM * 100, 2) << " | " << fixed(r.penetrationM * 1000, 2) << " |\n";
        }
        if (ours && bullet) {
            std::cout << "| " << scene << " | **ours/Bullet** | | **" << ratio(ours->medianMs, bullet->medianMs)
                      << "** | " << ratio(ours->p95Ms, bullet->p95Ms) << " | " << ratio(ours->p99Ms, bullet->p99Ms)
                      << " | " << ratio(ours->maxMs, bullet->maxMs) << " | "
                      << ratio(ours->contactsLast, bullet->contactsLast) << " | "
                      << ratio(ours->usPerContact, bullet->usPerContact) << " | "
                      << ratio(asDouble(ours->peakHeapBytes), asDouble(bullet->peakHeapBytes)) << " | "
                      << ratio(asDouble(ours->peakRssBytes), asDouble(bullet->peakRssBytes)) << " | "
                      << ratio(asDouble(ours->stateBytes), asDouble(bullet->stateBytes)) << " | | "
                      << ratio(ours->driftM, bullet->driftM) << " | "
                      << ratio(ours->penetrationM, bullet->penetrationM) << " |\n";
        }
    }
    for (const Row &row : rows) {
        if (row.result.ok && row.result.repeatsDiffer)
            std::cout << "\nNote: " << row.scene << " / " << row.engine
                      << " did not repeat exactly (contacts, drift or penetration differ between repeats).\n";
    }
    bool anyFailed = false;
    for (const Row &row : rows) {
        if (row.result.ok) continue;
        if (!anyFailed) std::cout << "\nFailed runs:\n";
        anyFailed = true;
        std::cout << "- " << row.scene << " / " << row.engine << ": " << row.result.error << "\n";
    }
}

// The target for the sleeping scene: its cost against the awake body alone.
void printSleepingRatio(const std::vector<Row> &rows) {
    for (const std::string &engine : {std::string("cyclone"), std::string("bullet")}) {
        const RunResult *sleeping = nullptr;
        const RunResult *alone = nullptr;
        for (const Row &row : rows) {
            if (row.engine != engine || !row.result.ok) continue;
            if (row.scene == "sleeping1000") sleeping = &row.result;
            if (row.scene == "sphere_alone") alone = &row.result;
        }
        if (sleeping && alone) {
            std::cout << "- " << engine << ": sleeping1000 / sphere_alone median step = "
                      << ratio(sleeping->medianMs, alone->medianMs) << "\n";
        }
    }
}

void writeCsv(std::ofstream &out, const std::vector<Row> &rows) {
    out << "scene,engine,bodies,steps,median_ms,p95_ms,p99_ms,mean_ms,max_ms,contacts_last,us_per_contact,"
           "peak_heap_bytes,peak_rss_bytes,state_bytes,allocs_per_step,drift_m,penetration_m,error\n";
    char line[1024];
    for (const Row &row : rows) {
        const RunResult &r = row.result;
        std::string error = r.error;
        std::replace(error.begin(), error.end(), '"', '\'');
        std::snprintf(line, sizeof line, "%s,%s,%d,%d,%.6f,%.6f,%.6f,%.6f,%.6f,%d,%.6f,%lld,%lld,%lld,%.3f,%.9f,%.9f,\"%s\"\n",
                      row.scene.c_str(), row.engine.c_str(), r.bodies, r.steps, r.medianMs, r.p95Ms, r.p99Ms, r.meanMs,
                      r.maxMs, r.contactsLast, r.usPerContact, r.peakHeapBytes, r.peakRssBytes, r.stateBytes,
                      r.allocsPerStep, r.driftM, r.penetrationM, error.c_str());
        out << line;
    }
}

// --- Command line ------------------------------------------------------------------------

void printUsage(std::ostream &out) {
    out << "usage: cyclone-bench [--scene NAME]... [--steps N] [--repeat R] [--substeps S] [--defaults]\n"
           "                     [--threads T] [--seed N] [--engine cyclone|bullet|both] [--csv FILE] [--in-process] [--list]\n"
           "  --scene NAME   run only this scene (repeatable, or comma-separated); default: all\n"
           "  --steps N      steps of 1/60 s per run, N >= 1; default 600 (10 s)\n"
           "  --repeat R     run each scene and engine R times and keep each step's fastest time\n"
           "                 (the scenes are deterministic); default 1\n"
           "  --substeps S   spread cyclone's velocity passes per frame over S sub-steps (S divides\n"
           "                 them; Bullet always takes one step); default "
        << kDefaultSubsteps << "\n"
        << "  --defaults     cyclone at WorldSettings' default sub-steps and velocity passes (4 x 3)\n"
           "                 instead of the scene's 1 x 10; Bullet keeps its 10 iterations\n"
           "  --threads T    threads of cyclone's step, 1 to 64 (WorldSettings::threads; Bullet\n"
           "                 always uses one); default 1\n"
           "  --seed N       mixed1000's shapes, sizes and orientations from seed N, to see how far\n"
           "                 its results spread (the pile is chaotic); default 0, the tables' scene\n"
           "  --engine E     cyclone, bullet or both; default: every engine built in\n"
           "  --csv FILE     also write the results as CSV to FILE\n"
           "  --in-process   run everything in this process (for profilers; peak RSS then\n"
           "                 includes earlier runs' heap)\n"
           "  --list         print the scenes and exit\n";
}

// Returns false after printing the reason when the command line is wrong.
bool parseOptions(int argc, char **argv, Options &options, bool &listOnly) {
    const std::vector<std::string> known = sceneNames();
    const std::vector<std::string> built = availableEngines();
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        auto value = [&](const char *name) -> const char * {
            if (i + 1 >= argc) {
                std::cerr << "cyclone-bench: " << name << " needs a value\n";
                return nullptr;
            }
            return argv[++i];
        };
        // An integer option in [low, high].
        auto intValue = [&](const char *name, long low, long high, int &out) {
            const char *v = value(name);
            if (!v) return false;
            char *end = nullptr;
            const long parsed = std::strtol(v, &end, 10);
            if (*v == '\0' || *end != '\0' || parsed < low || parsed > high) {
                std::cerr << "cyclone-bench: " << name << " must be an integer in [" << low << ", " << high
                          << "], got \"" << v << "\"\n";
                return false;
            }
            out = static_cast<int>(parsed);
            return true;
        };
        if (arg == "--help" || arg == "-h") {
            printUsage(std::cout);
            std::exit(0);
        } else if (arg == "--list") {
            listOnly = true;
        } else if (arg == "--in-process") {
            options.inProcess = true;
        } else if (arg == "--scene") {
            const char *v = value("--scene");
            if (!v) return false;
            for (const std::string &name : splitSceneList(v)) {
                if (name != "all" && std::find(known.begin(), known.end(), name) == known.end()) {
                    std::cerr << "cyclone-bench: --scene \"" << name << "\" is not a scene; --list shows them\n";
                    return false;
                }
                if (name == "all") {
                    options.scenes.insert(options.scenes.end(), known.begin(), known.end());
                } else {
                    options.scenes.push_back(name);
                }
            }
        } else if (arg == "--steps") {
            if (!intValue("--steps", 1, 10000000, options.steps)) return false;
        } else if (arg == "--repeat") {
            if (!intValue("--repeat", 1, 100, options.repeats)) return false;
        } else if (arg == "--substeps") {
            const char *v = value("--substeps");
            if (!v) return false;
            char *end = nullptr;
            const long substeps = std::strtol(v, &end, 10);
            if (*v == '\0' || *end != '\0' || substeps < 1 || kVelocityPassesPerFrame % substeps != 0) {
                std::cerr << "cyclone-bench: --substeps must divide " << kVelocityPassesPerFrame << ", got \"" << v
                          << "\"\n";
                return false;
            }
            options.substeps = static_cast<int>(substeps);
        } else if (arg == "--defaults") {
            options.worldDefaults = true;
        } else if (arg == "--threads") {
            if (!intValue("--threads", 1, 64, options.threads)) return false;
        } else if (arg == "--seed") {
            if (!intValue("--seed", 0, 1000000000, options.seed)) return false;
        } else if (arg == "--engine") {
            const char *v = value("--engine");
            if (!v) return false;
            const std::string engine = v;
            if (engine == "both") {
                options.engines = {"cyclone", "bullet"};
            } else if (engine == "cyclone" || engine == "bullet") {
                options.engines = {engine};
            } else {
                std::cerr << "cyclone-bench: --engine must be cyclone, bullet or both, got \"" << engine << "\"\n";
                return false;
            }
        } else if (arg == "--csv") {
            const char *v = value("--csv");
            if (!v) return false;
            options.csv = v;
        } else {
            std::cerr << "cyclone-bench: unknown argument \"" << arg << "\"\n";
            printUsage(std::cerr);
            return false;
        }
    }
    if (options.scenes.empty()) options.scenes = known;
    if (options.engines.empty()) options.engines = built;
    for (const std::string &engine : options.engines) {
        if (std::find(built.begin(), built.end(), engine) == built.end()) {
            std::cerr << "cyclone-bench: --engine " << engine
                      << " is not built in (install libbullet-dev and configure with -DCYCLONE_BENCH_BULLET=ON)\n";
            return false;
        }
    }
    return true;
}

int run(int argc, char **argv) {
    Options options;
    bool listOnly = false;
    if (!parseOptions(argc, argv, options, listOnly)) return 2;
    // Opened before the runs so that a bad path fails at once, not after minutes.
    std::ofstream csv;
    if (!options.csv.empty()) {
        csv.open(options.csv);
        if (!csv) {
            std::cerr << "cyclone-bench: --csv cannot open \"" << options.csv << "\" for writing\n";
            return 2;
        }
    }
    if (listOnly) {
        for (const std::string &name : sceneNames()) std::cout << name << ": " << makeScene(name).description << "\n";
        return 0;
    }

    std::cout << "# cyclone-bench\n\n"
              << "- step 1/60 s, " << options.steps << " steps (" << fixed(options.steps * kStep, 1)
              << " s simulated) per run; drift and penetration are read after the last step\n"
              << "- build: " << CYCLONE_BENCH_BUILD_TYPE << ", each run " << (options.inProcess ? "in this process" : "in its own forked process") << "\n"
              << "- times: wall clock of one World::step / stepSimulation"
              << (options.repeats > 1 ? ", fastest of " + std::to_string(options.repeats) +
                                            " repeats per step (engines taking turns)"
                                      : "")
              << "; µs/contact = total step time / contact points summed over all steps\n"
              << "- peak heap: counting allocator (global operator new/delete replaced in the harness, and Bullet's "
                 "btAlignedAllocSetCustom hook); memory that Eigen, libccd or qhull take with malloc directly is "
                 "not in it\n"
              << "- peak RSS Δ: VmHWM at the end minus VmRSS at the start of the run (after clear_refs), everything "
                 "included\n"
              << "- state B/body: heap the engine holds after the last step (counting allocator), per body\n"
              << "- allocs/step: allocation calls per step over the second half of the run (steady state)\n"
              << "- deepest pen.: cyclone StepStats::maxPenetration; Bullet -min btManifoldPoint::getDistance over "
                 "all manifolds of the last step\n"
              << "- both engines: " << kVelocityPassesPerFrame
              << " contact-solver velocity passes per frame, friction 0.6, restitution 0 unless a scene says "
                 "otherwise\n"
              << "- cyclone: WorldSettings defaults except sleep, "
              << (options.worldDefaults ? WorldSettings().substeps : options.substeps) << " sub-step(s) x "
              << (options.worldDefaults ? WorldSettings().velocityIterations
                                        : kVelocityPassesPerFrame / options.substeps)
              << " velocity iterations, "
              << WorldSettings().positionIterations << " position iterations per sub-step, " << options.threads
              << " thread(s)\n";
    if (options.seed != 0) std::cout << "- mixed1000 from seed " << options.seed << " (--seed), not the tables' scene\n";
#ifdef CYCLONE_BENCH_HAVE_BULLET
    if (std::find(options.engines.begin(), options.engines.end(), "bullet") != options.engines.end())
        std::cout << bulletSettingsNote();
#endif
    std::cout << "\nScenes:\n";
    for (const std::string &name : options.scenes) std::cout << "- " << name << ": " << makeScene(name).description << "\n";
    std::cout << "\n";

    std::vector<Row> rows;
    for (const std::string &sceneName : options.scenes) {
        Scene scene = makeScene(sceneName, static_cast<std::uint64_t>(options.seed));
        if (options.worldDefaults)
            useWorldDefaults(scene.world);
        else
            splitSubsteps(scene, options.substeps);
        scene.world.threads = options.threads;
        const std::vector<RunResult> results = measure(scene, options.engines, options);
        for (std::size_t e = 0; e < results.size(); ++e) rows.push_back(Row{sceneName, options.engines[e], results[e]});
    }
    printTable(rows, options.scenes);
    std::cout << "\n";
    printSleepingRatio(rows);
    if (csv.is_open()) writeCsv(csv, rows);
    return 0;
}

}  // namespace
}  // namespace cyclone::bench

int main(int argc, char **argv) {
    try {
        return cyclone::bench::run(argc, argv);
    } catch (const std::exception &e) {
        std::cerr << "cyclone-bench: " << e.what() << "\n";
        return 1;
    }
}
