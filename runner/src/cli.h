// The cyclone-world command line: parsing, the help text, and the commands run and
// report, with the exit statuses of the scene-format contract.
#pragma once

#include <cstdint>
#include <optional>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

namespace cyclone::scene {

/// Exit statuses.
inline constexpr int kExitOk = 0;
/// Bad command line, or a scene that cannot be run; nothing was written.
inline constexpr int kExitRefused = 2;
/// A state became non-finite during the run; the summary says so.
inline constexpr int kExitNonFinite = 3;

/// A scene file larger than this is refused rather than read, bytes.
inline constexpr std::uintmax_t kMaxSceneBytes = std::uintmax_t{1} << 30;

/// The full --help text.
extern const char *const kHelpText;

/// A command line that cannot be obeyed; what() is the one line to print.
class UsageError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// What the command line asks for.
struct Invocation {
    enum class Command { Run, Report, Help, Version };
    Command command = Command::Help;
    /// The scene file, as given.
    std::string scene;
    /// Overrides of the scene's settings.steps and settings.dt.
    std::optional<std::int64_t> steps;
    std::optional<double> dt;
    /// Output paths; empty: not written.
    std::string summary;
    std::string trace;
    /// (v3) Where to write the run's state after its last step (--save-state), and the
    /// state to resume from (--load-state); empty: none.
    std::string saveState;
    std::string loadState;
    /// (v3) Where to write the scene of the world after the last step (--save-scene).
    std::string saveScene;
    /// Trace every K-th step, >= 1.
    std::int64_t every = 1;
    /// No result line on stdout, no progress on stderr.
    bool quiet = false;
    /// Refuse a scene with unknown fields (exit 2) instead of warning about them.
    bool strict = false;
};

/// Parses the arguments after the program name; throws UsageError.
Invocation parseCommandLine(const std::vector<std::string> &args);

/// Reads a scene file of at most `maxBytes` bytes, however it is given (a file, a device,
/// a pipe), up to and including its first NUL byte; throws std::runtime_error ("cannot
/// read: ...") with the reason.
std::string readSceneFile(const std::string &path, std::uintmax_t maxBytes = kMaxSceneBytes);

/// Refuses (UsageError) outputs that would destroy something: --summary and --trace naming
/// one file (compared as real paths), either naming the scene file or a directory.
void checkOutputPaths(const Invocation &invocation);

/// Runs the command line; returns the exit status. `progress` allows progress lines on
/// `err` (main passes whether stderr is a terminal).
int runCommandLine(const std::vector<std::string> &args, std::ostream &out, std::ostream &err, bool progress);

/// Runs a run or report invocation on scene text already read (`invocation.scene` names
/// it in messages); returns the exit status. Never throws.
int runSceneText(const std::string &text, const Invocation &invocation, std::ostream &out, std::ostream &err,
                 bool progress);

}  // namespace cyclone::scene
