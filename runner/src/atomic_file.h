// Output files written whole or not at all: the text goes to PATH.tmp-<pid>, which is
// renamed to PATH only once it has been written and closed without error. A path that
// names something other than a regular file (a terminal, a pipe, /dev/stdout) cannot be
// replaced by a rename; it is written directly.
#pragma once

#include <fstream>
#include <string>

namespace cyclone::scene {

class AtomicFile {
public:
    /// Creates the temporary file next to `path`; throws std::runtime_error naming the
    /// path and the reason when it cannot.
    explicit AtomicFile(std::string path);
    /// Removes the temporary file unless commit() succeeded.
    ~AtomicFile();
    AtomicFile(const AtomicFile &) = delete;
    AtomicFile &operator=(const AtomicFile &) = delete;

    /// Where the content goes.
    std::ostream &stream() { return out_; }
    /// Flushes and closes the temporary file; throws std::runtime_error on any write or
    /// close error. Lets several files be checked whole before any of them is renamed.
    void close();
    /// Closes the temporary file (unless close() did) and renames it to the path; throws
    /// std::runtime_error (and removes it) on any write, close or rename error.
    void commit();
    /// The final path.
    const std::string &path() const { return path_; }

private:
    std::string path_;
    std::string temporary_;
    std::ofstream out_;
    bool direct_ = false;
    bool closed_ = false;
    std::string closeError_;
    bool committed_ = false;
};

}  // namespace cyclone::scene
