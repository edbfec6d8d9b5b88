// Helpers of the runner tests: temporary folders, files, and running the real
// cyclone-world executable with its exit status, stdout and stderr.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#ifndef CYCLONE_WORLD_EXE
#error "runner tests need CYCLONE_WORLD_EXE (set by runner/CMakeLists.txt)"
#endif
#ifndef CYCLONE_SCENES_DIR
#error "runner tests need CYCLONE_SCENES_DIR (set by runner/CMakeLists.txt)"
#endif

namespace runner_test {

namespace fs = std::filesystem;

/// A fresh folder, removed with everything in it at the end of the test.
class TempDir {
public:
    TempDir() {
        static int counter = 0;
        path_ = fs::temp_directory_path() /
                ("cyclone-runner-test-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
        fs::remove_all(path_);
        fs::create_directories(path_);
    }
    ~TempDir() {
        std::error_code ignored;
        fs::remove_all(path_, ignored);
    }
    TempDir(const TempDir &) = delete;
    TempDir &operator=(const TempDir &) = delete;
    std::string file(const std::string &name) const { return (path_ / name).string(); }
    /// Names of the files in the folder.
    std::vector<std::string> files() const {
        std::vector<std::string> names;
        for (const auto &entry : fs::directory_iterator(path_)) names.push_back(entry.path().filename().string());
        return names;
    }

private:
    fs::path path_;
};

inline std::string readText(const std::string &path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

inline void writeText(const std::string &path, const std::string &text) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out << text;
}

inline std::string scenePath(const std::string &name) { return std::string(CYCLONE_SCENES_DIR) + "/" + name + ".json"; }

struct Process {
    /// Exit status; 128 + signal number when killed by a signal; -1 if it could not start.
    int status = -1;
    std::string out;
    std::string err;
};

/// Runs cyclone-world with `args`, stdout and stderr captured through files in `dir`.
inline Process runWorld(const std::vector<std::string> &args, const TempDir &dir) {
    const std::string outPath = dir.file(".stdout"), errPath = dir.file(".stderr");
    Process result;
    const pid_t pid = ::fork();
    if (pid < 0) return result;
    if (pid == 0) {
        std::vector<char *> argv;
        std::string exe = CYCLONE_WORLD_EXE;
        argv.push_back(exe.data());
        std::vector<std::string> copy = args;
        for (auto &arg : copy) argv.push_back(arg.data());
        argv.push_back(nullptr);
        if (!std::freopen(outPath.c_str(), "w", stdout) || !std::freopen(errPath.c_str(), "w", stderr)) ::_exit(127);
        ::execv(exe.c_str(), argv.data());
        ::_exit(127);
    }
    int status = 0;
    ::waitpid(pid, &status, 0);
    result.status = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    result.out = readText(outPath);
    result.err = readText(errPath);
    std::error_code ignored;
    fs::remove(outPath, ignored);
    fs::remove(errPath, ignored);
    return result;
}

/// Number of lines of `text` (a last line without '\n' counts).
inline int lineCount(const std::string &text) {
    int lines = 0;
    for (char c : text) lines += c == '\n';
    return lines + (!text.empty() && text.back() != '\n');
}

}  // namespace runner_test
