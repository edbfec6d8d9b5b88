#include "atomic_file.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace cyclone::scene {

namespace {

std::string reason() { return errno ? std::strerror(errno) : "write error"; }

}  // namespace

AtomicFile::AtomicFile(std::string path)
    : path_(std::move(path)), temporary_(path_ + ".tmp-" + std::to_string(::getpid())) {
    struct stat info {};
    direct_ = ::stat(path_.c_str(), &info) == 0 && !S_ISREG(info.st_mode);
    errno = 0;
    out_.open(direct_ ? path_ : temporary_, std::ios::binary | std::ios::trunc);
    if (!out_) throw std::runtime_error("cannot write " + path_ + ": " + reason());
}

AtomicFile::~AtomicFile() {
    if (!committed_ && !direct_) {
        out_.close();
        std::remove(temporary_.c_str());
    }
}

void AtomicFile::close() {
    if (!closed_) {
        closed_ = true;
        errno = 0;
        out_.flush();
        const bool written = static_cast<bool>(out_);
        out_.close();
        if (!written || !out_) closeError_ = "cannot write " + path_ + ": " + reason();
    }
    if (!closeError_.empty()) throw std::runtime_error(closeError_);
}

void AtomicFile::commit() {
    close();
    if (direct_) {
        committed_ = true;
        return;
    }
    if (std::rename(temporary_.c_str(), path_.c_str()) != 0) {
        throw std::runtime_error("cannot write " + path_ + ": " + reason());
    }
    committed_ = true;
}

}  // namespace cyclone::scene
